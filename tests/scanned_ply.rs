//! A real scan: `tests/data/scan/frag_115.ply`, an RGB-D scan of a wall with a painted pattern
//! (Open3D's test data, MIT; see `tests/data/scan/README.md`), 127,229 triangles whose vertices
//! carry the camera's colours as `red green blue` bytes after float normals. The loader must
//! keep every vertex's colour, and all three algorithms must show them.

mod common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use glam::Vec3;
use rastray::Frame;
use rastray::mesh::MeshFile;
use rastray::render::{Algorithm, RenderOptions};

const ALGORITHMS: [Algorithm; 3] = [Algorithm::Gouraud, Algorithm::Phong, Algorithm::Ray];

fn scan_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/scan/frag_115.ply")
}

/// The vertices of the scan read straight from its bytes, independently of rastray's reader:
/// (position, the three colour bytes). The header must be the one the file has: x y z nx ny nz
/// as little-endian floats, then red green blue as uchar.
fn file_vertices(bytes: &[u8]) -> Vec<(Vec3, [u8; 3])> {
    let end = b"end_header\n";
    let body = bytes
        .windows(end.len())
        .position(|w| w == end)
        .expect("a PLY header")
        + end.len();
    let header = std::str::from_utf8(&bytes[..body]).expect("an ASCII header");
    let properties: Vec<&str> = header
        .lines()
        .skip_while(|l| !l.starts_with("element vertex"))
        .skip(1)
        .take_while(|l| l.starts_with("property"))
        .collect();
    assert_eq!(
        properties,
        [
            "property float x",
            "property float y",
            "property float z",
            "property float nx",
            "property float ny",
            "property float nz",
            "property uchar red",
            "property uchar green",
            "property uchar blue",
        ]
    );
    let count: usize = header
        .lines()
        .find_map(|l| l.strip_prefix("element vertex "))
        .and_then(|n| n.trim().parse().ok())
        .expect("a vertex count");
    let record = 6 * 4 + 3;
    bytes[body..body + count * record]
        .chunks_exact(record)
        .map(|r| {
            let f = |i: usize| f32::from_le_bytes(r[4 * i..4 * i + 4].try_into().unwrap());
            (Vec3::new(f(0), f(1), f(2)), [r[24], r[25], r[26]])
        })
        .collect()
}

/// The sRGB transfer function's inverse (IEC 61966-2-1), written out here rather than taken
/// from rastray, so the test checks the reader's decode too.
fn srgb_to_linear(byte: u8) -> f32 {
    let c = byte as f32 / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[test]
fn the_scan_keeps_every_vertex_colour_of_the_file() {
    let path = scan_path();
    let vertices = file_vertices(&std::fs::read(&path).expect("the scan is in tests/data"));
    assert_eq!(vertices.len(), 64_365);
    let model = MeshFile::load(&path).expect("the scan loads");
    assert_eq!(model.triangle_count(), 127_229);
    let geometries = model.geometries();
    assert_eq!(geometries.len(), 1);
    let geometry = geometries[0];
    let colours = geometry
        .colors
        .as_ref()
        .expect("the scan's vertex colours are read");
    assert_eq!(colours.len(), geometry.positions.len());
    let read: HashMap<[u32; 3], Vec3> = geometry
        .positions
        .iter()
        .zip(colours)
        .map(|(p, c)| (p.to_array().map(f32::to_bits), *c))
        .collect();
    // Positions the file gives twice may weld into one vertex, which keeps one of the colours:
    // compare only the positions the file gives once.
    let mut uses: HashMap<[u32; 3], u32> = HashMap::new();
    for (p, _) in &vertices {
        *uses.entry(p.to_array().map(f32::to_bits)).or_default() += 1;
    }
    let mut compared = 0;
    for (p, rgb) in &vertices {
        let key = p.to_array().map(f32::to_bits);
        if uses[&key] > 1 {
            continue;
        }
        let got = read
            .get(&key)
            .expect("every file vertex is a vertex of the model");
        let expected = Vec3::from_array(rgb.map(srgb_to_linear));
        // Tolerance: the two decodes differ only in f32 rounding.
        assert!(
            (*got - expected).abs().max_element() < 1e-5,
            "vertex at {p}: read {got}, the file says {rgb:?} (linear {expected})"
        );
        compared += 1;
    }
    assert!(compared > 60_000, "compared {compared} vertices");
}

/// The scan in white, lit by ambient 1 alone, filling most of a square view: every algorithm's
/// pixel is the interpolated vertex colour.
fn render(algorithm: Algorithm, size: u32) -> Frame {
    let scene = common::scene(&format!(
        "background = [0.0, 0.0, 0.0]\nambient = 1.0\n[camera]\nposition = [0.0, 0.0, 1.6]\n\
         target = [0.0, 0.0, 0.0]\nfov = 60.0\n[[object]]\ntype = \"mesh\"\npath = {:?}\n\
         material = {{ color = [1.0, 1.0, 1.0] }}\n",
        scan_path().display().to_string()
    ));
    let mut options = RenderOptions::new(algorithm, size, size);
    options.shadows = false;
    options.max_depth = Some(0);
    common::render(&common::world(&scene), &scene.camera, options).0
}

#[test]
fn the_scan_shows_its_wall_and_its_paint_alike_in_all_three_algorithms() {
    let size = 128;
    let frames = ALGORITHMS.map(|a| render(a, size));
    for (algorithm, frame) in ALGORITHMS.iter().zip(&frames) {
        let (mut covered, mut wall, mut paint) = (0, 0, 0);
        for j in 0..size {
            for i in 0..size {
                let [r, g, b] = frame.pixel(i, j).to_array();
                if r + g + b == 0.0 {
                    continue;
                }
                covered += 1;
                // The wall: lit and greyish (its channels within half of the largest). The
                // paint: yellow-green, blue well below red and green. A reader that dropped
                // the colours would show white alone.
                let (low, high) = (r.min(g).min(b), r.max(g).max(b));
                if low > 0.1 && high - low < 0.5 * high {
                    wall += 1;
                }
                if g > 2.0 * b && r > 1.5 * b {
                    paint += 1;
                }
            }
        }
        assert!(
            covered > size * size / 3,
            "{algorithm:?}: covered {covered}"
        );
        assert!(
            wall > covered / 2,
            "{algorithm:?}: wall {wall} of {covered}"
        );
        assert!(
            paint > covered / 50,
            "{algorithm:?}: paint {paint} of {covered}"
        );
        assert!(
            paint < covered / 4,
            "{algorithm:?}: paint {paint} of {covered}"
        );
    }
    // Gouraud and Phong interpolate the same vertex colours over the same coverage; the ray
    // tracer meets the same triangles at the pixel centres.
    let bytes = frames.each_ref().map(|f| f.to_srgb8());
    for (a, b) in [(0, 1), (1, 2), (0, 2)] {
        let db = common::psnr(&bytes[a], &bytes[b]);
        assert!(
            db >= 40.0,
            "{:?} and {:?} agree at {db:.1} dB",
            ALGORITHMS[a],
            ALGORITHMS[b]
        );
    }
}
