//! The binary PLY reader's fast paths (vertex records of scalars only, faces of three 32-bit
//! indices, decoded in parallel blocks) against the general reader: the same mesh written as
//! ASCII (read only by the general reader) and as binary of both byte orders, in layouts the
//! fast paths take and layouts they refuse or leave part-way (a quad among triangles, 16-bit
//! indices, extra scalars and lists), loads to the same geometry; an index out of range in a
//! fast-path block is reported at its face and byte as the general reader reports it.

mod common;

use common::ply_types::TYPES;
use rastray::mesh::load_ply;

/// A small xorshift generator: the same cases on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

/// `value` (a whole number that fits the type) as the bytes of type `ty`.
fn bytes_of(ty: &str, value: i64, big: bool) -> Vec<u8> {
    let mut b = match ty {
        "char" => vec![value as i8 as u8],
        "uchar" => vec![value as u8],
        "short" => (value as i16).to_le_bytes().to_vec(),
        "ushort" => (value as u16).to_le_bytes().to_vec(),
        "int" => (value as i32).to_le_bytes().to_vec(),
        "uint" => (value as u32).to_le_bytes().to_vec(),
        "float" => (value as f32).to_le_bytes().to_vec(),
        _ => (value as f64).to_le_bytes().to_vec(),
    };
    if big {
        b.reverse();
    }
    b
}

/// One property of a record: a scalar, or a list (count type, item type).
#[derive(Clone)]
enum Prop {
    Scalar(&'static str, &'static str),
    List(&'static str, &'static str, &'static str),
}

/// A mesh and how its file lays it out.
struct Case {
    vertex_props: Vec<Prop>,
    /// Each vertex's values, in `vertex_props` order (scalars only).
    vertices: Vec<Vec<i64>>,
    face_props: Vec<Prop>,
    /// Each face's records: a scalar's value, or a list's items.
    faces: Vec<Vec<Vec<i64>>>,
}

impl Case {
    fn write(&self, format: &str) -> Vec<u8> {
        let big = format == "binary_big_endian";
        let mut header = format!("ply\nformat {format} 1.0\n");
        for (name, props, count) in [
            ("vertex", &self.vertex_props, self.vertices.len()),
            ("face", &self.face_props, self.faces.len()),
        ] {
            header += &format!("element {name} {count}\n");
            for p in props {
                header += &match p {
                    Prop::Scalar(ty, name) => format!("property {ty} {name}\n"),
                    Prop::List(c, i, name) => format!("property list {c} {i} {name}\n"),
                };
            }
        }
        header += "end_header\n";
        let mut out = header.into_bytes();
        let records = self.vertices.iter().map(|v| {
            v.iter()
                .zip(&self.vertex_props)
                .map(|(&x, p)| (p.clone(), vec![x]))
                .collect::<Vec<_>>()
        });
        let faces = self.faces.iter().map(|f| {
            f.iter()
                .cloned()
                .zip(&self.face_props)
                .map(|(x, p)| (p.clone(), x))
                .collect::<Vec<_>>()
        });
        for record in records.chain(faces) {
            let mut words = Vec::new();
            for (p, values) in record {
                match p {
                    Prop::Scalar(ty, _) => {
                        words.push(values[0].to_string());
                        out_extend(&mut out, format, bytes_of(ty, values[0], big));
                    }
                    Prop::List(c, i, _) => {
                        words.push(values.len().to_string());
                        out_extend(&mut out, format, bytes_of(c, values.len() as i64, big));
                        for &v in &values {
                            words.push(v.to_string());
                            out_extend(&mut out, format, bytes_of(i, v, big));
                        }
                    }
                }
            }
            if format == "ascii" {
                out.extend(words.join(" ").into_bytes());
                out.push(b'\n');
            }
        }
        out
    }
}

fn out_extend(out: &mut Vec<u8>, format: &str, bytes: Vec<u8>) {
    if format != "ascii" {
        out.extend(bytes);
    }
}

/// A random mesh of `n_vertices` (positions from a small pool, so some repeat; some unused)
/// and `n_faces` triangles (a quad now and then when `quads`), in a random layout.
fn random_case(rng: &mut Rng, n_vertices: usize, n_faces: usize, quads: bool) -> Case {
    let mut vertex_props = Vec::new();
    for axis in ["x", "y", "z"] {
        let ty = [TYPES[0].0, TYPES[2].0, TYPES[4].0, TYPES[6].0, TYPES[7].0];
        vertex_props.push(Prop::Scalar(ty[rng.below(5) as usize], axis));
    }
    if rng.below(2) == 0 {
        for c in ["red", "green", "blue"] {
            vertex_props.push(Prop::Scalar("uchar", c));
        }
    }
    for name in ["extra0", "extra1", "extra2"]
        .iter()
        .take(rng.below(4) as usize)
    {
        let (ty, _) = TYPES[rng.below(8) as usize];
        vertex_props.push(Prop::Scalar(ty, name));
    }
    // Shuffle the vertex properties.
    for i in (1..vertex_props.len()).rev() {
        vertex_props.swap(i, rng.below(i as u64 + 1) as usize);
    }
    let vertices = (0..n_vertices)
        .map(|_| {
            vertex_props
                .iter()
                .map(|p| match p {
                    Prop::Scalar(_, "red" | "green" | "blue") => rng.below(256) as i64,
                    Prop::Scalar(ty, _) if ty.starts_with('u') => rng.below(3) as i64,
                    _ => rng.below(7) as i64 - 3,
                })
                .collect()
        })
        .collect();
    let count = ["uchar", "char", "ushort", "int", "uint"][rng.below(5) as usize];
    let item = ["int", "uint", "int", "uint", "short"][rng.below(5) as usize];
    let mut face_props = vec![Prop::List(count, item, "vertex_indices")];
    if rng.below(2) == 0 {
        face_props.insert(0, Prop::Scalar("uchar", "flags"));
    }
    if rng.below(2) == 0 {
        face_props.push(Prop::Scalar(TYPES[rng.below(8) as usize].0, "quality"));
    }
    // The vertices from n_vertices / 10 on, the last excepted, are the ones faces use.
    let low = n_vertices as u64 / 10;
    let faces = (0..n_faces)
        .map(|_| {
            let corners = if quads && rng.below(500) == 0 { 4 } else { 3 };
            face_props
                .iter()
                .map(|p| match p {
                    Prop::List(..) => (0..corners)
                        .map(|_| (low + rng.below(n_vertices as u64 - 1 - low)) as i64)
                        .collect(),
                    Prop::Scalar(..) => vec![rng.below(2) as i64],
                })
                .collect()
        })
        .collect();
    Case {
        vertex_props,
        vertices,
        face_props,
        faces,
    }
}

fn load(bytes: &[u8], name: &str) -> Result<rastray::mesh::PlyModel, String> {
    let path = common::scratch().join(name);
    std::fs::write(&path, bytes).unwrap();
    load_ply(&path).map_err(|e| e.to_string())
}

#[test]
fn binary_of_both_byte_orders_loads_as_the_ascii_text_of_the_same_mesh() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    // Small meshes in many layouts; then large ones that span several parallel blocks.
    let sizes = [(40, 60, false); 24]
        .into_iter()
        .chain([(40, 60, true); 8])
        .chain([(20_000, 40_000, false), (20_000, 40_000, true)]);
    for (case_number, (n_vertices, n_faces, quads)) in sizes.enumerate() {
        let mut case = random_case(&mut rng, n_vertices, n_faces, quads);
        if case_number % 2 == 1 {
            // The plain layout scanners write (float x y z, with or without uchar colours),
            // which the fast path decodes straight from the bytes.
            for prop in &mut case.vertex_props {
                if let Prop::Scalar(ty, "x" | "y" | "z") = prop {
                    *ty = "float";
                }
            }
        }
        let ascii = load(&case.write("ascii"), "fast.ply").expect("the ASCII file loads");
        for format in ["binary_little_endian", "binary_big_endian"] {
            let binary = load(&case.write(format), "fast.ply").expect("the binary file loads");
            assert_eq!(
                binary.geometry, ascii.geometry,
                "case {case_number} in {format}"
            );
        }
    }
}

#[test]
fn an_index_out_of_range_in_a_fast_block_names_its_face_and_byte() {
    let mut rng = Rng(7);
    let mut case = random_case(&mut rng, 100, 30_000, false);
    case.face_props = vec![Prop::List("uchar", "int", "vertex_indices")];
    for face in &mut case.faces {
        *face = vec![(0..3).map(|_| rng.below(100) as i64).collect()];
    }
    // The same header (the face count is the same) and vertex records, and no face records.
    let header_and_vertices = Case {
        vertex_props: case.vertex_props.clone(),
        vertices: case.vertices.clone(),
        face_props: case.face_props.clone(),
        faces: vec![Vec::new(); case.faces.len()],
    }
    .write("binary_little_endian")
    .len();
    for (bad, value) in [(20_001, 100), (17, -1), (29_999, 1 << 30)] {
        let mut bad_case = Case {
            vertex_props: case.vertex_props.clone(),
            vertices: case.vertices.clone(),
            face_props: case.face_props.clone(),
            faces: case.faces.clone(),
        };
        bad_case.faces[bad - 1][0][1] = value;
        let err = load(&bad_case.write("binary_little_endian"), "bad.ply").unwrap_err();
        let byte = header_and_vertices + (bad - 1) * 13;
        assert!(
            err.ends_with(&format!(
                "bad.ply at byte {byte}: face {bad} names a vertex out of range (the file has \
                 100 vertices)"
            )),
            "{err}"
        );
    }
}
