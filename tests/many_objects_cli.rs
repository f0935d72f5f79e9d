//! A scene of many objects through the command line: 1,000 boxes, each its own object, seen
//! from inside their grid. `info` summarises the warnings about the boxes behind the camera in a
//! few lines, and the ray tracer (which searches the objects through a tree over their boxes)
//! draws the image that one mesh object holding the same triangles gives.

mod common;

use std::fmt::Write;
use std::path::Path;

use common::{psnr, rastray_in, scratch};

/// Boxes a side of the grid: 10³ boxes.
const SIDE: usize = 10;

/// The header both scenes share: a camera inside the grid an eighth of the way along its
/// diagonal, looking along it, and one light.
const HEADER: &str = "[camera]\nposition = [3.0, 3.0, 3.0]\ntarget = [18.0, 18.0, 18.0]\nfov = 60.0\n\
                      [[light]]\nposition = [28.0, 58.0, -10.0]\n";

/// Unit boxes at (2i, 2j, 2k), as one object each and as one OBJ file whose triangles are the
/// same (its bounding-box centre placed where the grid's is).
fn write_scenes(dir: &Path) {
    let mut boxes = String::from(HEADER);
    let mut obj = String::new();
    let corners = |c: [f32; 3]| {
        let mut v = Vec::new();
        for dz in [-0.5, 0.5] {
            for (dx, dy) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
                v.push([c[0] + dx, c[1] + dy, c[2] + dz]);
            }
        }
        v
    };
    let faces = [
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [3, 7, 6],
        [3, 6, 2],
        [0, 4, 7],
        [0, 7, 3],
        [1, 2, 6],
        [1, 6, 5],
    ];
    let mut n = 0;
    for k in 0..SIDE {
        for j in 0..SIDE {
            for i in 0..SIDE {
                let c = [2.0 * i as f32, 2.0 * j as f32, 2.0 * k as f32];
                writeln!(
                    boxes,
                    "[[object]]\ntype = \"box\"\ncenter = {c:?}\nsize = [1.0, 1.0, 1.0]"
                )
                .expect("String");
                for v in corners(c) {
                    writeln!(obj, "v {} {} {}", v[0], v[1], v[2]).expect("String");
                }
                for f in faces {
                    writeln!(
                        obj,
                        "f {} {} {}",
                        8 * n + f[0] + 1,
                        8 * n + f[1] + 1,
                        8 * n + f[2] + 1
                    )
                    .expect("String");
                }
                n += 1;
            }
        }
    }
    let middle = (SIDE - 1) as f32;
    let one_mesh = format!(
        "{HEADER}[[object]]\ntype = \"mesh\"\npath = \"boxes.obj\"\nsmooth = false\nposition = [{middle:?}, {middle:?}, {middle:?}]\n"
    );
    std::fs::write(dir.join("boxes.toml"), boxes).expect("write");
    std::fs::write(dir.join("boxes.obj"), obj).expect("write");
    std::fs::write(dir.join("one-mesh.toml"), one_mesh).expect("write");
}

fn pixels(path: &Path) -> Vec<u8> {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8()
        .into_raw()
}

#[test]
fn many_boxes_render_as_one_mesh_of_the_same_triangles_and_info_summarises_warnings() {
    let dir = scratch();
    write_scenes(dir);

    let info = rastray_in(&["info", "boxes.toml"], dir);
    assert!(info.status.success(), "{info:?}");
    let stdout = String::from_utf8_lossy(&info.stdout);
    assert!(stdout.contains("objects  1000"), "{stdout}");
    let stderr = String::from_utf8_lossy(&info.stderr);
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .collect();
    // Five in full, then one line that counts the rest.
    assert_eq!(warnings.len(), 6, "{stderr}");
    assert!(
        warnings[5].contains("more objects entirely behind the camera"),
        "{stderr}"
    );

    for scene in ["boxes", "one-mesh"] {
        let out = rastray_in(
            &[
                "render",
                &format!("{scene}.toml"),
                "-a",
                "ray",
                "-s",
                "96x72",
                "-o",
                &format!("{scene}.png"),
            ],
            dir,
        );
        assert!(out.status.success(), "{scene}: {out:?}");
    }
    let boxes = pixels(&dir.join("boxes.png"));
    let mesh = pixels(&dir.join("one-mesh.png"));
    // The same triangles, but the box shape splits its faces along other diagonals than the
    // OBJ does: a point on a face is then interpolated from other corners, which moves it and
    // its shading by rounding only. So the images agree to within a level or two, not bit for
    // bit; a box missed or a shadow lost would cost far more than 45 dB.
    let differing = boxes
        .iter()
        .zip(&mesh)
        .filter(|(a, b)| a.abs_diff(**b) > 2)
        .count();
    assert!(
        differing <= boxes.len() / 500,
        "{differing} channels differ by more than 2"
    );
    // And the image is of boxes, lit and shaded: their faces in several colours (flat faces of
    // one orientation are nearly one colour each; 17 here), not one background.
    let mut colours: Vec<&[u8]> = boxes.chunks(3).collect();
    colours.sort();
    colours.dedup();
    assert!(colours.len() > 8, "{} colours", colours.len());
    let quality = psnr(&boxes, &mesh);
    assert!(quality > 45.0, "PSNR {quality:.1} dB");
}
