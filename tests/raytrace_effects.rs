//! What only the ray tracer shows (shadows and mirror reflections), and how it runs: the same
//! bytes on any number of threads, cancellation, and ray counts.

use std::num::NonZeroUsize;
use std::path::Path;
use std::sync::Arc;

use glam::Vec3;
use rastray::World;
use rastray::render::{
    Algorithm, Cancelled, Frame, Progress, RayCounts, RenderError, RenderOptions, Renderer, View,
};
use rastray::scene::{Scene, from_toml_str};

fn scene(text: &str) -> (Scene, Arc<World>) {
    let scene = from_toml_str(text, Path::new("test.toml")).expect("valid scene");
    let world = World::build(&scene, Path::new(".")).expect("world");
    (scene, Arc::new(world))
}

/// Renders with `options` into a new frame; the frame and the rays cast.
fn render(scene: &Scene, world: &Arc<World>, options: RenderOptions) -> (Frame, RayCounts) {
    let mut frame = Frame::default();
    let stats = Renderer::new(options)
        .render(world, &scene.camera, &Progress::new(), &mut frame)
        .expect("render");
    (frame, stats.rays)
}

/// The ray tracer's options at `size`, with or without shadows, reflecting to `depth`.
fn ray_options(size: (u32, u32), shadows: bool, depth: u32) -> RenderOptions {
    RenderOptions {
        shadows,
        max_depth: Some(depth),
        ..RenderOptions::new(Algorithm::Ray, size.0, size.1)
    }
}

fn ray_frame(
    scene: &Scene,
    world: &Arc<World>,
    size: (u32, u32),
    shadows: bool,
    depth: u32,
) -> Frame {
    render(scene, world, ray_options(size, shadows, depth)).0
}

/// A clearly red 8-bit pixel.
fn is_red([r, g, b]: [u8; 3]) -> bool {
    r > 60 && r as u32 > 2 * g as u32 && r as u32 > 2 * b as u32
}

/// A grey mirror filling the view, and a red box behind the camera that only the mirror shows.
const MIRROR: &str = r#"
ambient = 0.2
background = [0.0, 0.0, 0.0]
[camera]
position = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
fov = 45.0
[[light]]
position = [0.0, 3.0, 6.0]
[[object]]
type = "box"
name = "mirror"
center = [0.0, 0.0, -2.0]
size = [20.0, 20.0, 0.2]
material = { color = [0.1, 0.1, 0.1], diffuse = 0.1, specular = 0.0, reflection = 1.0 }
[[object]]
type = "box"
name = "red"
center = [0.0, 0.0, 9.0]
size = [2.0, 2.0, 2.0]
material = { color = [0.9, 0.05, 0.05], diffuse = 0.9, specular = 0.0 }
"#;

#[test]
fn mirror_shows_the_red_box_only_with_reflections() {
    let (scene, world) = scene(MIRROR);
    let reflected = ray_frame(&scene, &world, (64, 48), true, 1);
    assert!(
        is_red(reflected.srgb8_at(32, 24)),
        "the mirror's centre reflects the box: {:?}",
        reflected.srgb8_at(32, 24)
    );
    let flat = ray_frame(&scene, &world, (64, 48), true, 0);
    let red = (0..48)
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .filter(|&(x, y)| is_red(flat.srgb8_at(x, y)))
        .count();
    assert_eq!(red, 0, "no reflection at depth 0, so nothing red");
}

/// A box floating between a light straight above and the floor.
const SHADOW: &str = r#"
ambient = 0.1
[camera]
position = [0.0, 4.0, 6.0]
target = [0.0, 0.0, 0.0]
fov = 50.0
[[light]]
position = [0.0, 6.0, 0.0]
[[object]]
type = "box"
name = "floor"
center = [0.0, -0.1, 0.0]
size = [10.0, 0.2, 10.0]
material = { color = [0.8, 0.8, 0.8], diffuse = 0.9, specular = 0.0 }
[[object]]
type = "box"
name = "blocker"
center = [0.0, 2.0, 0.0]
size = [1.0, 1.0, 1.0]
material = { color = [0.2, 0.4, 0.9] }
"#;

/// The pixel where world point `p` appears.
fn pixel_of(scene: &Scene, size: (u32, u32), p: Vec3) -> (u32, u32) {
    let view = View::new(&scene.camera, size.0, size.1);
    let px = view.clip_to_pixel(view.to_clip(p));
    (px.x as u32, px.y as u32)
}

#[test]
fn box_shadows_the_floor_only_with_shadows_on() {
    let (scene, world) = scene(SHADOW);
    let size = (96, 72);
    let under = pixel_of(&scene, size, Vec3::ZERO);
    let aside = pixel_of(&scene, size, Vec3::new(3.0, 0.0, 1.0));
    let on = ray_frame(&scene, &world, size, true, 0);
    let off = ray_frame(&scene, &world, size, false, 0);
    let lum = |f: &Frame, (x, y): (u32, u32)| f.pixel(x, y).element_sum();
    // In shadow only the ambient term remains: 0.1 · 0.8 per channel.
    assert!(
        (lum(&on, under) - 3.0 * 0.08).abs() < 1e-3,
        "under the box: {}",
        on.pixel(under.0, under.1)
    );
    assert!(lum(&off, under) > 3.0 * 0.5, "lit without shadow rays");
    assert_eq!(
        on.pixel(aside.0, aside.1),
        off.pixel(aside.0, aside.1),
        "outside the shadow"
    );
}

#[test]
fn same_bytes_on_one_and_two_threads() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml");
    let scene = rastray::scene::load(&path).expect("scene");
    let world = Arc::new(World::build(&scene, path.parent().expect("dir")).expect("world"));
    let render_on = |threads: usize| {
        let options = RenderOptions {
            threads: NonZeroUsize::new(threads),
            ..ray_options((160, 90), true, 4)
        };
        render(&scene, &world, options).0
    };
    let one = render_on(1);
    let two = render_on(2);
    assert!(one.pixels == two.pixels, "thread count changed the image");
}

#[test]
fn ray_counts_follow_the_options() {
    let (scene, world) = scene(SHADOW);
    let mut options = ray_options((40, 30), false, 0);
    let (_, stats) = render(&scene, &world, options);
    assert_eq!(
        (stats.primary, stats.shadow, stats.reflection),
        (1200, 0, 0)
    );
    options.shadows = true;
    let (_, stats) = render(&scene, &world, options);
    // One light: at most one shadow ray per primary ray, and some surface faces it.
    assert!(
        stats.shadow > 0 && stats.shadow <= stats.primary,
        "{stats:?}"
    );

    let (scene, world) = self::scene(MIRROR);
    options.max_depth = Some(3);
    let (_, stats) = render(&scene, &world, options);
    // Every pixel sees the mirror, so every primary ray spawns at least one reflection.
    assert!(stats.reflection >= stats.primary, "{stats:?}");
}

#[test]
fn cancelled_render_stops_with_an_error() {
    let (scene, world) = scene(SHADOW);
    let progress = Progress::new();
    progress.cancel();
    let mut renderer = Renderer::new(RenderOptions::new(Algorithm::Ray, 64, 48));
    let result = renderer.render(&world, &scene.camera, &progress, &mut Frame::default());
    assert_eq!(result.map(|_| ()), Err(RenderError::Cancelled(Cancelled)));
}
