//! A textured quad as a glTF file written by the test, and the scene and options that render
//! it square-on: shared by the texture and alpha tests.

use std::path::{Path, PathBuf};

use base64::Engine;
use base64::engine::general_purpose::STANDARD;
use rastray::Frame;
use rastray::render::{Algorithm, RenderOptions};

/// Writes `bytes` to `name` in a folder of its own (`folder` under the scratch folder).
pub fn write(folder: &str, name: &str, bytes: &[u8]) -> PathBuf {
    let dir = super::scratch().join(folder);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// A glTF file of the quad [-1, 1]² at z = 0 facing +Z, textured with image `uri` through a
/// sampler `sampler` (JSON), `material_extra` added to its material, and `uvs` (glTF's
/// convention: (0, 0) the image's top-left) at the corners (-1, -1), (1, -1), (1, 1), (-1, 1).
pub fn quad_gltf(
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

/// A glTF file of the same quad as [`quad_gltf`], untextured, its white vertex colours
/// (`COLOR_0`, RGBA floats) carrying `alphas` at the corners (-1, -1), (1, -1), (1, 1),
/// (-1, 1), and `material_extra` added to its material.
pub fn vertex_alpha_quad_gltf(alphas: [f32; 4], material_extra: &str) -> String {
    let positions: [[f32; 3]; 4] = [[-1., -1., 0.], [1., -1., 0.], [1., 1., 0.], [-1., 1., 0.]];
    let mut bytes = Vec::new();
    for c in positions.iter().flatten() {
        bytes.extend(c.to_le_bytes());
    }
    for a in alphas {
        for c in [1.0f32, 1.0, 1.0, a] {
            bytes.extend(c.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2, 0, 2, 3] {
        bytes.extend(i.to_le_bytes());
    }
    let data = STANDARD.encode(&bytes);
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"COLOR_0":1}},"indices":2,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"metallicFactor":0.0,"roughnessFactor":1.0}}{material_extra}}}],
"buffers":[{{"byteLength":{len},"uri":"data:application/octet-stream;base64,{data}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":48}},{{"buffer":0,"byteOffset":48,"byteLength":64}},{{"buffer":0,"byteOffset":112,"byteLength":12}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5126,"count":4,"type":"VEC4"}},{{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}}]}}"#,
        len = bytes.len()
    )
}

/// `image` as PNG bytes.
pub fn png_bytes<P>(image: &image::ImageBuffer<P, Vec<P::Subpixel>>) -> Vec<u8>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
{
    let mut bytes = Vec::new();
    image
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    bytes
}

/// The object of `model` with `rest` (its keys) lit by ambient 1 alone, seen square-on from where the quad just fills a 60° view: pixel
/// (i, j)'s centre meets texel (i, j)'s centre.
pub fn scene_of(model: &Path, rest: &str) -> rastray::Scene {
    super::scene(&format!(
        "background = [0.0, 0.0, 0.0]\nambient = 1.0\n[camera]\n\
         position = [0.0, 0.0, {d}]\ntarget = [0.0, 0.0, 0.0]\nfov = 60.0\n[[object]]\n\
         type = \"mesh\"\npath = {:?}\n{rest}\n",
        model.display().to_string(),
        d = 1.0 / 30f32.to_radians().tan(),
    ))
}

pub fn render(scene: &rastray::Scene, algorithm: Algorithm, size: u32, samples: u32) -> Frame {
    let mut options = RenderOptions::new(algorithm, size, size);
    options.shadows = false;
    options.max_depth = Some(0);
    options.samples = samples;
    super::render(&super::world(scene), &scene.camera, options).0
}
