//! The Z-buffer renderers: known answers, Gouraud/Phong agreement, supersampling and
//! thread-count determinism. The rasterizer's own invariants (coverage, near-plane clipping,
//! depth, strips) are tested inside it, in `src/render/raster/tests.rs`.

mod common;

use std::num::NonZeroUsize;

use glam::Vec3;
use rastray::render::{Algorithm, RenderOptions};

/// A 2×2 square facing the camera (a thin box split in 2×2 so that a vertex sits at the centre),
/// camera and one light both 5 units in front of it on the axis.
const HEAD_ON: &str = r#"
ambient = 0.1
background = [0.0, 0.0, 0.0]
[camera]
position = [0.0, 0.0, 5.0]
target = [0.0, 0.0, 0.0]
fov = 40.0
[[light]]
position = [0.0, 0.0, 5.0]
intensity = 1.0
[[object]]
type = "box"
center = [0.0, 0.0, -0.05]
size = [2.0, 2.0, 0.1]
segments = 2
material = { color = [0.4, 0.2, 0.1], diffuse = 0.5, specular = 0.25, shininess = 10.0 }
"#;

#[test]
fn square_lit_head_on_has_the_analytic_colour_at_its_centre() {
    // At the centre N = L = V = +Z, so N·L = 1 and R·V = 1:
    // C = Ia·color + I·(Kd·color + Ks) per channel.
    let expected = Vec3::new(0.4, 0.2, 0.1) * (0.1 + 0.5) + Vec3::splat(0.25);
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        // 33×33: the centre pixel's centre lies exactly on the view axis.
        let frame = common::draw(&common::scene(HEAD_ON), algorithm, 33, 33);
        let got = frame.pixel(16, 16);
        // Tolerance: f32 rounding only.
        assert!(
            (got - expected).abs().max_element() < 1e-4,
            "{algorithm}: got {got}, expected {expected}"
        );
        // The corner pixel is background: the square does not fill the view.
        assert_eq!(frame.pixel(0, 0), Vec3::ZERO, "{algorithm}");
    }
}

#[test]
fn gouraud_equals_phong_on_a_flat_face_under_a_distant_light() {
    let toml = r#"
ambient = 0.05
background = [0.0, 0.0, 0.0]
[camera]
position = [0.0, 0.0, 6.0]
target = [0.0, 0.0, 0.0]
[[light]]
position = [300.0, 500.0, 1000.0]
[[object]]
type = "box"
center = [0.0, 0.0, 0.0]
size = [3.0, 2.0, 0.2]
segments = 3
rotation = [10.0, 35.0, 0.0]
material = { color = [0.9, 0.6, 0.3], diffuse = 0.9, specular = 0.0 }
"#;
    let scene = common::scene(toml);
    let gouraud = common::draw(&scene, Algorithm::Gouraud, 120, 90);
    let phong = common::draw(&scene, Algorithm::Phong, 120, 90);
    let mut covered = 0;
    for (g, p) in gouraud.pixels.iter().zip(&phong.pixels) {
        // A light 1,000 units away changes N·L by well under 1e-3 across a 3-unit face, so the
        // vertex-lit and pixel-lit colours agree to that tolerance.
        assert!(
            (*g - *p).abs().max_element() < 1e-3,
            "gouraud {g} vs phong {p}"
        );
        covered += (*g != Vec3::ZERO) as usize;
    }
    assert!(
        covered > 1000,
        "the face covers a good part of the image ({covered} pixels)"
    );
}

#[test]
fn one_and_two_threads_give_the_same_bytes() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
        let render_on = |threads: usize| {
            let options = RenderOptions {
                threads: NonZeroUsize::new(threads),
                ..RenderOptions::new(algorithm, 203, 117)
            };
            common::render(&world, &scene.camera, options).0
        };
        let (one, two) = (render_on(1), render_on(2));
        let bits = |f: &rastray::Frame| {
            f.pixels
                .iter()
                .flat_map(|p| p.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(
            bits(&one),
            bits(&two),
            "{algorithm} differs between 1 and 2 threads"
        );
        assert_eq!(one.to_srgb8(), two.to_srgb8());
    }
}

#[test]
fn supersampling_averages_the_samples_of_each_pixel() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let options = RenderOptions {
        samples: 3,
        ..RenderOptions::new(Algorithm::Phong, 40, 30)
    };
    let (smooth, _) = common::render(&world, &scene.camera, options);
    let big = common::draw(&scene, Algorithm::Phong, 120, 90);
    assert_eq!((smooth.width, smooth.height), (40, 30));
    for (x, y) in [(0, 0), (13, 17), (39, 29), (20, 12)] {
        let mut sum = Vec3::ZERO;
        for sy in 0..3 {
            for sx in 0..3 {
                sum += big.pixel(x * 3 + sx, y * 3 + sy);
            }
        }
        assert!((smooth.pixel(x, y) - sum / 9.0).abs().max_element() < 1e-5);
    }
}
