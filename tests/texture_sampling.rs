//! Texture sampling through real glTF files, in all three algorithms: the sampler's wrap modes
//! (repeat, clamp, mirror), `KHR_texture_transform`, a JPEG texture and an image embedded as a
//! data URI each render as a reference sampler written here says they should.

mod common;

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use common::textured_quad::{png_bytes, quad_gltf, render, scene_of, write};
use rastray::render::Algorithm;

const ALGORITHMS: [Algorithm; 3] = [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray];

/// Side of the renders, pixels.
const SIDE: u32 = 64;
/// Side of the block texture, texels.
const BLOCKS: u32 = 4;

/// A 4×4 texture of sixteen distinct colours, so that every texel read is told apart.
fn blocks() -> image::RgbImage {
    image::RgbImage::from_fn(BLOCKS, BLOCKS, |x, y| {
        image::Rgb([
            (30 + 60 * x) as u8,
            (30 + 60 * y) as u8,
            (220 - 30 * (x + y)) as u8,
        ])
    })
}

/// glTF's wrap modes by their numbers.
#[derive(Clone, Copy, Debug)]
enum Wrap {
    Repeat = 10497,
    Clamp = 33071,
    Mirror = 33648,
}

/// The texel index integer texel coordinate `i` reads under `wrap`, of `n` texels (OpenGL's
/// rules).
fn wrapped(i: i64, n: i64, wrap: Wrap) -> u32 {
    (match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::Clamp => i.clamp(0, n - 1),
        Wrap::Mirror => {
            let m = i.rem_euclid(2 * n);
            if m >= n { 2 * n - 1 - m } else { m }
        }
    }) as u32
}

/// What a quad filling the view should show (RGB bytes, row-major) when pixel (i, j)'s centre
/// has texture coordinates `uv_at(s, t)`, (s, t) in [0, 1]² from the top-left, read nearest
/// with `wrap` from `image`.
fn expected(
    image: &image::RgbImage,
    wrap: Wrap,
    uv_at: impl Fn(f32, f32) -> (f32, f32),
) -> Vec<u8> {
    let n = image.width() as i64;
    (0..SIDE * SIDE)
        .flat_map(|k| {
            let (s, t) = (
                ((k % SIDE) as f32 + 0.5) / SIDE as f32,
                ((k / SIDE) as f32 + 0.5) / SIDE as f32,
            );
            let (u, v) = uv_at(s, t);
            let x = wrapped((u * n as f32).floor() as i64, n, wrap);
            let y = wrapped((v * n as f32).floor() as i64, n, wrap);
            image.get_pixel(x, y).0
        })
        .collect()
}

/// A sampler of `wrap` on both axes, nearest filtering and no mipmaps.
fn nearest(wrap: Wrap) -> String {
    format!(
        r#"{{"magFilter":9728,"minFilter":9728,"wrapS":{w},"wrapT":{w}}}"#,
        w = wrap as u32
    )
}

/// Renders the glTF text `gltf` (written as `name` in `folder`, whose textures only one test
/// writes) square-on in every algorithm and checks each against `want` (30 dB: a pixel centre
/// within rounding of a texel edge may read its neighbour).
fn renders_as(folder: &str, name: &str, gltf: &str, want: &[u8], what: &str) {
    let model = write(folder, name, gltf.as_bytes());
    for algorithm in ALGORITHMS {
        let got = render(&scene_of(&model, ""), algorithm, SIDE, 1).to_srgb8();
        let psnr = common::psnr(&got, want);
        assert!(psnr >= 30.0, "{what}, {algorithm:?}: {psnr:.1} dB");
    }
}

#[test]
fn repeat_clamp_and_mirror_wrap_coordinates_outside_the_image_as_opengl_does() {
    write("wrap", "blocks.png", &png_bytes(&blocks()));
    // Coordinates from −1 to 2 across and down: three copies of the image's span.
    let uvs = [[-1.0, 2.0], [2.0, 2.0], [2.0, -1.0], [-1.0, -1.0]];
    let spread = |s: f32, t: f32| (3.0 * s - 1.0, 3.0 * t - 1.0);
    let images: Vec<Vec<u8>> = [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror]
        .into_iter()
        .map(|wrap| {
            let gltf = quad_gltf("blocks.png", &nearest(wrap), "", 1.0, uvs);
            let want = expected(&blocks(), wrap, spread);
            renders_as(
                "wrap",
                &format!("{wrap:?}.gltf"),
                &gltf,
                &want,
                &format!("{wrap:?}"),
            );
            want
        })
        .collect();
    // The three answers differ, so each test tells its mode apart.
    assert!(images[0] != images[1] && images[1] != images[2] && images[0] != images[2]);
}

#[test]
fn khr_texture_transform_offsets_and_scales_the_coordinates() {
    write("transform", "blocks.png", &png_bytes(&blocks()));
    let uvs = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let gltf = quad_gltf("blocks.png", &nearest(Wrap::Repeat), "", 1.0, uvs)
        .replacen(
            r#"{"asset":"#,
            r#"{"extensionsUsed":["KHR_texture_transform"],"asset":"#,
            1,
        )
        .replacen(
            r#""baseColorTexture":{"index":0}"#,
            r#""baseColorTexture":{"index":0,"extensions":{"KHR_texture_transform":{"offset":[0.375,0.0],"scale":[2.0,1.5]}}}"#,
            1,
        );
    // uv' = offset + scale·uv.
    let want = expected(&blocks(), Wrap::Repeat, |s, t| (0.375 + 2.0 * s, 1.5 * t));
    renders_as(
        "transform",
        "transformed.gltf",
        &gltf,
        &want,
        "KHR_texture_transform",
    );
    let plain = expected(&blocks(), Wrap::Repeat, |s, t| (s, t));
    assert!(
        common::psnr(&want, &plain) < 20.0,
        "the transform changes the image"
    );
}

/// A smooth image (a gradient in each channel), which JPEG keeps close.
fn gradient() -> image::RgbImage {
    image::RgbImage::from_fn(SIDE, SIDE, |x, y| {
        image::Rgb([
            (40 + 3 * x) as u8,
            (40 + 3 * y) as u8,
            (230 - 2 * (x + y) / 2) as u8,
        ])
    })
}

#[test]
fn a_jpeg_texture_and_a_data_uri_image_render_as_their_images() {
    let image = gradient();
    let mut jpeg = Vec::new();
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut jpeg, 95)
        .encode_image(&image)
        .unwrap();
    write("images", "gradient.jpg", &jpeg);
    let uvs = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let data_uri = format!(
        "data:image/png;base64,{}",
        STANDARD.encode(png_bytes(&image))
    );
    for (uri, name) in [
        ("gradient.jpg", "jpeg.gltf"),
        (data_uri.as_str(), "data_uri.gltf"),
    ] {
        let gltf = quad_gltf(uri, "{}", "", 1.0, uvs);
        renders_as("images", name, &gltf, image.as_raw(), name);
    }
}
