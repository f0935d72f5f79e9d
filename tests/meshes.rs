//! Face-list meshes: face counts, exact radii, outward winding, normals, OBJ import.

mod common;

use std::path::Path;

use glam::Vec3;
use rastray::mesh::{cuboid, icosahedron, load_obj, prism, tessellate, with_normals};
use rastray::scene::{Object, Shape};

fn outward(positions: &[Vec3], triangles: &[[u32; 3]]) -> bool {
    triangles.iter().all(|&[a, b, c]| {
        let (a, b, c) = (
            positions[a as usize],
            positions[b as usize],
            positions[c as usize],
        );
        (b - a).cross(c - a).dot((a + b + c) / 3.0) > 0.0
    })
}

#[test]
fn icosahedron_has_20_times_4_to_the_k_faces_on_its_sphere() {
    for k in 0..=4 {
        let f = icosahedron(2.5, k);
        assert_eq!(f.triangles.len(), 20 * 4usize.pow(k));
        for p in &f.positions {
            assert!(
                (p.length() - 2.5).abs() < 1e-5,
                "vertex {p} is off the sphere"
            );
        }
        assert!(
            outward(&f.positions, &f.triangles),
            "k = {k}: a face winds inward"
        );
    }
    // Euler's formula for the closed, welded subdivision: V − E + F = 2 with E = 3F/2.
    let f = icosahedron(1.0, 3);
    assert_eq!(
        f.positions.len() as i64 - (f.triangles.len() as i64 * 3 / 2) + f.triangles.len() as i64,
        2
    );
}

#[test]
fn boxes_and_prisms_have_12_and_8_faces_times_segments_squared() {
    for s in [1, 2, 5] {
        let b = cuboid(Vec3::new(2.0, 3.0, 4.0), s);
        assert_eq!(b.triangles.len() as u32, 12 * s * s);
        assert!(outward(&b.positions, &b.triangles));
        let p = prism(Vec3::new(2.0, 3.0, 4.0), s);
        assert_eq!(p.triangles.len() as u32, 8 * s * s);
        assert!(outward(&p.positions, &p.triangles));
        // Segments add faces, not area.
        let area = |f: &rastray::mesh::FaceList| {
            with_normals(&f.positions, &f.triangles, false).surface_area()
        };
        assert!((area(&b) - 2.0 * (2.0 * 3.0 + 3.0 * 4.0 + 2.0 * 4.0)).abs() < 1e-3);
        let slope = (1.0f32 + 9.0).sqrt(); // from (±1, −1.5) to (0, 1.5)
        let prism_area = 2.0 * (0.5 * 2.0 * 3.0) + 4.0 * (2.0 + 2.0 * slope);
        assert!(
            (area(&p) - prism_area).abs() < 1e-3,
            "prism area {}",
            area(&p)
        );
    }
}

#[test]
fn faces_of_boxes_and_prisms_share_their_edges_bit_for_bit() {
    // Faces meeting along an edge must give its vertices the same bits, or the Z-buffer and the
    // ray tracer may let a pixel through between them. Over the distinct positions the surface
    // is then closed: V − E + F = 2 with E = 3F/2. Sizes whose lattice steps are not exact in
    // binary, and grids of 3 and more, are where separately computed edges drifted apart.
    for size in [
        Vec3::new(0.8, 0.5, 0.6),
        Vec3::new(2.0, 3.0, 4.0),
        Vec3::new(0.3, 7.1, 1.9),
    ] {
        for s in [1, 2, 3, 5, 7, 16] {
            for faces in [cuboid(size, s), prism(size, s)] {
                let mesh = with_normals(&faces.positions, &faces.triangles, false);
                let distinct = rastray::mesh::UniquePositions::of(&mesh).positions.len() as i64;
                let f = faces.triangles.len() as i64;
                assert_eq!(distinct - f * 3 / 2 + f, 2, "{size} with {s} segments");
            }
        }
    }
}

#[test]
fn flat_normals_are_face_normals_and_smooth_ones_follow_the_sphere() {
    let f = icosahedron(1.0, 3);
    let flat = with_normals(&f.positions, &f.triangles, false);
    assert_eq!(
        flat.positions.len(),
        flat.triangles.len() * 3,
        "flat shading splits vertices per face"
    );
    for t in &flat.triangles {
        let [a, b, c] = t.map(|i| flat.positions[i as usize]);
        let n = (b - a).cross(c - a).normalize();
        assert!(flat.normals[t[0] as usize].distance(n) < 1e-5);
    }
    let smooth = with_normals(&f.positions, &f.triangles, true);
    assert_eq!(
        smooth.positions.len(),
        f.positions.len(),
        "smooth shading keeps vertices welded"
    );
    for (p, n) in smooth.positions.iter().zip(&smooth.normals) {
        assert!(
            n.dot(p.normalize()) > 0.995,
            "smooth normal {n} strays from the radius at {p}"
        );
    }
    // A box's 90° edges exceed the crease angle: smooth shading keeps its faces flat.
    let b = cuboid(Vec3::ONE, 1);
    let smooth_box = with_normals(&b.positions, &b.triangles, true);
    for n in &smooth_box.normals {
        assert!(
            (n.abs().max_element() - 1.0).abs() < 1e-6,
            "box normal {n} was smoothed across an edge"
        );
    }
}

#[test]
fn rotation_turns_the_object_about_its_centre() {
    let mut object = Object::new(Shape::Box {
        center: Vec3::new(5.0, 0.0, 0.0),
        size: Vec3::new(2.0, 1.0, 1.0),
        segments: 1,
    });
    object.rotation = Vec3::new(0.0, 90.0, 0.0);
    let mesh = tessellate(&object, None);
    let (lo, hi) = mesh.bounds().expect("bounds");
    // The 2-unit width now lies along Z; the centre stays put.
    assert!(
        (hi - lo - Vec3::new(1.0, 1.0, 2.0)).abs().max_element() < 1e-5,
        "{lo} {hi}"
    );
    assert!(
        ((lo + hi) / 2.0 - Vec3::new(5.0, 0.0, 0.0))
            .abs()
            .max_element()
            < 1e-5
    );
}

#[test]
fn obj_polygons_are_triangulated_and_missing_normals_computed() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/suzanne.obj");
    let model = load_obj(&path).expect("suzanne loads");
    // 500 faces of which 468 are quads: 32 + 2·468 = 968 triangles.
    assert_eq!(model.triangles.len(), 968);
    assert!(model.corner_normals.is_some(), "suzanne carries normals");

    let dir = tempfile::tempdir().expect("tempdir");
    let quad = dir.path().join("quad.obj");
    std::fs::write(&quad, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").expect("write");
    let model = load_obj(&quad).expect("quad loads");
    assert_eq!(model.triangles.len(), 2);
    assert!(model.corner_normals.is_none());
    let object = Object::new(Shape::Mesh {
        path: quad.clone(),
        position: Vec3::ZERO,
        scale: 1.0,
        up: Default::default(),
        materials: rastray::scene::MaterialSource::File,
    });
    let mesh = tessellate(&object, Some(&model));
    for n in &mesh.normals {
        assert!(n.distance(Vec3::Z) < 1e-6, "computed normal {n}");
    }
}

#[test]
fn an_open_mesh_is_lit_from_both_sides() {
    // The same quad, once facing the camera and once facing away: with the light at the eye
    // both sides must show the same lit colour (the normal flips toward the viewer).
    let scene_for = |yaw: f32| {
        common::scene(&format!(
            r#"
background = [0.0, 0.0, 0.0]
[camera]
position = [0.0, 0.0, 4.0]
[[light]]
position = [0.0, 0.0, 4.0]
[[object]]
type = "mesh"
path = "tests/data/quad_open.obj"
rotation = [0.0, {yaw}, 0.0]
smooth = false
"#
        ))
    };
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    assert!(dir.join("quad_open.obj").exists());
    let front = common::draw(&scene_for(0.0), rastray::Algorithm::Phong, 33, 33);
    let back = common::draw(&scene_for(180.0), rastray::Algorithm::Phong, 33, 33);
    let (f, b) = (front.pixel(16, 16), back.pixel(16, 16));
    assert!(f.max_element() > 0.5, "the front is lit: {f}");
    assert!(
        (f - b).abs().max_element() < 1e-4,
        "front {f} and back {b} differ"
    );
}

/// Writes `text` as an OBJ file and returns the error loading it.
fn obj_error(text: &str) -> (rastray::mesh::ObjError, String) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("bad.obj");
    std::fs::write(&path, text).expect("write");
    let error = load_obj(&path).expect_err("must be refused");
    let message = error.to_string();
    assert!(
        message.starts_with(&path.display().to_string()),
        "the file is named: {message}"
    );
    (error, message)
}

#[test]
fn obj_errors_name_the_file_and_line() {
    use rastray::mesh::ObjProblem;
    let (e, m) = obj_error("v 0 0 0\nv 1 zero 0\nv 0 1 0\nf 1 2 3\n");
    assert!(matches!(e.problem, ObjProblem::Malformed(_)), "{m}");
    assert_eq!(e.line, Some(2), "{m}");

    // A face continued on the next line is refused on its first line, saying so.
    let (e, m) = obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 \\\n  3\n");
    assert_eq!(e.line, Some(4), "{m}");
    assert!(m.contains("after `\\`"), "{m}");
    let (_, m) = obj_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    assert!(m.contains("a face corner is"), "{m}");

    let (e, m) = obj_error("v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
    assert!(
        matches!(e.problem, ObjProblem::NonFiniteVertex { vertex: 3 }),
        "{m}"
    );
    assert!(
        m.contains("bad.obj:3: vertex 3 is not a finite number"),
        "{m}"
    );

    let (e, m) = obj_error("v 0 0 0\nv 1 0 0\n# a comment\nf 1 2 9\nv 0 1 0\n");
    assert!(
        matches!(e.problem, ObjProblem::MissingVertex { index: 9, count: 3 }),
        "{m}"
    );
    assert!(
        m.contains("bad.obj:4: a face names vertex 9, but the file has 3 vertices"),
        "{m}"
    );

    let (e, m) = obj_error("v 0 0 0\nv 1 0 0\nf -3 1 2\n");
    assert!(
        matches!(e.problem, ObjProblem::MissingVertex { index: -3, .. }),
        "{m}"
    );
    assert_eq!(e.line, Some(3));

    let (e, m) = obj_error("v 0 0 0\nv 1 0 0\nl 1 2\n");
    assert!(matches!(e.problem, ObjProblem::NoFaces), "{m}");
    assert!(m.ends_with("bad.obj: the file holds no faces"), "{m}");

    let missing = Path::new("/nonexistent/rastray/model.obj");
    let e = load_obj(missing).expect_err("no such file");
    assert!(matches!(e.problem, ObjProblem::Io(_)), "{e}");
    assert!(
        e.to_string()
            .starts_with("/nonexistent/rastray/model.obj: "),
        "{e}"
    );
}

#[test]
fn vertex_colours_stay_with_their_vertices_and_a_colour_seam_is_no_crease() {
    use rastray::mesh::with_colors_and_normals;
    // Two faces folded 30° along the edge (0,0,0)–(0,1,0), which each face holds with its own
    // colour: the edge's points are given twice.
    let positions = vec![
        Vec3::ZERO,
        Vec3::Y,
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::ZERO,
        Vec3::Y,
        Vec3::new(30f32.to_radians().cos(), 0.0, 30f32.to_radians().sin()),
    ];
    let (red, blue) = (Vec3::X, Vec3::Z);
    let colors = vec![red, red, red, blue, blue, blue];
    let triangles = vec![[2, 0, 1], [3, 5, 4]];
    let smooth = with_colors_and_normals(&positions, &triangles, Some(&colors), true);
    let out = smooth.colors.as_ref().expect("colours kept");
    assert_eq!(out.len(), smooth.positions.len());
    for (t, tri) in smooth.triangles.iter().enumerate() {
        for &v in tri {
            assert_eq!(out[v as usize], [red, blue][t], "triangle {t}'s colour");
        }
    }
    // The edge's two red and two blue vertices share the smoothed normal: no crease there.
    let edge_normals: Vec<Vec3> = (0..smooth.positions.len())
        .filter(|&v| smooth.positions[v].x == 0.0 && smooth.positions[v].z == 0.0)
        .map(|v| smooth.normals[v])
        .collect();
    assert_eq!(edge_normals.len(), 4, "split by colour, never merged");
    assert!(
        edge_normals
            .iter()
            .all(|n| n.distance(edge_normals[0]) < 1e-6)
    );
    let flat = with_colors_and_normals(&positions, &triangles, Some(&colors), false);
    assert_eq!(flat.colors, Some(vec![red, red, red, blue, blue, blue]));
    assert_eq!(
        with_colors_and_normals(&positions, &triangles, None, true).colors,
        None
    );
}
