//! The text-cell encoders on a 160×48-cell frame of the default scene (rendered once, at 6×12
//! pixels a cell): the time to choose every cell's glyph and colours and spell them as SGR text.
//! The goal is at most 2 ms a frame for each set.

use std::path::PathBuf;
use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::scene::default_scene;
use rastray::terminal_image::ColorMode;
use rastray::terminal_image::GlyphSet;
use rastray::terminal_image::glyph_cells::{SAMPLES_X, SAMPLES_Y, encode};
use rastray::terminal_image::preview::PreviewImage;

const COLS: u32 = 160;
const ROWS: u32 = 48;

fn encoders(c: &mut Criterion) {
    let scene = default_scene();
    let world = Arc::new(World::build(&scene, &PathBuf::from(".")).unwrap());
    let options = RenderOptions::new(Algorithm::Phong, COLS * SAMPLES_X, ROWS * SAMPLES_Y);
    let mut frame = Frame::default();
    Renderer::new(options)
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .unwrap();
    let image = PreviewImage::from_frame(&frame);
    for set in GlyphSet::ALL {
        c.bench_function(&format!("encode 160x48 cells {}", set.name()), |b| {
            b.iter(|| encode(&image, COLS, ROWS, set, ColorMode::Truecolor))
        });
    }
}

criterion_group!(benches, encoders);
criterion_main!(benches);
