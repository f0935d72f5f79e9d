//! Turntables written to files and read back by `image`'s GIF and APNG decoders: frame count,
//! size, timing, and each frame against a still render from its own camera, in order.

mod common;

use std::fs::File;
use std::io::BufReader;
use std::path::Path;

use image::{AnimationDecoder, RgbaImage};
use rastray::export::{
    AnimationFormat, ExportError, Exported, Output, PngDepth, Turntable, TurntableError,
    render_to_file,
};
use rastray::render::{Algorithm, Frame, Progress, RenderError, RenderOptions, encode_srgb16};
use rastray::{Scene, World};

/// Small frames keep the test quick; 6 frames are more than one batch on any test machine
/// with fewer than six cores, so frames from different batches are checked.
const SIZE: (u32, u32) = (48, 27);
const FRAMES: u32 = 6;

fn options(algorithm: Algorithm) -> RenderOptions {
    RenderOptions::new(algorithm, SIZE.0, SIZE.1)
}

/// Writes the turntable of `scene` to `path` as `format`.
fn turntable(
    scene: &Scene,
    options: RenderOptions,
    format: AnimationFormat,
    path: &Path,
) -> Result<Exported, ExportError> {
    let world: std::sync::Arc<World> = common::world(scene);
    let output = Output::Turntable(Turntable::new(FRAMES), format);
    render_to_file(
        &world,
        &scene.camera,
        &options,
        output,
        path,
        &Progress::new(),
    )
}

/// Frame `k` rendered on its own, from the turntable's camera `k`.
fn still(scene: &Scene, options: RenderOptions, k: u32) -> Frame {
    let camera = Turntable::new(FRAMES).camera(&scene.camera, k);
    common::render(&common::world(scene), &camera, options).0
}

/// Every frame of an animation, with its delay in milliseconds.
fn frames(decoder: impl for<'a> AnimationDecoder<'a>) -> Vec<(RgbaImage, u32)> {
    decoder
        .into_frames()
        .map(|f| {
            let f = f.expect("a frame decodes");
            let (numer, denom) = f.delay().numer_denom_ms();
            (f.into_buffer(), numer / denom)
        })
        .collect()
}

fn gif_frames(path: &Path) -> Vec<(RgbaImage, u32)> {
    let file = BufReader::new(File::open(path).expect("the GIF exists"));
    frames(image::codecs::gif::GifDecoder::new(file).expect("a GIF"))
}

fn apng_frames(path: &Path) -> Vec<(RgbaImage, u32)> {
    let file = BufReader::new(File::open(path).expect("the PNG exists"));
    let decoder = image::codecs::png::PngDecoder::new(file).expect("a PNG");
    assert!(decoder.is_apng().expect("readable"), "an animated PNG");
    frames(decoder.apng().expect("an APNG"))
}

/// Mean absolute difference of the RGB channels, in 8-bit codes.
fn mean_difference(a: &RgbaImage, b: &[u8]) -> f64 {
    let rgb = a.pixels().flat_map(|p| [p[0], p[1], p[2]]);
    let total: u64 = rgb.zip(b).map(|(x, &y)| x.abs_diff(y) as u64).sum();
    total as f64 / b.len() as f64
}

#[test]
fn an_animated_png_holds_every_view_in_order_losslessly() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::default_scene();
    let path = dir.path().join("spin.png");
    let done = turntable(
        &scene,
        options(Algorithm::Gouraud),
        AnimationFormat::Apng(PngDepth::Eight),
        &path,
    )
    .expect("turntable");
    assert!(matches!(done, Exported::Turntable(stats) if stats.frames == FRAMES));
    let frames = apng_frames(&path);
    assert_eq!(frames.len(), FRAMES as usize);
    for (k, (image, delay)) in frames.iter().enumerate() {
        assert_eq!(image.dimensions(), SIZE);
        assert_eq!(*delay, 40, "25 frames per second");
        let expected = still(&scene, options(Algorithm::Gouraud), k as u32).to_srgb8();
        assert_eq!(mean_difference(image, &expected), 0.0, "frame {k}");
        assert!(image.pixels().all(|p| p[3] == 255), "frame {k}: opaque");
    }
    // The views differ: the camera moved.
    assert_ne!(frames[0].0, frames[FRAMES as usize / 2].0);
}

#[test]
fn a_gif_holds_every_view_in_order_within_its_palette() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::default_scene();
    let path = dir.path().join("spin.gif");
    turntable(
        &scene,
        options(Algorithm::Phong),
        AnimationFormat::Gif,
        &path,
    )
    .expect("turntable");
    let frames = gif_frames(&path);
    assert_eq!(frames.len(), FRAMES as usize);
    let stills: Vec<Vec<u8>> = (0..FRAMES)
        .map(|k| still(&scene, options(Algorithm::Phong), k).to_srgb8())
        .collect();
    for (k, (image, delay)) in frames.iter().enumerate() {
        assert_eq!(image.dimensions(), SIZE);
        assert_eq!(*delay, 40, "4 hundredths of a second");
        // Tolerance: 256 colours chosen by NeuQuant for a few hundred distinct ones stay
        // within a few codes on average; another view of the scene is much further off.
        let own = mean_difference(image, &stills[k]);
        assert!(own < 3.0, "frame {k}: {own} codes from its view");
        let other = mean_difference(image, &stills[(k + FRAMES as usize / 2) % FRAMES as usize]);
        assert!(
            other > 3.0 * own.max(1.0),
            "frame {k}: {other} codes from the opposite view"
        );
    }
}

#[test]
fn transparent_turntables_keep_coverage() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::default_scene();
    let transparent = RenderOptions {
        samples: 2,
        alpha: true,
        ..options(Algorithm::Ray)
    };
    let apng = dir.path().join("clear.png");
    turntable(
        &scene,
        transparent,
        AnimationFormat::Apng(PngDepth::Eight),
        &apng,
    )
    .expect("turntable");
    let gif = dir.path().join("clear.gif");
    turntable(&scene, transparent, AnimationFormat::Gif, &gif).expect("turntable");
    let apng = apng_frames(&apng);
    let gif = gif_frames(&gif);
    for k in 0..FRAMES as usize {
        let frame = still(&scene, transparent, k as u32);
        let alpha = frame.alpha.as_ref().expect("alpha");
        for (i, &a) in alpha.iter().enumerate() {
            let (x, y) = (i as u32 % SIZE.0, i as u32 / SIZE.0);
            let png_alpha = apng[k].0.get_pixel(x, y)[3];
            assert_eq!(
                png_alpha,
                (a * 255.0 + 0.5) as u8,
                "APNG frame {k} ({x}, {y})"
            );
            // GIF has one bit: opaque from half coverage up.
            let gif_alpha = gif[k].0.get_pixel(x, y)[3];
            assert_eq!(
                gif_alpha,
                if png_alpha >= 128 { 255 } else { 0 },
                "GIF frame {k}"
            );
        }
        assert!(alpha.contains(&0.0) && alpha.contains(&1.0), "frame {k}");
    }
}

#[test]
fn a_sixteen_bit_animated_png_holds_sixteen_bit_views() {
    // `image` decodes 8-bit animations only; the `png` crate reads every frame at full depth.
    let dir = tempfile::tempdir().unwrap();
    let scene = common::default_scene();
    let path = dir.path().join("deep.png");
    let format = AnimationFormat::Apng(PngDepth::Sixteen);
    turntable(&scene, options(Algorithm::Phong), format, &path).expect("turntable");
    let file = BufReader::new(File::open(&path).unwrap());
    let mut reader = png::Decoder::new(file).read_info().expect("a PNG");
    let info = reader.info();
    assert_eq!(
        (info.bit_depth, info.color_type),
        (png::BitDepth::Sixteen, png::ColorType::Rgb)
    );
    assert_eq!(info.animation_control.map(|a| a.num_frames), Some(FRAMES));
    let mut samples = vec![0; reader.output_buffer_size().expect("a sane size")];
    for k in 0..FRAMES {
        reader.next_frame(&mut samples).expect("a frame decodes");
        let view = still(&scene, options(Algorithm::Phong), k);
        let expected: Vec<u8> = view
            .pixels
            .iter()
            .flat_map(|p| p.to_array().map(|c| encode_srgb16(c).to_be_bytes()))
            .flatten()
            .collect();
        assert!(
            samples == expected,
            "frame {k}: the view's 16-bit sRGB samples"
        );
    }
}

#[test]
fn a_cancelled_turntable_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::default_scene();
    let world = common::world(&scene);
    let path = dir.path().join("never.gif");
    let progress = Progress::new();
    progress.cancel();
    let output = Output::Turntable(Turntable::new(FRAMES), AnimationFormat::Gif);
    let options = options(Algorithm::Phong);
    let result = render_to_file(&world, &scene.camera, &options, output, &path, &progress);
    assert!(
        matches!(result, Err(ExportError::Render(RenderError::Cancelled(_)))),
        "{result:?}"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "no file and no temporary file: {left:?}");
}

#[test]
fn bad_turntables_are_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::default_scene();
    let world = common::world(&scene);
    let options = options(Algorithm::Phong);
    let none = Output::Turntable(Turntable::new(0), AnimationFormat::Gif);
    let path = dir.path().join("x.gif");
    let result = render_to_file(
        &world,
        &scene.camera,
        &options,
        none,
        &path,
        &Progress::new(),
    );
    assert!(matches!(
        result,
        Err(ExportError::Turntable(TurntableError::Frames(0)))
    ));
    let nowhere = dir.path().join("missing").join("x.gif");
    let output = Output::Turntable(Turntable::new(2), AnimationFormat::Gif);
    let result = render_to_file(
        &world,
        &scene.camera,
        &options,
        output,
        &nowhere,
        &Progress::new(),
    );
    let message = result.expect_err("no such folder").to_string();
    assert!(message.contains("missing"), "{message}");
}
