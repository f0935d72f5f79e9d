//! The terminal encoders on a 160×48-cell frame of the default scene, each rendered once at the
//! size the picture is drawn from: for the text cells (half blocks, quadrants, sextants,
//! braille) the 6×12 samples a cell that [`Protocol::picture_size`] asks on 1:2 cells, spelled
//! as SGR text in truecolor and in the 256-colour palette; for kitty the pixels the editor
//! renders on 10×20-pixel cells (the cells' pixels within [`PIXEL_BUDGET`]), as PNG in base64
//! pieces. The goal is at most 2 ms a frame for each set of text cells.

use std::path::PathBuf;
use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use rastray::World;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
use rastray::scene::default_scene;
use rastray::terminal_image::{CellArea, CellSize, ColorMode, GlyphSet, PreviewImage, Protocol};
use rastray::tui::terminal::graphics::PIXEL_BUDGET;

const AREA: CellArea = CellArea {
    cols: 160,
    rows: 48,
};
/// A common cell shape, 1:2, the one the text encoders sample without resampling.
const CELL: CellSize = CellSize {
    width: 10,
    height: 20,
};

/// The default scene rendered at `width`×`height` as 8-bit sRGB.
fn picture(width: u32, height: u32) -> PreviewImage {
    let scene = default_scene();
    let world = Arc::new(World::build(&scene, &PathBuf::from(".")).unwrap());
    let options = RenderOptions::new(Algorithm::Phong, width, height);
    let mut frame = Frame::default();
    Renderer::new(options)
        .render(&world, &scene.camera, &Progress::new(), &mut frame)
        .unwrap();
    PreviewImage::from_frame(&frame)
}

fn encoders(c: &mut Criterion) {
    let sample = Protocol::Cells(GlyphSet::HalfBlock, ColorMode::Truecolor);
    let (width, height) = sample.picture_size(AREA, CELL);
    let cells = picture(width, height);
    for mode in [ColorMode::Truecolor, ColorMode::Ansi256] {
        for set in GlyphSet::ALL {
            let protocol = Protocol::Cells(set, mode);
            let name = format!("encode 160x48 cells {} {mode:?}", set.name());
            c.bench_function(&name, |b| b.iter(|| protocol.encode(&cells, AREA).unwrap()));
        }
    }
    let (width, height) = AREA.pixels_within(CELL, PIXEL_BUDGET);
    let pixels = picture(width, height);
    c.bench_function(
        &format!("encode 160x48 cells kitty {width}x{height}"),
        |b| b.iter(|| Protocol::Kitty.encode(&pixels, AREA).unwrap()),
    );
}

criterion_group!(benches, encoders);
criterion_main!(benches);
