//! Textures in all three algorithms: a textured quad renders as its image (from glTF and from
//! PLY, whose UV origins differ), Phong and the ray tracer agree on textured models, mipmaps
//! tame a grazing checker plane, and textures that cannot be read are warned about by name.

mod common;

use common::textured_quad::{png_bytes, quad_gltf, render, scene_of, write};

use std::path::{Path, PathBuf};

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use rastray::render::Algorithm;

const ALGORITHMS: [Algorithm; 3] = [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray];

/// Side of the test image and of the known-answer renders, pixels.
const SIDE: u32 = 64;

/// An asymmetric image: a red gradient left to right, a green one top to bottom, and a black
/// letter F (upright, facing right) whose flips in either axis read differently.
fn letter_image() -> image::RgbImage {
    image::RgbImage::from_fn(SIDE, SIDE, |x, y| {
        let stem = (16..24).contains(&x) && (12..52).contains(&y);
        let top = (16..48).contains(&x) && (12..20).contains(&y);
        let bar = (16..40).contains(&x) && (28..34).contains(&y);
        if stem || top || bar {
            image::Rgb([0, 0, 0])
        } else {
            image::Rgb([(40 + 3 * x) as u8, (40 + 3 * y) as u8, 90])
        }
    })
}

/// An ASCII PLY of the same quad, textured by `comment TextureFile texture`, with PLY's UVs
/// ((0, 0) the image's bottom-left).
fn quad_ply(texture: &str) -> String {
    format!(
        "ply\nformat ascii 1.0\ncomment TextureFile {texture}\nelement vertex 4\n\
         property float x\nproperty float y\nproperty float z\nproperty float s\nproperty float t\n\
         element face 1\nproperty list uchar int vertex_indices\nend_header\n\
         -1 -1 0 0 0\n1 -1 0 1 0\n1 1 0 1 1\n-1 1 0 0 1\n4 0 1 2 3\n"
    )
}

/// An OBJ of the same quad with its MTL library, whose material is white and textured by
/// `texture` (`map_Kd`), with OBJ's UVs ((0, 0) the image's bottom-left): (OBJ, MTL).
fn quad_obj(texture: &str) -> (String, String) {
    (
        "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n\
         vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl letter\nf 1/1 2/2 3/3 4/4\n"
            .to_string(),
        format!("newmtl letter\nKd 1 1 1\nKs 0 0 0\nmap_Kd {texture}\n"),
    )
}

/// `image` upside down.
fn flipped(image: &image::RgbImage) -> Vec<u8> {
    image::imageops::flip_vertical(image).into_raw()
}

#[test]
fn a_textured_quad_renders_as_its_image_upright_from_gltf_ply_and_obj_in_every_algorithm() {
    let image = letter_image();
    let png = png_bytes(&image);
    write("quad", "letter.png", &png);
    let gltf = quad_gltf(
        "letter.png",
        "{}",
        "",
        1.0,
        [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
    );
    let gltf = write("quad", "quad.gltf", gltf.as_bytes());
    let ply = write("quad", "quad.ply", quad_ply("letter.png").as_bytes());
    let (obj, mtl) = quad_obj("letter.png");
    let obj = write("quad", "quad.obj", obj.as_bytes());
    write("quad", "quad.mtl", mtl.as_bytes());
    // glTF's and the MTL's materials are white; a PLY has none, so the object's is made white
    // and the file's texture kept (`materials = "file"`).
    let white = "material = { color = [1.0, 1.0, 1.0] }\nmaterials = \"file\"";
    for (model, material) in [(gltf, ""), (ply, white), (obj, "")] {
        let scene = scene_of(&model, material);
        for algorithm in ALGORITHMS {
            let got = render(&scene, algorithm, SIDE, 1).to_srgb8();
            let upright = common::psnr(&got, image.as_raw());
            let upside_down = common::psnr(&got, &flipped(&image));
            // 30 dB: the texels sampled at their centres come back through the sRGB decode and
            // encode within a code value or two.
            assert!(
                upright >= 30.0,
                "{algorithm:?} from {}: {upright:.1} dB against the image",
                model.display()
            );
            // The check that catches a flipped V: the image upside down is far from the render.
            assert!(
                upside_down < 20.0,
                "{algorithm:?} from {}: {upside_down:.1} dB against the flipped image",
                model.display()
            );
        }
    }
}

/// Where the Khronos sample models are: `../shared/models/gltf` beside the project.
fn sample_model(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/models/gltf")
        .join(name)
}

#[test]
fn phong_and_the_ray_tracer_agree_on_the_textured_duck_and_box() {
    // In perspective and in an orthographic view, where the footprint is one fixed width.
    let projections = ["fov = 40.0", "projection = \"orthographic\"\nheight = 2.5"];
    for (name, projection) in ["Duck.glb", "BoxTextured.glb"]
        .into_iter()
        .flat_map(|name| projections.map(|p| (name, p)))
    {
        let model = sample_model(name);
        let scene = common::scene(&format!(
            "background = [0.0, 0.0, 0.0]\nambient = 0.2\n[[light]]\nposition = [2.0, 3.0, 4.0]\n\
             intensity = 0.8\n[camera]\nposition = [1.2, 1.0, 3.0]\n\
             target = [0.0, 0.0, 0.0]\n{projection}\n[[object]]\ntype = \"mesh\"\npath = {:?}\n",
            model.display().to_string()
        ));
        let phong = render(&scene, Algorithm::Phong, 160, 1).to_srgb8();
        let ray = render(&scene, Algorithm::Ray, 160, 1).to_srgb8();
        let psnr = common::psnr(&phong, &ray);
        eprintln!("{name} ({projection}): Phong against ray tracing {psnr:.1} dB");
        assert!(
            psnr >= 40.0,
            "{name} ({projection}): Phong against ray tracing {psnr:.1} dB"
        );
    }
}

/// A checker of 8-texel squares, 256 texels a side.
fn checker() -> image::RgbImage {
    image::RgbImage::from_fn(256, 256, |x, y| {
        if (x / 8 + y / 8) % 2 == 0 {
            image::Rgb([230, 230, 230])
        } else {
            image::Rgb([20, 20, 20])
        }
    })
}

#[test]
fn mipmaps_bring_a_grazing_checker_plane_closer_to_its_supersampled_render() {
    write("checker", "checker.png", &png_bytes(&checker()));
    // The quad laid flat below the eye, 40 units a side, the texture repeated 16 times.
    let uvs = [[0.0, 16.0], [16.0, 16.0], [16.0, 0.0], [0.0, 0.0]];
    let psnr_of = |sampler: &str, file: &str| {
        let gltf = quad_gltf("checker.png", sampler, "", 20.0, uvs);
        let model = write("checker", file, gltf.as_bytes());
        let scene = common::scene(&format!(
            "background = [0.0, 0.0, 0.0]\nambient = 1.0\n[camera]\nposition = [0.0, -19.0, 1.0]\n\
             target = [0.0, 20.0, 0.0]\nfov = 50.0\n[[object]]\ntype = \"mesh\"\npath = {:?}\n",
            model.display().to_string()
        ));
        let algorithm = Algorithm::Phong;
        let one = render(&scene, algorithm, 96, 1).to_srgb8();
        let eight = render(&scene, algorithm, 96, 8).to_srgb8();
        common::psnr(&one, &eight)
    };
    // LINEAR minification reads level 0 only; the default sampler is trilinear.
    let before = psnr_of(r#"{"minFilter":9729}"#, "flat.gltf");
    let after = psnr_of("{}", "mipmapped.gltf");
    eprintln!(
        "grazing checker, 1x1 against 8x8 samples: {before:.1} dB without mipmaps, {after:.1} dB with"
    );
    assert!(
        after > before + 3.0,
        "{before:.1} dB without mipmaps, {after:.1} dB with"
    );
}

/// The CRC-32 of a PNG chunk (its type and data).
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[test]
fn a_missing_or_absurd_texture_is_a_warning_that_names_it_and_the_model_draws_untextured() {
    // A PNG whose header declares 100000×100000: refused from the header.
    let mut huge = png_bytes(&image::RgbImage::new(1, 1));
    huge[16..20].copy_from_slice(&100_000u32.to_be_bytes());
    huge[20..24].copy_from_slice(&100_000u32.to_be_bytes());
    let crc = crc32(&huge[12..29]);
    huge[29..33].copy_from_slice(&crc.to_be_bytes());
    write("bad", "huge.png", &huge);
    for (texture, expected) in [
        ("missing.png", "texture missing.png: "),
        ("huge.png", "100000×100000"),
    ] {
        let ply = write(
            "bad",
            &format!("{texture}.ply"),
            quad_ply(texture).as_bytes(),
        );
        let model = rastray::mesh::MeshFile::load(&ply).unwrap();
        let warnings: Vec<String> = model.warnings().iter().map(|w| w.to_string()).collect();
        assert!(
            warnings.len() == 1 && warnings[0].contains(expected) && warnings[0].contains(texture),
            "{warnings:?}"
        );
        let scene = scene_of(&ply, "");
        let world = common::world(&scene);
        assert!(world.objects.iter().all(|o| !o.is_textured()));
    }
}

#[test]
fn info_lists_each_gltf_parts_texture_by_name_with_its_size() {
    let png = png_bytes(&letter_image());
    write("info", "letter.png", &png);
    let uvs = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
    let by_uri = quad_gltf("letter.png", "{}", "", 1.0, uvs);
    // The same image embedded, under a name of its own.
    let data_uri = format!("data:image/png;base64,{}", STANDARD.encode(&png));
    let named = quad_gltf(&data_uri, "{}", "", 1.0, uvs).replacen(
        r#""images":[{"uri""#,
        r#""images":[{"name":"letter","uri""#,
        1,
    );
    let folder = write("info", "by_uri.gltf", by_uri.as_bytes());
    write("info", "named.gltf", named.as_bytes());
    let folder = folder.parent().unwrap();
    for (model, expected) in [
        ("by_uri.gltf", "texture letter.png 64×64"),
        ("named.gltf", "texture letter (data URI) 64×64"),
    ] {
        let o = common::rastray_in(&["info", model], folder);
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{model}: {stdout}");
        let part = stdout
            .lines()
            .find(|l| l.contains("primitive 0"))
            .unwrap_or_else(|| panic!("{model}: no part line in {stdout}"));
        assert!(part.contains(expected), "{model}: {part}");
    }
}
