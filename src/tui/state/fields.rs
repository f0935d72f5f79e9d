//! The editable properties of the selected item: their labels, current values, steps, and how
//! typed text becomes a value. Ranges and steps come from [`crate::scene::limits`], and every
//! change is checked with [`crate::scene::validate`] on a copy of the scene, so a refused value
//! changes nothing.

use std::path::PathBuf;

use glam::Vec3;

use super::selection::Item;
use crate::scene::limits::{self, CountLimits, Limits};
use crate::scene::{Camera, Light, MaterialSource, Object, Scene, Shape, UpAxis, validate};
use crate::tui::text::clean;

/// One component of a vector field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    X,
    Y,
    Z,
}

impl Axis {
    const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];

    fn index(self) -> usize {
        self as usize
    }
}

/// A property of an object, a light or the scene settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    Name,
    Center(Axis),
    Radius,
    Subdivisions,
    Size(Axis),
    Segments,
    Path,
    Scale,
    /// The axis of a mesh's file that points up.
    Up,
    /// Whether a mesh is drawn with its file's materials or the object's own.
    Materials,
    Rotation(Axis),
    Color(Axis),
    Diffuse,
    Specular,
    Shininess,
    Reflection,
    Smooth,
    Position(Axis),
    Intensity,
    CameraPosition(Axis),
    CameraTarget(Axis),
    Fov,
    Ambient,
    Background(Axis),
    MaxDepth,
}

/// The current value of a property.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    Number(f32),
    Count(u32),
    Flag(bool),
    Text(String),
}

impl std::fmt::Display for Value {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Value::Number(x) => f.write_str(&format_number(*x)),
            Value::Count(n) => write!(f, "{n}"),
            Value::Flag(b) => f.write_str(if *b { "yes" } else { "no" }),
            Value::Text(s) => f.write_str(&clean(s)),
        }
    }
}

/// A number with at most four decimals and no trailing zeros: 1, 0.85, -2.2.
pub fn format_number(x: f32) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// The accepted values of a numeric property, which Left/Right steps through.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Range {
    Number(Limits),
    Count(CountLimits),
}

impl Key {
    /// The label shown in the properties panel, such as `center.x` or `color.r`.
    pub fn label(self, item: &Part) -> String {
        let xyz = |base: &str, a: Axis| format!("{base}.{}", ["x", "y", "z"][a.index()]);
        let rgb = |base: &str, a: Axis| format!("{base}.{}", ["r", "g", "b"][a.index()]);
        match self {
            Key::Name => "name".into(),
            Key::Center(a) => match item {
                Part::Object(o) if matches!(o.shape, Shape::Mesh { .. }) => xyz("position", a),
                _ => xyz("center", a),
            },
            Key::Radius => "radius".into(),
            Key::Subdivisions => "subdivisions".into(),
            Key::Size(a) => format!("size.{}", ["w", "h", "d"][a.index()]),
            Key::Segments => "segments".into(),
            Key::Path => "path".into(),
            Key::Scale => "scale".into(),
            Key::Up => "up".into(),
            Key::Materials => "materials".into(),
            Key::Rotation(a) => xyz("rotation", a),
            Key::Color(a) => rgb("color", a),
            Key::Diffuse => "diffuse".into(),
            Key::Specular => "specular".into(),
            Key::Shininess => "shininess".into(),
            Key::Reflection => "reflection".into(),
            Key::Smooth => "smooth".into(),
            Key::Position(a) => xyz("position", a),
            Key::Intensity => "intensity".into(),
            Key::CameraPosition(a) => xyz("camera.pos", a),
            Key::CameraTarget(a) => xyz("camera.target", a),
            Key::Fov => "camera.fov".into(),
            Key::Ambient => "ambient".into(),
            Key::Background(a) => rgb("background", a),
            Key::MaxDepth => "max depth".into(),
        }
    }

    /// The scene's limits for a numeric property; `None` for names, paths and flags.
    pub fn range(self) -> Option<Range> {
        use Range::{Count, Number};
        Some(match self {
            Key::Center(_) | Key::Position(_) | Key::CameraPosition(_) | Key::CameraTarget(_) => {
                Number(limits::COORDINATE)
            }
            Key::Radius | Key::Size(_) | Key::Scale => Number(limits::EXTENT),
            Key::Rotation(_) => Number(limits::ROTATION),
            Key::Color(_) | Key::Background(_) => Number(limits::COLOR),
            Key::Diffuse | Key::Specular | Key::Reflection => Number(limits::COEFFICIENT),
            Key::Shininess => Number(limits::SHININESS),
            Key::Intensity => Number(limits::INTENSITY),
            Key::Fov => Number(limits::FOV),
            Key::Ambient => Number(limits::AMBIENT),
            Key::Subdivisions => Count(limits::SUBDIVISIONS),
            Key::Segments => Count(limits::SEGMENTS),
            Key::MaxDepth => Count(limits::REFLECTION_DEPTH),
            Key::Name | Key::Path | Key::Smooth | Key::Up | Key::Materials => return None,
        })
    }
}

/// An owned copy of the selected item, edited and then stored back into a copy of the scene.
#[derive(Debug, Clone, PartialEq)]
pub enum Part {
    Settings(Settings),
    Light(Light),
    Object(Object),
}

/// The scene-wide properties shown under "Camera & scene".
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    pub camera: Camera,
    pub ambient: f32,
    pub background: Vec3,
    pub max_depth: u32,
}

/// A mutable reference to one property inside a [`Part`].
enum Slot<'a> {
    Number(&'a mut f32),
    Count(&'a mut u32),
    Flag(&'a mut bool),
    Name(&'a mut Option<String>),
    Path(&'a mut PathBuf),
    Axis(&'a mut UpAxis),
    Source(&'a mut MaterialSource),
}

fn component(v: &mut Vec3, a: Axis) -> &mut f32 {
    match a {
        Axis::X => &mut v.x,
        Axis::Y => &mut v.y,
        Axis::Z => &mut v.z,
    }
}

impl Part {
    /// A copy of `item` in `scene`, or `None` when the item no longer exists.
    pub fn of(scene: &Scene, item: Item) -> Option<Part> {
        Some(match item {
            Item::Settings => Part::Settings(Settings {
                camera: scene.camera,
                ambient: scene.ambient,
                background: scene.background,
                max_depth: scene.max_depth,
            }),
            Item::Light(i) => Part::Light(scene.lights.get(i)?.clone()),
            Item::Object(i) => Part::Object(scene.objects.get(i)?.clone()),
        })
    }

    /// Writes this part back over `item` of `scene`.
    fn store(self, scene: &mut Scene, item: Item) {
        match (self, item) {
            (Part::Settings(s), _) => {
                scene.camera = s.camera;
                scene.ambient = s.ambient;
                scene.background = s.background;
                scene.max_depth = s.max_depth;
            }
            (Part::Light(l), Item::Light(i)) => scene.lights[i] = l,
            (Part::Object(o), Item::Object(i)) => scene.objects[i] = o,
            _ => {}
        }
    }

    /// Every property of this part, in display order.
    pub fn keys(&self) -> Vec<Key> {
        let xyz = |f: fn(Axis) -> Key| Axis::ALL.map(f);
        let mut keys = Vec::new();
        match self {
            Part::Settings(_) => {
                keys.extend(xyz(Key::CameraPosition));
                keys.extend(xyz(Key::CameraTarget));
                keys.extend([Key::Fov, Key::Ambient]);
                keys.extend(xyz(Key::Background));
                keys.push(Key::MaxDepth);
            }
            Part::Light(_) => {
                keys.push(Key::Name);
                keys.extend(xyz(Key::Position));
                keys.push(Key::Intensity);
                keys.extend(xyz(Key::Color));
            }
            Part::Object(o) => {
                keys.push(Key::Name);
                keys.extend(xyz(Key::Center));
                match o.shape {
                    Shape::Icosahedron { .. } => keys.extend([Key::Radius, Key::Subdivisions]),
                    Shape::Box { .. } | Shape::Prism { .. } => {
                        keys.extend(xyz(Key::Size));
                        keys.push(Key::Segments);
                    }
                    Shape::Mesh { .. } => {
                        keys.extend([Key::Path, Key::Scale, Key::Up, Key::Materials]);
                    }
                }
                keys.extend(xyz(Key::Rotation));
                keys.extend(xyz(Key::Color));
                keys.extend([
                    Key::Diffuse,
                    Key::Specular,
                    Key::Shininess,
                    Key::Reflection,
                    Key::Smooth,
                ]);
            }
        }
        keys
    }

    fn slot(&mut self, key: Key) -> Option<Slot<'_>> {
        Some(match self {
            Part::Settings(s) => match key {
                Key::CameraPosition(a) => Slot::Number(component(&mut s.camera.position, a)),
                Key::CameraTarget(a) => Slot::Number(component(&mut s.camera.target, a)),
                Key::Fov => Slot::Number(&mut s.camera.fov),
                Key::Ambient => Slot::Number(&mut s.ambient),
                Key::Background(a) => Slot::Number(component(&mut s.background, a)),
                Key::MaxDepth => Slot::Count(&mut s.max_depth),
                _ => return None,
            },
            Part::Light(l) => match key {
                Key::Name => Slot::Name(&mut l.name),
                Key::Position(a) => Slot::Number(component(&mut l.position, a)),
                Key::Intensity => Slot::Number(&mut l.intensity),
                Key::Color(a) => Slot::Number(component(&mut l.color, a)),
                _ => return None,
            },
            Part::Object(o) => {
                let m = &mut o.material;
                match (key, &mut o.shape) {
                    (Key::Name, _) => Slot::Name(&mut o.name),
                    (Key::Center(a), Shape::Mesh { position: c, .. })
                    | (Key::Center(a), Shape::Icosahedron { center: c, .. })
                    | (Key::Center(a), Shape::Box { center: c, .. })
                    | (Key::Center(a), Shape::Prism { center: c, .. }) => {
                        Slot::Number(component(c, a))
                    }
                    (Key::Radius, Shape::Icosahedron { radius, .. }) => Slot::Number(radius),
                    (Key::Subdivisions, Shape::Icosahedron { subdivisions, .. }) => {
                        Slot::Count(subdivisions)
                    }
                    (Key::Size(a), Shape::Box { size, .. } | Shape::Prism { size, .. }) => {
                        Slot::Number(component(size, a))
                    }
                    (
                        Key::Segments,
                        Shape::Box { segments, .. } | Shape::Prism { segments, .. },
                    ) => Slot::Count(segments),
                    (Key::Path, Shape::Mesh { path, .. }) => Slot::Path(path),
                    (Key::Scale, Shape::Mesh { scale, .. }) => Slot::Number(scale),
                    (Key::Up, Shape::Mesh { up, .. }) => Slot::Axis(up),
                    (Key::Materials, Shape::Mesh { materials, .. }) => Slot::Source(materials),
                    (Key::Rotation(a), _) => Slot::Number(component(&mut o.rotation, a)),
                    (Key::Color(a), _) => Slot::Number(component(&mut m.color, a)),
                    (Key::Diffuse, _) => Slot::Number(&mut m.diffuse),
                    (Key::Specular, _) => Slot::Number(&mut m.specular),
                    (Key::Shininess, _) => Slot::Number(&mut m.shininess),
                    (Key::Reflection, _) => Slot::Number(&mut m.reflection),
                    (Key::Smooth, _) => Slot::Flag(&mut o.smooth),
                    _ => return None,
                }
            }
        })
    }

    /// The current value of `key`, or `None` when this part has no such property.
    pub fn value(&self, key: Key) -> Option<Value> {
        Some(match self.clone().slot(key)? {
            Slot::Number(x) => Value::Number(*x),
            Slot::Count(n) => Value::Count(*n),
            Slot::Flag(b) => Value::Flag(*b),
            Slot::Name(n) => Value::Text(n.clone().unwrap_or_default()),
            Slot::Path(p) => Value::Text(p.display().to_string()),
            Slot::Axis(a) => Value::Text(a.name().to_string()),
            Slot::Source(m) => Value::Text(m.name().to_string()),
        })
    }
}

/// Why a change was refused: a message for the status line or the inline error.
pub type Refusal = String;

/// Rounds away float noise so that 0.8 + 4 × 0.05 is exactly 1.
fn tidy(x: f32) -> f32 {
    (x * 10_000.0).round() / 10_000.0
}

/// `scene` with `key` of `item` stepped `times` steps (negative: down) within the key's
/// [`Range`]; booleans toggle. A step that would not move toward `times` is refused.
pub fn stepped(scene: &Scene, item: Item, key: Key, times: i32) -> Result<Scene, Refusal> {
    let mut part = Part::of(scene, item).ok_or("nothing selected")?;
    let range = key.range();
    let moved = |old: f64, new: f64| (new - old) * times as f64 > 0.0;
    match (part.slot(key).ok_or("no such property")?, range) {
        (Slot::Number(x), Some(Range::Number(limits))) => {
            let (lo, hi) = limits.stepping_range();
            let new = tidy(*x + limits.step * times as f32).clamp(lo, hi);
            if !moved(*x as f64, new as f64) {
                return Err(format!("already at its limit ({limits})"));
            }
            *x = new;
        }
        (Slot::Count(n), Some(Range::Count(limits))) => {
            let new = (*n as i64 + times as i64).clamp(limits.min as i64, limits.max as i64);
            if !moved(*n as f64, new as f64) {
                return Err(format!("already at its limit ({limits})"));
            }
            *n = new as u32;
        }
        (Slot::Flag(b), _) => *b = !*b,
        (Slot::Axis(a), _) => *a = cycled(&UpAxis::ALL, *a, times),
        (Slot::Source(m), _) => *m = cycled(&MaterialSource::ALL, *m, times),
        (Slot::Name(_) | Slot::Path(_), _) => {
            return Err("press Enter to type a new value".into());
        }
        (Slot::Number(_) | Slot::Count(_), _) => return Err("no range for this property".into()),
    }
    checked(scene, item, part)
}

/// The choice `times` steps after `current` in `all`, wrapping around.
fn cycled<T: Copy + PartialEq>(all: &[T], current: T, times: i32) -> T {
    let at = all.iter().position(|x| *x == current).unwrap_or(0) as i64;
    all[(at + times as i64).rem_euclid(all.len() as i64) as usize]
}

/// `scene` with `key` of `item` set from typed `text`.
pub fn typed(scene: &Scene, item: Item, key: Key, text: &str) -> Result<Scene, Refusal> {
    let mut part = Part::of(scene, item).ok_or("nothing selected")?;
    let t = text.trim();
    match part.slot(key).ok_or("no such property")? {
        Slot::Number(x) => {
            *x = t
                .parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| format!("`{t}` is not a number"))?;
        }
        Slot::Count(n) => {
            *n = t
                .parse::<u32>()
                .map_err(|_| format!("`{t}` is not a whole number ≥ 0"))?;
        }
        Slot::Flag(b) => {
            *b = match t.to_ascii_lowercase().as_str() {
                "yes" | "y" | "true" | "on" | "1" => true,
                "no" | "n" | "false" | "off" | "0" => false,
                _ => return Err(format!("`{t}` is not yes or no")),
            };
        }
        Slot::Name(n) => {
            let name = clean(t);
            *n = (!name.is_empty()).then_some(name);
        }
        Slot::Axis(a) => {
            *a = UpAxis::from_name(t)
                .ok_or_else(|| format!("`{t}` is not an axis: x, y, z, -x, -y or -z"))?;
        }
        Slot::Source(m) => {
            *m = MaterialSource::from_name(t)
                .ok_or_else(|| format!("`{t}` is not file or object"))?;
        }
        Slot::Path(p) => {
            if t.is_empty() {
                return Err("type the path of a model file".into());
            }
            *p = PathBuf::from(t);
        }
    }
    checked(scene, item, part)
}

/// Stores `part` into a copy of `scene` and validates the result.
fn checked(scene: &Scene, item: Item, part: Part) -> Result<Scene, Refusal> {
    let mut new = scene.clone();
    part.store(&mut new, item);
    validate(&new).map_err(|e| e.problem.to_string())?;
    Ok(new)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{ShapeKind, default_scene};

    /// The default scene with a mesh object of `path` added last, and that object's item.
    fn default_scene_with_mesh(path: &str) -> (Scene, Item) {
        let mut scene = default_scene();
        scene.objects.push(Object::new(Shape::new(
            ShapeKind::Mesh,
            glam::Vec3::ZERO,
            path.into(),
        )));
        let item = Item::Object(scene.objects.len() - 1);
        (scene, item)
    }

    #[test]
    fn a_meshs_up_axis_steps_through_the_six_and_takes_a_typed_name() {
        let (scene, item) = default_scene_with_mesh("part.stl");
        let up = |scene: &Scene| Part::of(scene, item).unwrap().value(Key::Up);
        assert_eq!(up(&scene), Some(Value::Text("y".into())));
        let once = stepped(&scene, item, Key::Up, 1).unwrap();
        assert_eq!(up(&once), Some(Value::Text("z".into())));
        let back = stepped(&scene, item, Key::Up, -1).unwrap();
        assert_eq!(up(&back), Some(Value::Text("x".into())));
        let written = typed(&scene, item, Key::Up, " -Z ").unwrap();
        assert_eq!(up(&written), Some(Value::Text("-z".into())));
        assert!(
            typed(&scene, item, Key::Up, "w")
                .unwrap_err()
                .contains("not an axis")
        );
        // Only meshes have one.
        assert_eq!(
            Part::of(&scene, Item::Object(0)).unwrap().value(Key::Up),
            None
        );
    }

    #[test]
    fn a_meshs_materials_toggle_between_file_and_object_and_take_a_typed_name() {
        let (scene, item) = default_scene_with_mesh("chair.obj");
        let source = |scene: &Scene| Part::of(scene, item).unwrap().value(Key::Materials);
        assert_eq!(source(&scene), Some(Value::Text("file".into())));
        let toggled = stepped(&scene, item, Key::Materials, 1).unwrap();
        assert_eq!(source(&toggled), Some(Value::Text("object".into())));
        let back = stepped(&toggled, item, Key::Materials, -1).unwrap();
        assert_eq!(source(&back), Some(Value::Text("file".into())));
        let typed_in = typed(&scene, item, Key::Materials, " Object ").unwrap();
        assert_eq!(source(&typed_in), Some(Value::Text("object".into())));
        assert!(
            typed(&scene, item, Key::Materials, "mtl")
                .unwrap_err()
                .contains("not file or object")
        );
        // Only meshes have the choice.
        let part = Part::of(&scene, Item::Object(0)).unwrap();
        assert!(!part.keys().contains(&Key::Materials));
    }
}
