//! Still images written to files and read back by independent decoders (`image` for PNG, the
//! `exr` crate for OpenEXR): sizes, channels, bit depths and known pixel values, with and
//! without coverage as alpha.

mod common;

use std::path::Path;
use std::sync::Arc;

use glam::Vec3;
use rastray::export::{Exported, ImageFormat, Output, render_to_file, save_image};
use rastray::render::{Algorithm, Frame, Progress, RenderOptions, decode_srgb16, encode_srgb};
use rastray::{Scene, World};

/// A 2×2 square facing the camera, lit head-on by a light bright enough to push its centre
/// past 1: C = color·(Ia + I·Kd) + I·Ks = (1.84, 1.42, 1.21).
const OVERBRIGHT: &str = r#"
ambient = 0.1
background = [0.5, 0.25, 0.125]
[camera]
position = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
fov = 40.0
[[light]]
position = [0.0, 0.0, 5.0]
intensity = 4.0
[[object]]
type = "box"
center = [0.0, 0.0, -0.05]
size = [2.0, 2.0, 0.1]
segments = 2
material = { color = [0.4, 0.2, 0.1], diffuse = 0.5, specular = 0.25, shininess = 10.0 }
"#;

/// A flat-coloured box lit by ambient light only (colour Ia·color = (0.4, 0.2, 0.1) on every
/// face), seen head-on through a 90° lens on a 20×20 image: its front face spans columns 10.5
/// to 15.5 (its thin side face falls between 10.495 and 10.5) and rows 8.74 to 11.26. With 4×4
/// samples, pixel (10, 10) has exactly half its sample columns (at x + 0.625 and x + 0.875) on
/// the box.
const HALF_COVERED: &str = r#"
ambient = 0.5
background = [0.5, 0.25, 0.125]
[camera]
position = [0.0, 0.0, 2.0]
target = [0.0, 0.0, 0.0]
fov = 90.0
[[object]]
type = "box"
center = [0.5995, 0.0, 0.0]
size = [1.0, 0.5, 0.02]
material = { color = [0.8, 0.4, 0.2], diffuse = 0.5, specular = 0.0, shininess = 10.0 }
"#;

/// The flat colour of the box of [`HALF_COVERED`].
const BOX_COLOR: Vec3 = Vec3::new(0.4, 0.2, 0.1);

/// Renders `scene` with `options` into a frame.
fn render(scene: &Scene, options: RenderOptions) -> Frame {
    common::render(&common::world(scene), &scene.camera, options).0
}

/// Renders `scene` with `options` straight into `path` as `format`, as `rastray render` does.
fn export(scene: &Scene, options: RenderOptions, format: ImageFormat, path: &Path) {
    let world: Arc<World> = common::world(scene);
    let done = render_to_file(
        &world,
        &scene.camera,
        &options,
        Output::Image(format),
        path,
        &Progress::new(),
    )
    .expect("export");
    assert!(matches!(done, Exported::Image(_)));
}

/// An OpenEXR file as the `exr` crate reads it.
struct Exr {
    /// Width and height, pixels.
    size: (usize, usize),
    /// Each channel's name and 32-bit float samples, in the file's order.
    channels: Vec<(String, Vec<f32>)>,
}

impl Exr {
    /// The channel names, in the file's order.
    fn names(&self) -> Vec<&str> {
        self.channels.iter().map(|(n, _)| n.as_str()).collect()
    }

    /// The samples of channel `name`.
    fn channel(&self, name: &str) -> &[f32] {
        &self
            .channels
            .iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no channel {name}"))
            .1
    }
}

/// Reads an OpenEXR file with the `exr` crate; every channel must hold 32-bit floats.
fn read_exr(path: &Path) -> Exr {
    let image = exr::prelude::read_first_flat_layer_from_file(path).expect("a valid OpenEXR file");
    let layer = image.layer_data;
    let channels = layer
        .channel_data
        .list
        .iter()
        .map(|c| {
            let exr::prelude::FlatSamples::F32(values) = &c.sample_data else {
                panic!("channel {} is not 32-bit float", c.name);
            };
            (c.name.to_string(), values.clone())
        })
        .collect();
    Exr {
        size: (layer.size.width(), layer.size.height()),
        channels,
    }
}

/// sRGB encoding in f64, from the standard, independent of the renderer's: linear [0, 1] to
/// a 16-bit code.
fn srgb16(linear: f64) -> u16 {
    let s = if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    };
    (s * 65535.0).round() as u16
}

#[test]
fn an_exr_holds_the_renderers_linear_values_unclamped() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::scene(OVERBRIGHT);
    for algorithm in Algorithm::ALL {
        let options = RenderOptions::new(algorithm, 33, 25);
        let path = dir.path().join(format!("{algorithm}.exr"));
        export(&scene, options, ImageFormat::Exr, &path);
        let frame = render(&scene, options);
        let exr = read_exr(&path);
        assert_eq!(exr.size, (33, 25));
        assert_eq!(
            exr.names(),
            ["B", "G", "R"],
            "RGB, no alpha, sorted as OpenEXR stores them"
        );
        let [r, g, b] = ["R", "G", "B"].map(|n| exr.channel(n));
        for (i, p) in frame.pixels.iter().enumerate() {
            // Bit for bit: no transfer curve, no clamping, no rounding.
            assert_eq!([r[i], g[i], b[i]], p.to_array(), "{algorithm} pixel {i}");
        }
        // Known answers: the lit centre past 1, and the background as given.
        let centre = Vec3::new(r[12 * 33 + 16], g[12 * 33 + 16], b[12 * 33 + 16]);
        let expected = Vec3::new(1.84, 1.42, 1.21);
        assert!(
            (centre - expected).abs().max_element() < 1e-4,
            "{algorithm}: centre {centre}, expected {expected}"
        );
        assert_eq!([r[0], g[0], b[0]], [0.5, 0.25, 0.125], "{algorithm}");
    }
}

#[test]
fn a_sixteen_bit_png_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::scene(OVERBRIGHT);
    let options = RenderOptions::new(Algorithm::Phong, 33, 25);
    let path = dir.path().join("deep.png");
    export(&scene, options, ImageFormat::PNG16, &path);
    let frame = render(&scene, options);
    let decoded = image::open(&path).expect("a PNG");
    assert_eq!(decoded.color(), image::ColorType::Rgb16, "16-bit RGB");
    let decoded = decoded.to_rgb16();
    assert_eq!(decoded.dimensions(), (33, 25));
    for (x, y, code) in decoded.enumerate_pixels() {
        let linear = frame.pixel(x, y);
        for c in 0..3 {
            // The code is the standard sRGB encoding of the clamped value (±1 code for f32
            // against f64 rounding), and decodes back to it within half a 16-bit step of the
            // curve's steepest slope (12.92 / 65535 ≈ 2e-4).
            let clamped = linear[c].clamp(0.0, 1.0);
            let want = srgb16(clamped as f64);
            assert!(
                code[c].abs_diff(want) <= 1,
                "({x}, {y})[{c}]: {} vs {want}",
                code[c]
            );
            let back = decode_srgb16(code[c]);
            assert!(
                (back - clamped).abs() < 2e-4,
                "({x}, {y})[{c}]: {back} vs {clamped}"
            );
        }
    }
    // The background 0.5 is sRGB 0.735357…, 48192 of 65535; over-bright pixels clamp to 65535.
    assert_eq!(decoded.get_pixel(0, 0)[0], 48192);
    assert_eq!(decoded.get_pixel(16, 12)[0], 65535);
}

#[test]
fn an_eight_bit_png_is_the_frames_srgb_bytes() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::scene(OVERBRIGHT);
    let options = RenderOptions::new(Algorithm::Ray, 33, 25);
    let path = dir.path().join("plain.png");
    export(&scene, options, ImageFormat::PNG8, &path);
    let decoded = image::open(&path).expect("a PNG");
    assert_eq!(
        decoded.color(),
        image::ColorType::Rgb8,
        "8-bit RGB, no alpha"
    );
    assert_eq!(
        decoded.to_rgb8().into_raw(),
        render(&scene, options).to_srgb8()
    );
    // The background 0.5 is sRGB code 188.
    assert_eq!(decoded.to_rgb8().get_pixel(0, 0)[0], 188);
}

#[test]
fn coverage_is_zero_on_the_background_one_inside_and_a_fraction_on_an_edge() {
    let scene = common::scene(HALF_COVERED);
    for algorithm in Algorithm::ALL {
        let frame = render(
            &scene,
            RenderOptions {
                samples: 4,
                alpha: true,
                ..RenderOptions::new(algorithm, 20, 20)
            },
        );
        let alpha = |x, y| frame.alpha_at(x, y);
        assert_eq!(alpha(2, 2), 0.0, "{algorithm}: background");
        assert_eq!(
            frame.pixel(2, 2),
            Vec3::ZERO,
            "{algorithm}: no background colour"
        );
        assert_eq!(alpha(12, 10), 1.0, "{algorithm}: inside");
        assert_eq!(alpha(10, 10), 0.5, "{algorithm}: 8 of 16 samples");
        // Premultiplied: the covered half of the box's colour, the background left out.
        // Tolerance: f32 sums of 16 samples.
        let tolerance = 1e-6;
        let edge = frame.pixel(10, 10);
        assert!(
            (edge - BOX_COLOR * 0.5).abs().max_element() < tolerance,
            "{algorithm}: {edge}"
        );
        let inside = frame.pixel(12, 10);
        assert!(
            (inside - BOX_COLOR).abs().max_element() < tolerance,
            "{algorithm}: {inside}"
        );
    }
}

#[test]
fn a_transparent_render_over_its_background_is_the_opaque_render() {
    // Coverage and colour come from separate passes; composited over the background they must
    // give back the opaque image, or the two disagree about which samples a surface covers.
    let scene = common::default_scene();
    let world = common::world(&scene);
    for algorithm in Algorithm::ALL {
        for samples in [1, 3] {
            let options = RenderOptions {
                samples,
                ..RenderOptions::new(algorithm, 64, 36)
            };
            let opaque = common::render(&world, &scene.camera, options).0;
            let transparent = common::render(
                &world,
                &scene.camera,
                RenderOptions {
                    alpha: true,
                    ..options
                },
            )
            .0;
            assert!(opaque.alpha.is_none());
            let alpha = transparent.alpha.as_ref().expect("alpha was asked for");
            assert!(alpha.contains(&0.0) && alpha.contains(&1.0));
            if samples > 1 {
                assert!(
                    alpha.iter().any(|&a| a > 0.0 && a < 1.0),
                    "{algorithm}: soft edges"
                );
            }
            for (i, ((&p, &o), &a)) in transparent
                .pixels
                .iter()
                .zip(&opaque.pixels)
                .zip(alpha)
                .enumerate()
            {
                let composite = p + (1.0 - a) * world.background;
                // Tolerance: f32 rounding of the sums of up to 9 samples.
                assert!(
                    (composite - o).abs().max_element() < 1e-5,
                    "{algorithm} ×{samples} pixel {i}: {composite} over the background, {o} opaque"
                );
                if a == 1.0 {
                    assert_eq!(
                        p, o,
                        "{algorithm} ×{samples} pixel {i}: fully covered, same bits"
                    );
                }
            }
        }
    }
}

#[test]
fn a_transparent_png_has_straight_colour_and_linear_alpha() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::scene(HALF_COVERED);
    let options = RenderOptions {
        samples: 4,
        alpha: true,
        ..RenderOptions::new(Algorithm::Phong, 20, 20)
    };
    let path8 = dir.path().join("alpha8.png");
    export(&scene, options, ImageFormat::PNG8, &path8);
    let decoded = image::open(&path8).expect("a PNG");
    assert_eq!(decoded.color(), image::ColorType::Rgba8);
    let rgba = decoded.to_rgba8();
    assert_eq!(
        rgba.get_pixel(2, 2).0,
        [0, 0, 0, 0],
        "background: transparent black"
    );
    let inside = BOX_COLOR.to_array().map(encode_srgb);
    assert_eq!(
        rgba.get_pixel(12, 10).0,
        [inside[0], inside[1], inside[2], 255]
    );
    // Straight colour: the half-covered pixel shows the box's own colour, at alpha 0.5·255.
    assert_eq!(
        rgba.get_pixel(10, 10).0,
        [inside[0], inside[1], inside[2], 128]
    );

    let path16 = dir.path().join("alpha16.png");
    export(&scene, options, ImageFormat::PNG16, &path16);
    let decoded = image::open(&path16).expect("a PNG");
    assert_eq!(decoded.color(), image::ColorType::Rgba16);
    let edge = decoded.to_rgba16().get_pixel(10, 10).0;
    assert_eq!(edge[3], 32768, "alpha 0.5 of 65535, rounded");
    assert_eq!(edge[0], srgb16(0.4), "straight colour");
}

#[test]
fn a_transparent_exr_has_premultiplied_colour_and_alpha() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::scene(HALF_COVERED);
    let options = RenderOptions {
        samples: 4,
        alpha: true,
        ..RenderOptions::new(Algorithm::Ray, 20, 20)
    };
    let path = dir.path().join("alpha.exr");
    export(&scene, options, ImageFormat::Exr, &path);
    let frame = render(&scene, options);
    let exr = read_exr(&path);
    assert_eq!(exr.size, (20, 20));
    assert_eq!(exr.names(), ["A", "B", "G", "R"]);
    let [r, g, b, a] = ["R", "G", "B", "A"].map(|n| exr.channel(n));
    let alpha = frame.alpha.as_ref().expect("alpha");
    for (i, p) in frame.pixels.iter().enumerate() {
        assert_eq!(
            [r[i], g[i], b[i], a[i]],
            [p.x, p.y, p.z, alpha[i]],
            "pixel {i}"
        );
    }
    let edge = 10 * 20 + 10;
    assert_eq!(a[edge], 0.5);
    assert!(
        (r[edge] - 0.2).abs() < 1e-6,
        "premultiplied: 0.5 × 0.4, got {}",
        r[edge]
    );
    assert_eq!(
        [r[42], g[42], b[42], a[42]],
        [0.0; 4],
        "background: nothing"
    );
}

#[test]
fn saving_an_image_replaces_the_file_whole() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("over.exr");
    std::fs::write(&path, b"old").unwrap();
    save_image(
        &Frame::filled(3, 2, Vec3::new(2.0, 0.5, 0.0)),
        ImageFormat::Exr,
        &path,
    )
    .unwrap();
    let exr = read_exr(&path);
    assert_eq!(exr.size, (3, 2));
    assert!(exr.channel("R").iter().all(|&v| v == 2.0));
    let leftovers: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(leftovers.len(), 1, "no temporary file left behind");
}
