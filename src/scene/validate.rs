//! Range checks on a parsed scene. Every check is written so that NaN fails it.

use std::fmt;

use glam::Vec3;

use super::material::Material;
use super::model::Scene;
use super::object::Shape;

/// Most subdivisions an icosahedron may have (8 gives 1,310,720 faces).
pub const MAX_SUBDIVISIONS: u32 = 8;
/// Most segments per box or prism face edge (512 gives 3,145,728 box faces).
pub const MAX_SEGMENTS: u32 = 512;
/// Deepest reflection recursion allowed.
pub const MAX_DEPTH: u32 = 16;
/// Largest coordinate magnitude accepted, world units.
pub const MAX_COORDINATE: f32 = 1.0e6;

/// Where in a scene file a value lives, such as `object[2].size`.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct FieldPath(pub Vec<PathSegment>);

/// One step of a [`FieldPath`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PathSegment {
    Key(String),
    Index(usize),
}

impl FieldPath {
    fn key(mut self, k: &str) -> FieldPath {
        self.0.push(PathSegment::Key(k.to_string()));
        self
    }
    fn index(mut self, i: usize) -> FieldPath {
        self.0.push(PathSegment::Index(i));
        self
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (n, seg) in self.0.iter().enumerate() {
            match seg {
                PathSegment::Key(k) if n == 0 => write!(f, "{k}")?,
                PathSegment::Key(k) => write!(f, ".{k}")?,
                PathSegment::Index(i) => write!(f, "[{i}]")?,
            }
        }
        Ok(())
    }
}

/// A value out of its range: where it is and what is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct Invalid {
    pub path: FieldPath,
    pub message: String,
}

type Check = Result<(), Invalid>;

fn fail(path: &FieldPath, message: String) -> Check {
    Err(Invalid {
        path: path.clone(),
        message,
    })
}

fn finite_vec(path: &FieldPath, v: Vec3) -> Check {
    if v.is_finite() && v.abs().max_element() <= MAX_COORDINATE {
        Ok(())
    } else {
        fail(
            path,
            format!("must be finite numbers of magnitude at most {MAX_COORDINATE:e}, got {v}"),
        )
    }
}

fn unit_range(path: &FieldPath, x: f32) -> Check {
    if (0.0..=1.0).contains(&x) {
        Ok(())
    } else {
        fail(path, format!("must be between 0 and 1, got {x}"))
    }
}

fn color(path: &FieldPath, c: Vec3) -> Check {
    if c.cmpge(Vec3::ZERO).all() && c.cmple(Vec3::ONE).all() {
        Ok(())
    } else {
        fail(
            path,
            format!("each channel must be between 0 and 1, got {c}"),
        )
    }
}

fn positive(path: &FieldPath, x: f32) -> Check {
    if x > 0.0 && x <= MAX_COORDINATE {
        Ok(())
    } else {
        fail(path, format!("must be a positive finite number, got {x}"))
    }
}

fn positive_size(path: &FieldPath, v: Vec3) -> Check {
    if v.cmpgt(Vec3::ZERO).all() && v.max_element() <= MAX_COORDINATE {
        Ok(())
    } else {
        fail(
            path,
            format!("width, height and depth must be positive finite numbers, got {v}"),
        )
    }
}

fn non_negative(path: &FieldPath, x: f32, max: f32) -> Check {
    if (0.0..=max).contains(&x) {
        Ok(())
    } else {
        fail(path, format!("must be between 0 and {max}, got {x}"))
    }
}

fn at_most(path: &FieldPath, x: u32, min: u32, max: u32) -> Check {
    if (min..=max).contains(&x) {
        Ok(())
    } else {
        fail(path, format!("must be between {min} and {max}, got {x}"))
    }
}

/// Checks a material's coefficients.
pub fn validate_material(path: &FieldPath, m: &Material) -> Check {
    color(&path.clone().key("color"), m.color)?;
    unit_range(&path.clone().key("diffuse"), m.diffuse)?;
    unit_range(&path.clone().key("specular"), m.specular)?;
    non_negative(&path.clone().key("shininess"), m.shininess, 10_000.0)?;
    unit_range(&path.clone().key("reflection"), m.reflection)
}

/// Checks every number of `scene`; the first problem found is returned.
pub fn validate(scene: &Scene) -> Check {
    let root = FieldPath::default();
    let cam = root.clone().key("camera");
    let c = &scene.camera;
    finite_vec(&cam.clone().key("position"), c.position)?;
    finite_vec(&cam.clone().key("target"), c.target)?;
    finite_vec(&cam.clone().key("up"), c.up)?;
    if !(c.fov > 0.0 && c.fov < 180.0) {
        fail(
            &cam.clone().key("fov"),
            format!(
                "must be between 0 and 180 degrees (exclusive), got {}",
                c.fov
            ),
        )?;
    }
    let dir = c.target - c.position;
    if dir.length_squared() < 1e-12 {
        fail(
            &cam.clone().key("target"),
            "must differ from the camera position".into(),
        )?;
    }
    if dir
        .normalize()
        .cross(c.up.normalize_or_zero())
        .length_squared()
        < 1e-8
    {
        fail(
            &cam.clone().key("up"),
            "must not be parallel to the view direction".into(),
        )?;
    }
    unit_range(&root.clone().key("ambient"), scene.ambient)?;
    color(&root.clone().key("background"), scene.background)?;
    at_most(
        &root.clone().key("max_depth"),
        scene.max_depth,
        0,
        MAX_DEPTH,
    )?;
    if let Some(f) = &scene.falloff {
        let fp = root.clone().key("falloff");
        non_negative(&fp.clone().key("linear"), f.linear, 1.0e6)?;
        non_negative(&fp.clone().key("quadratic"), f.quadratic, 1.0e6)?;
    }
    for (i, light) in scene.lights.iter().enumerate() {
        let lp = root.clone().key("light").index(i);
        finite_vec(&lp.clone().key("position"), light.position)?;
        non_negative(&lp.clone().key("intensity"), light.intensity, 1.0e6)?;
        color(&lp.clone().key("color"), light.color)?;
    }
    for (i, object) in scene.objects.iter().enumerate() {
        let op = root.clone().key("object").index(i);
        finite_vec(&op.clone().key("rotation"), object.rotation)?;
        validate_material(&op.clone().key("material"), &object.material)?;
        match &object.shape {
            Shape::Icosahedron {
                center,
                radius,
                subdivisions,
            } => {
                finite_vec(&op.clone().key("center"), *center)?;
                positive(&op.clone().key("radius"), *radius)?;
                at_most(
                    &op.clone().key("subdivisions"),
                    *subdivisions,
                    0,
                    MAX_SUBDIVISIONS,
                )?;
            }
            Shape::Box {
                center,
                size,
                segments,
            }
            | Shape::Prism {
                center,
                size,
                segments,
            } => {
                finite_vec(&op.clone().key("center"), *center)?;
                positive_size(&op.clone().key("size"), *size)?;
                at_most(&op.clone().key("segments"), *segments, 1, MAX_SEGMENTS)?;
            }
            Shape::Mesh {
                path,
                position,
                scale,
            } => {
                if path.as_os_str().is_empty() {
                    fail(&op.clone().key("path"), "must name an OBJ file".into())?;
                }
                finite_vec(&op.clone().key("position"), *position)?;
                positive(&op.clone().key("scale"), *scale)?;
            }
        }
    }
    Ok(())
}
