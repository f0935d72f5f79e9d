//! Textures in all three algorithms: a textured quad renders as its image (from glTF and from
//! PLY, whose UV origins differ), Phong and the ray tracer agree on textured models, mipmaps
//! tame a grazing checker plane, and textures that cannot be read are warned about by name.

mod common;

use std::path::{Path, PathBuf};

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use rastray::Frame;
use rastray::render::{Algorithm, RenderOptions};

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

/// Writes `bytes` to `name` in a folder of its own (`folder` under the scratch folder).
fn write(folder: &str, name: &str, bytes: &[u8]) -> PathBuf {
    let dir = common::scratch().join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// A glTF file of the quad [-1, 1]² at z = 0 facing +Z, textured with image `uri` through a
/// sampler `sampler` (JSON), `material_extra` added to its material, and `uvs` (glTF's
/// convention: (0, 0) the image's top-left) at the corners (-1, -1), (1, -1), (1, 1), (-1, 1).
fn quad_gltf(
    uri: &str,
    sampler: &str,
    material_extra: &str,
    scale: f32,
    uvs: [[f32; 2]; 4],
) -> String {
    let positions: [[f32; 3]; 4] = [[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]];
    let mut bytes = Vec::new();
    for p in positions {
        for c in p {
            bytes.extend((c * scale).to_le_bytes());
        }
    }
    for uv in uvs {
        for c in uv {
            bytes.extend(c.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bytes.extend(i.to_le_bytes());
    }
    let data = STANDARD.encode(&bytes);
    let s = scale;
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"TEXCOORD_0":1}},"indices":2,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"baseColorTexture":{{"index":0}},"metallicFactor":0.0,"roughnessFactor":1.0}}{material_extra}}}],
"textures":[{{"source":0,"sampler":0}}],"samplers":[{sampler}],"images":[{{"uri":"{uri}"}}],
"buffers":[{{"byteLength":{len},"uri":"data:application/octet-stream;base64,{data}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":32}},{{"buffer":0,"byteOffset":80,"byteLength":12}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-{s},-{s},0],"max":[{s},{s},0]}},
{{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"}},{{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}}]}}"#,
        len = bytes.len()
    )
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

/// The object of `model` with `rest` (its keys) lit by ambient 1 alone, seen square-on from where the quad just fills a 60° view: pixel
/// (i, j)'s centre meets texel (i, j)'s centre.
fn scene_of(model: &Path, rest: &str) -> rastray::Scene {
    common::scene(&format!(
        "background = [0.0, 0.0, 0.0]\nambient = 1.0\n[camera]\n\
         position = [0.0, 0.0, {d}]\ntarget = [0.0, 0.0, 0.0]\nfov = 60.0\n[[object]]\n\
         type = \"mesh\"\npath = {:?}\n{rest}\n",
        model.display().to_string(),
        d = 1.0 / 30f32.to_radians().tan(),
    ))
}

fn render(scene: &rastray::Scene, algorithm: Algorithm, size: u32, samples: u32) -> Frame {
    let mut options = RenderOptions::new(algorithm, size, size);
    options.shadows = false;
    options.max_depth = Some(0);
    options.samples = samples;
    common::render(&common::world(scene), &scene.camera, options).0
}

/// `image` upside down.
fn flipped(image: &image::RgbImage) -> Vec<u8> {
    image::imageops::flip_vertical(image).into_raw()
}

fn png_bytes(image: &image::RgbImage) -> Vec<u8> {
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
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
