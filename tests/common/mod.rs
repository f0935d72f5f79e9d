//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod model_invariants;
pub mod ply_types;
pub mod textured_quad;

use std::path::Path;
use std::sync::Arc;

use rastray::render::{Algorithm, Frame, Progress, RenderOptions, RenderStats, Renderer};
use rastray::scene::Camera;
use rastray::{Scene, World};

/// Parses a scene from TOML text (panics with the error: the tests' scenes are valid).
pub fn scene(toml: &str) -> Scene {
    rastray::scene::from_toml_str(toml, Path::new("test.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// Builds the world of `scene` with OBJ paths relative to the crate root.
pub fn world(scene: &Scene) -> Arc<World> {
    let world = World::build(scene, Path::new(env!("CARGO_MANIFEST_DIR")));
    Arc::new(world.unwrap_or_else(|e| panic!("{e}")))
}

/// Renders `world` seen by `camera` with `options` into a new frame, by a new renderer.
pub fn render(world: &Arc<World>, camera: &Camera, options: RenderOptions) -> (Frame, RenderStats) {
    let mut frame = Frame::default();
    let stats = Renderer::new(options)
        .render(world, camera, &Progress::new(), &mut frame)
        .expect("render");
    (frame, stats)
}

/// Renders `scene` with `algorithm` at `width`×`height`, one sample per pixel.
pub fn draw(scene: &Scene, algorithm: Algorithm, width: u32, height: u32) -> Frame {
    let options = RenderOptions::new(algorithm, width, height);
    render(&world(scene), &scene.camera, options).0
}

/// PSNR in dB of two 8-bit images of the same size (infinite when identical).
pub fn psnr(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mse = a
        .iter()
        .zip(b)
        .map(|(&x, &y)| (x as f64 - y as f64).powi(2))
        .sum::<f64>()
        / a.len() as f64;
    10.0 * (255.0f64 * 255.0 / mse).log10()
}

/// The default scene file shipped in scenes/.
pub fn default_scene() -> Scene {
    rastray::scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml"))
        .expect("default.toml")
}

/// Makes a FIFO (named pipe) at `path`, mode 0600.
pub fn mkfifo(path: &Path) {
    rustix::fs::mknodat(
        rustix::fs::CWD,
        path,
        rustix::fs::FileType::Fifo,
        rustix::fs::Mode::from_raw_mode(0o600),
        0,
    )
    .expect("mkfifo");
}

/// A folder made once per test binary, for cases that write files: a folder per case costs more
/// than the case.
pub fn scratch() -> &'static Path {
    static DIR: std::sync::OnceLock<tempfile::TempDir> = std::sync::OnceLock::new();
    DIR.get_or_init(|| tempfile::tempdir().expect("tempdir"))
        .path()
}

/// Runs the built `rastray` with `args` in folder `dir`, its output captured.
pub fn rastray_in(args: &[&str], dir: &Path) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs")
}

/// `document` and `bin` in a GLB container: the 12-byte header, the JSON chunk padded with
/// spaces and the binary chunk padded with zeros, each to four bytes.
pub fn glb(document: &serde_json::Value, mut bin: Vec<u8>) -> Vec<u8> {
    let mut json = serde_json::to_vec(document).expect("JSON");
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    for word in [0x4654_6C67, 2, total as u32, json.len() as u32, 0x4E4F_534A] {
        out.extend_from_slice(&u32::to_le_bytes(word));
    }
    out.extend_from_slice(&json);
    out.extend_from_slice(&u32::to_le_bytes(bin.len() as u32));
    out.extend_from_slice(&u32::to_le_bytes(0x004E_4942));
    out.extend_from_slice(&bin);
    out
}
