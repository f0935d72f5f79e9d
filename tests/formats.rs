//! STL and PLY import: known answers on tiny handwritten files, the files Blender's exporters
//! write, and the same mesh written in every format drawing the same pixels.

mod common;

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3};
use rastray::mesh::{
    MeshFile, ModelGeometry, PlyEncoding, StlEncoding, icosahedron, load_ply, load_stl,
};
use rastray::render::{Algorithm, RenderOptions};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// Writes `bytes` to a file called `name` in the scratch folder.
fn file(name: &str, bytes: &[u8]) -> PathBuf {
    let path = common::scratch().join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

/// A binary STL of `triangles` with `header` (padded to 80 bytes).
fn binary_stl(header: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
    let mut bytes = header.to_vec();
    bytes.resize(80, b' ');
    bytes.extend((triangles.len() as u32).to_le_bytes());
    for t in triangles {
        bytes.extend([0f32, 0.0, 1.0].iter().flat_map(|c| c.to_le_bytes()));
        for corner in t {
            bytes.extend(corner.iter().flat_map(|c| c.to_le_bytes()));
        }
        bytes.extend([0, 0]);
    }
    bytes
}

const SQUARE: [[[f32; 3]; 3]; 2] = [
    [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
    [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
];

/// The corners of each triangle, as positions.
fn corners(g: &ModelGeometry) -> Vec<[Vec3; 3]> {
    g.triangles
        .iter()
        .map(|t| t.map(|i| g.positions[i as usize]))
        .collect()
}

#[test]
fn a_binary_stl_whose_header_begins_with_solid_is_read_as_binary_and_welded() {
    let path = file(
        "solid_header.stl",
        &binary_stl(b"solid  exported by a CAD program", &SQUARE),
    );
    let model = load_stl(&path).expect("loads");
    assert_eq!(model.encoding, StlEncoding::Binary);
    assert_eq!(model.geometry.triangles.len(), 2);
    assert_eq!(
        model.geometry.positions.len(),
        4,
        "the shared edge is welded"
    );
    assert_eq!(
        corners(&model.geometry),
        SQUARE.map(|t| t.map(Vec3::from_array)).to_vec()
    );
    assert!(
        model.geometry.corner_normals.is_none(),
        "facet normals are not read"
    );
}

#[test]
fn every_solid_of_an_ascii_stl_is_read() {
    let text = "solid first\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n\
                vertex 0 1 0\n  endloop\n endfacet\nendsolid first\n\
                SOLID second\r\n FACET NORMAL 0 0 1\r\n OUTER LOOP\r\n VERTEX 1 0 0\r\n\
                VERTEX 1 1 0\r\n VERTEX 0 1 0\r\n ENDLOOP\r\n ENDFACET\r\nENDSOLID second\r\n";
    let model = load_stl(&file("two_solids.stl", text.as_bytes())).expect("loads");
    assert_eq!(model.encoding, StlEncoding::Ascii);
    assert_eq!(
        corners(&model.geometry),
        SQUARE.map(|t| t.map(Vec3::from_array)).to_vec()
    );
    assert_eq!(model.geometry.positions.len(), 4);
}

#[test]
fn negative_zero_welds_with_zero() {
    let mut square = SQUARE;
    square[1][2] = [-0.0, 1.0, -0.0];
    let model = load_stl(&file("negative_zero.stl", &binary_stl(b"", &square))).expect("loads");
    assert_eq!(model.geometry.positions.len(), 4);
}

/// A big-endian PLY with the vertex properties out of the usual order and of mixed types
/// (double z, short x, float y, colour bytes between them), an unknown element with a list
/// between vertices and faces, and faces with a property before their `vertex_index` list:
/// a quad and a triangle.
fn odd_big_endian_ply() -> Vec<u8> {
    let mut bytes = b"ply\nformat binary_big_endian 1.0\ncomment TextureFile wood grain.png\n\
        element vertex 5\nproperty double z\nproperty short x\nproperty uchar red\n\
        property float y\nproperty uchar green\nproperty uchar blue\nproperty float s\n\
        property float t\n\
        element edge 2\nproperty list ushort int32 vertices\nproperty float weight\n\
        element face 2\nproperty uchar flags\nproperty list uint8 uint vertex_index\n\
        end_header\n"
        .to_vec();
    let vertices: [(f64, i16, u8, f32, u8, u8); 5] = [
        (0.5, 0, 0, 0.0, 0, 0),
        (0.5, 2, 255, 0.0, 128, 0),
        (0.5, 2, 255, 3.0, 255, 255),
        (0.5, 0, 0, 3.0, 64, 255),
        (-1.0, -4, 10, 2.5, 20, 30),
    ];
    for (i, (z, x, r, y, g, b)) in vertices.into_iter().enumerate() {
        bytes.extend(z.to_be_bytes());
        bytes.extend(x.to_be_bytes());
        bytes.push(r);
        bytes.extend(y.to_be_bytes());
        bytes.extend([g, b]);
        bytes.extend((i as f32 * 0.25).to_be_bytes());
        bytes.extend(0.75f32.to_be_bytes());
    }
    for list in [&[0i32, 1, 2][..], &[4]] {
        bytes.extend((list.len() as u16).to_be_bytes());
        bytes.extend(list.iter().flat_map(|i| i.to_be_bytes()));
        bytes.extend(1.5f32.to_be_bytes());
    }
    bytes.extend([7, 4]);
    bytes.extend([0u32, 1, 2, 3].iter().flat_map(|i| i.to_be_bytes()));
    bytes.extend([0, 3]);
    bytes.extend([0u32, 3, 4].iter().flat_map(|i| i.to_be_bytes()));
    bytes
}

#[test]
fn a_big_endian_ply_with_odd_property_order_and_mixed_types_reads_as_written() {
    let model = load_ply(&file("odd.ply", &odd_big_endian_ply())).expect("loads");
    assert_eq!(model.encoding, PlyEncoding::BinaryBigEndian);
    assert_eq!(model.texture.as_deref(), Some("wood grain.png"));
    let g = &model.geometry;
    // The quad fans into two triangles, then the triangle.
    assert_eq!(g.triangles.len(), 3);
    let expected = [
        [(0.0, 0.0, 0.5), (2.0, 0.0, 0.5), (2.0, 3.0, 0.5)],
        [(0.0, 0.0, 0.5), (2.0, 3.0, 0.5), (0.0, 3.0, 0.5)],
        [(0.0, 0.0, 0.5), (0.0, 3.0, 0.5), (-4.0, 2.5, -1.0)],
    ];
    let expected: Vec<[Vec3; 3]> = expected
        .iter()
        .map(|t| t.map(|(x, y, z)| Vec3::new(x, y, z)))
        .collect();
    assert_eq!(corners(g), expected);
    // Colours: sRGB bytes decoded to linear, one per position.
    let colors = g.colors.as_ref().expect("colours");
    let color_of = |p: Vec3| colors[g.positions.iter().position(|&q| q == p).unwrap()];
    assert_eq!(color_of(Vec3::new(0.0, 0.0, 0.5)), Vec3::ZERO);
    let half = color_of(Vec3::new(2.0, 0.0, 0.5));
    assert_eq!(half.x, 1.0);
    assert!((half.y - 0.215_860_5).abs() < 1e-6, "sRGB 128 → {}", half.y);
    assert_eq!(color_of(Vec3::new(2.0, 3.0, 0.5)), Vec3::ONE);
    // Texture coordinates per corner, v flipped: (s, 1 − t).
    let uvs = g.corner_uvs.as_ref().expect("uvs");
    assert_eq!(
        uvs[0],
        [
            Vec2::new(0.0, 0.25),
            Vec2::new(0.25, 0.25),
            Vec2::new(0.5, 0.25)
        ]
    );
}

#[test]
fn ascii_ply_quads_fan_and_float_colours_are_srgb_too() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                property float z\nproperty float red\nproperty float green\nproperty float blue\n\
                element face 1\nproperty list uchar int vertex_indices\nend_header\n\
                0 0 0 0.5 0 1\n1 0 0 0.5 0 1\n\n1 1 0 0.5 0 1\n0 1 0 0.5 0 1\n4 0 1 2 3\n";
    let model = load_ply(&file("quad.ply", text.as_bytes())).expect("loads");
    assert_eq!(model.encoding, PlyEncoding::Ascii);
    assert_eq!(model.geometry.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    let colors = model.geometry.colors.expect("colours");
    assert!((colors[0].x - 0.214_041_1).abs() < 1e-6, "{}", colors[0].x);
    assert_eq!(colors[0].z, 1.0);
}

#[test]
fn blenders_stl_files_read_as_the_same_cube() {
    let binary = load_stl(&data("stl/cube_binary.stl")).expect("binary");
    let ascii = load_stl(&data("stl/cube_ascii.stl")).expect("ascii");
    assert_eq!(binary.encoding, StlEncoding::Binary);
    assert_eq!(ascii.encoding, StlEncoding::Ascii);
    for model in [&binary, &ascii] {
        assert_eq!(model.geometry.triangles.len(), 12);
        assert_eq!(model.geometry.positions.len(), 8);
        assert_eq!(model.geometry.bounds(), (Vec3::splat(-1.0), Vec3::ONE));
    }
    assert_eq!(corners(&binary.geometry), corners(&ascii.geometry));
    let suzanne = load_stl(&data("stl/suzanne_binary.stl")).expect("suzanne");
    assert_eq!(suzanne.geometry.triangles.len(), 968);
    // Blender's Suzanne has 507 vertices, two pairs of them at the same place: welded.
    assert_eq!(suzanne.geometry.positions.len(), 505);
}

#[test]
fn blenders_ply_files_give_colours_uvs_and_normals() {
    let ascii = load_ply(&data("ply/cube_colors_ascii.ply")).expect("ascii");
    let binary = load_ply(&data("ply/cube_colors_binary.ply")).expect("binary");
    assert_eq!(binary.encoding, PlyEncoding::BinaryLittleEndian);
    // The ASCII file rounds the normals to six decimals; the rest agrees exactly.
    let (a, g) = (&ascii.geometry, &binary.geometry);
    assert_eq!(
        (&a.positions, &a.triangles, &a.colors, &a.corner_uvs),
        (&g.positions, &g.triangles, &g.colors, &g.corner_uvs)
    );
    assert_eq!(g.triangles.len(), 12);
    assert!(g.corner_uvs.is_some() && g.corner_normals.is_some());
    // Blender wrote each corner's colour as its position mapped to 0..1, in sRGB bytes.
    let colors = g.colors.as_ref().expect("colours");
    for (p, c) in g.positions.iter().zip(colors) {
        let expected = ((*p + 1.0) / 2.0).round();
        assert_eq!(*c, expected, "at {p}");
    }
    let plain = load_ply(&data("ply/cube_plain_binary.ply")).expect("plain");
    assert!(plain.geometry.colors.is_none() && plain.geometry.corner_uvs.is_none());
    assert_eq!(plain.geometry.positions.len(), 8);
    let suzanne = load_ply(&data("ply/suzanne_ascii.ply")).expect("suzanne");
    assert_eq!(suzanne.geometry.triangles.len(), 968);
}

#[test]
fn models_are_known_by_content_without_an_extension() {
    let bytes = std::fs::read(data("ply/cube_plain_binary.ply")).unwrap();
    let ply = MeshFile::load(&file("cube_without_extension", &bytes)).expect("PLY");
    assert_eq!(ply.format(), "PLY binary_little_endian");
    let stl = MeshFile::load(&file("part", &binary_stl(b"solid", &SQUARE))).expect("STL");
    assert_eq!(stl.format(), "STL binary");
    assert!(stl.flat_by_default());
    let refused = MeshFile::load(&file("noise.dat", &[1, 2, 3, 0, 255])).unwrap_err();
    assert!(
        refused
            .to_string()
            .contains("noise.dat: not a model file: OBJ, STL, PLY"),
        "{refused}"
    );
}

/// An icosphere written as OBJ, binary STL, ASCII STL and PLY (ASCII, and binary in both byte
/// orders); every number written so that it reads back to the same bits.
fn same_mesh_in_every_format(dir: &Path) -> Vec<PathBuf> {
    let faces = icosahedron(1.0, 2);
    let (p, t) = (&faces.positions, &faces.triangles);
    let corner = |i: u32| p[i as usize];
    let mut obj = String::new();
    for v in p {
        obj += &format!("v {:?} {:?} {:?}\n", v.x, v.y, v.z);
    }
    for f in t {
        obj += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    let triangles: Vec<[[f32; 3]; 3]> = t.iter().map(|f| f.map(|i| corner(i).to_array())).collect();
    let mut ascii_stl = "solid ico\n".to_string();
    for f in &triangles {
        ascii_stl += "facet normal 0 0 0\nouter loop\n";
        for v in f {
            ascii_stl += &format!("vertex {:?} {:?} {:?}\n", v[0], v[1], v[2]);
        }
        ascii_stl += "endloop\nendfacet\n";
    }
    ascii_stl += "endsolid ico\n";
    let header = |format: &str| {
        format!(
            "ply\nformat {format} 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
             property float z\nelement face {}\nproperty list uchar uint vertex_indices\n\
             end_header\n",
            p.len(),
            t.len()
        )
    };
    let mut ascii_ply = header("ascii");
    for v in p {
        ascii_ply += &format!("{:?} {:?} {:?}\n", v.x, v.y, v.z);
    }
    for f in t {
        ascii_ply += &format!("3 {} {} {}\n", f[0], f[1], f[2]);
    }
    let binary_ply = |big: bool| {
        let mut bytes = header(if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        })
        .into_bytes();
        let word = |x: [u8; 4]| {
            if big {
                let mut x = x;
                x.reverse();
                x
            } else {
                x
            }
        };
        for v in p {
            bytes.extend(v.to_array().iter().flat_map(|c| word(c.to_le_bytes())));
        }
        for f in t {
            bytes.push(3);
            bytes.extend(f.iter().flat_map(|i| word(i.to_le_bytes())));
        }
        bytes
    };
    let files: [(&str, Vec<u8>); 6] = [
        ("ico.obj", obj.into_bytes()),
        ("ico_binary.stl", binary_stl(b"ico", &triangles)),
        ("ico_ascii.stl", ascii_stl.into_bytes()),
        ("ico_ascii.ply", ascii_ply.into_bytes()),
        ("ico_le.ply", binary_ply(false)),
        ("ico_be.ply", binary_ply(true)),
    ];
    files
        .into_iter()
        .map(|(name, bytes)| {
            let path = dir.join(name);
            std::fs::write(&path, bytes).expect("write");
            path
        })
        .collect()
}

#[test]
fn the_same_mesh_in_any_format_covers_the_same_pixels() {
    let dir = tempfile::tempdir().expect("tempdir");
    let mut reference: Option<(usize, Vec<f32>, Vec<Vec3>)> = None;
    for path in same_mesh_in_every_format(dir.path()) {
        let model = MeshFile::load(&path).unwrap_or_else(|e| panic!("{e}"));
        let scene = common::scene(&format!(
            "[camera]\nposition = [0.4, 0.5, 3.0]\nfov = 45.0\n[[light]]\n\
             position = [2.0, 3.0, 4.0]\n[[object]]\ntype = \"mesh\"\npath = {:?}\n\
             smooth = false\n",
            path.display().to_string()
        ));
        let mut options = RenderOptions::new(Algorithm::Phong, 64, 48);
        options.alpha = true;
        let (frame, _) = common::render(&common::world(&scene), &scene.camera, options);
        let alpha = frame.alpha.clone().expect("alpha");
        assert!(alpha.iter().any(|&a| a > 0.0), "{}: drawn", path.display());
        let name = path.display().to_string();
        match &reference {
            None => reference = Some((model.triangle_count(), alpha, frame.pixels)),
            Some((triangles, mask, pixels)) => {
                assert_eq!(model.triangle_count(), *triangles, "{name}");
                assert_eq!(&alpha, mask, "{name}: the same coverage");
                assert_eq!(&frame.pixels, pixels, "{name}: the same pixels");
            }
        }
    }
}

#[test]
fn face_texcoords_give_each_corner_its_uv_and_a_list_after_the_indices_leaves_them_be() {
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
                property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
                property list uchar float texcoord\nproperty list uchar int other\nend_header\n\
                0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3 8 0 0 1 0 1 1 0 1 2 7 7\n";
    let model = load_ply(&file("texcoord.ply", text.as_bytes())).expect("loads");
    assert_eq!(model.geometry.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    let uv = Vec2::new;
    assert_eq!(
        model.geometry.corner_uvs.expect("uvs"),
        vec![
            [uv(0.0, 1.0), uv(1.0, 1.0), uv(1.0, 0.0)],
            [uv(0.0, 1.0), uv(1.0, 0.0), uv(0.0, 0.0)]
        ]
    );
}
