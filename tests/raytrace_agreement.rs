//! With shadows and reflections off, the ray tracer and the Phong Z-buffer compute the same
//! thing: the shared lighting function with the interpolated normal at the surface seen through
//! each pixel centre. Their 8-bit sRGB images must agree to a PSNR of at least 40 dB.

mod common;

use std::path::Path;
use std::sync::Arc;

use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::{Scene, World};

/// Least acceptable peak signal-to-noise ratio, dB.
const MIN_PSNR: f64 = 40.0;

fn load(path: &str) -> (Scene, Arc<World>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    let scene = rastray::scene::load(&path).expect("scene loads");
    let world = World::build(&scene, path.parent().expect("a directory")).expect("world");
    (scene, Arc::new(world))
}

fn frame(scene: &Scene, world: &Arc<World>, algorithm: Algorithm) -> Frame {
    let mut options = RenderOptions::new(algorithm, 480, 270);
    options.shadows = false;
    options.max_depth = Some(0);
    let mut frame = Frame::default();
    Renderer::new(options)
        .render(world, &scene.camera, &Progress::new(), &mut frame)
        .expect("render");
    frame
}

/// Pixels where exactly one of the two images shows the background: coverage disagreements.
fn coverage_mismatches(a: &Frame, b: &Frame, background: glam::Vec3) -> usize {
    a.pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| (**p == background) != (**q == background))
        .count()
}

fn check(path: &str) {
    let (scene, world) = load(path);
    let phong = frame(&scene, &world, Algorithm::Phong);
    let ray = frame(&scene, &world, Algorithm::Ray);
    let db = common::psnr(&phong.to_srgb8(), &ray.to_srgb8());
    let misses = coverage_mismatches(&phong, &ray, world.background);
    println!(
        "{path}: ray tracer vs Phong PSNR {db:.2} dB; {misses} of {} pixels differ in coverage",
        phong.pixels.len()
    );
    assert!(db >= MIN_PSNR, "{path}: PSNR {db:.2} dB < {MIN_PSNR} dB");
}

#[test]
fn default_scene_agrees_with_phong() {
    check("scenes/default.toml");
}

#[test]
fn teapot_obj_scene_agrees_with_phong() {
    check("scenes/teapot.toml");
}

#[test]
fn suzanne_gltf_scene_agrees_with_phong() {
    check("scenes/suzanne.toml");
}
