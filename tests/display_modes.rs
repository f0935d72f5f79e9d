//! The display modes and overlays: known answers on tiny images, the Z-buffer and the ray
//! tracer drawing the same edges, and the command line's `--mode` and `--overlay`.

mod common;

use std::path::Path;
use std::process::Command;

use rastray::render::{Algorithm, DisplayMode, Frame, Overlays, RenderOptions, encode_srgb};

/// A scene of `objects` (TOML `[[object]]` tables) seen from `camera` (TOML body of `[camera]`).
fn scene_with(camera: &str, objects: &str) -> rastray::Scene {
    common::scene(&format!(
        "background = [0.2, 0.3, 0.4]\n[camera]\n{camera}\n[[light]]\nposition = [2.0, 3.0, 6.0]\nintensity = 0.8\n{objects}"
    ))
}

/// Renders `scene` with `algorithm` in `mode` at `width`×`height`, `samples`² samples a pixel.
fn render(
    scene: &rastray::Scene,
    algorithm: Algorithm,
    mode: DisplayMode,
    size: (u32, u32),
    samples: u32,
) -> Frame {
    let options = RenderOptions {
        mode,
        samples,
        ..RenderOptions::new(algorithm, size.0, size.1)
    };
    common::render(&common::world(scene), &scene.camera, options).0
}

/// A unit cube at the origin seen from +Z.
fn unit_cube_from_front() -> rastray::Scene {
    scene_with(
        "position = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 45.0",
        "[[object]]\ntype = \"box\"\ncenter = [0.0, 0.0, 0.0]\nsize = [1.0, 1.0, 1.0]",
    )
}

#[test]
fn normals_show_a_front_face_as_128_128_255_in_every_algorithm() {
    // The face's normal is +Z: (n + 1)/2 = (0.5, 0.5, 1), written as bytes with no sRGB curve
    // and no lighting; 0.5 · 255 = 127.5, so 127 or 128, and 2 levels are allowed.
    let scene = unit_cube_from_front();
    for algorithm in Algorithm::ALL {
        for samples in [1, 3] {
            let frame = render(&scene, algorithm, DisplayMode::Normals, (32, 32), samples);
            for (x, y) in [(16, 16), (12, 12), (19, 19)] {
                let [r, g, b] = frame.srgb8_at(x, y);
                assert!(
                    r.abs_diff(128) <= 2 && g.abs_diff(128) <= 2 && b >= 253,
                    "{algorithm} {samples}x: ({r}, {g}, {b}) at ({x}, {y})"
                );
            }
        }
    }
}

#[test]
fn depth_runs_from_white_at_the_nearest_bound_to_black_at_the_farthest() {
    // Two unit cubes, fronts at z = 0.5 and z = −1.5, the scene's bounds from z = −2.5 to 0.5;
    // from z = 5 that is depth 4.5 (white) to 7.5 (black). The far cube's front, at depth 6.5,
    // is a third of the way from black: 255/3 = 85. The background is black. One level allowed
    // for rounding.
    let scene = scene_with(
        "position = [0.0, 0.0, 5.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 45.0",
        "[[object]]\ntype = \"box\"\ncenter = [-0.8, 0.0, 0.0]\nsize = [1.0, 1.0, 1.0]\n\
         [[object]]\ntype = \"box\"\ncenter = [0.8, 0.0, -2.0]\nsize = [1.0, 1.0, 1.0]",
    );
    for algorithm in Algorithm::ALL {
        let frame = render(&scene, algorithm, DisplayMode::Depth, (48, 24), 1);
        // Columns: the near cube's centre projects to x = 24 − 0.8/(4.5·tan 22.5°)·12 ≈ 18.8,
        // the far one's to 24 + 0.8/(6.5·tan 22.5°)·12 ≈ 27.6.
        let near = frame.srgb8_at(18, 12);
        let far = frame.srgb8_at(27, 12);
        let background = frame.srgb8_at(2, 2);
        assert!(near.iter().all(|&c| c >= 254), "{algorithm}: near {near:?}");
        assert!(
            far.iter().all(|&c| c.abs_diff(85) <= 1),
            "{algorithm}: far {far:?}"
        );
        assert_eq!(background, [0, 0, 0], "{algorithm}");
    }
}

#[test]
fn hidden_line_draws_white_faces_with_one_pixel_edges_where_the_geometry_says() {
    // A 1.9 × 1.9 slab whose front face, at depth 2 under a 90° fov on 20×20 pixels, spans
    // pixels 5.25 to 14.75: columns and rows 5 and 14 have their centres 0.25 px inside the
    // border (under the half width 0.5: edge), 6 and 13 are 1.25 px in (face). The face's
    // diagonal passes through the centres of (i, i) or of (i, 19 − i), and its neighbours are
    // 0.71 px off it. The image must be exactly one of the two masks.
    let scene = scene_with(
        "position = [0.0, 0.0, 2.1]\ntarget = [0.0, 0.0, 0.0]\nfov = 90.0",
        "[[object]]\ntype = \"box\"\ncenter = [0.0, 0.0, 0.0]\nsize = [1.9, 1.9, 0.2]",
    );
    let background = [0.2f32, 0.3, 0.4].map(encode_srgb);
    let expected = |anti: bool, x: u32, y: u32| {
        let inside = (5..=14).contains(&x) && (5..=14).contains(&y);
        let border = [5, 14].contains(&x) || [5, 14].contains(&y);
        let diagonal = if anti { x + y == 19 } else { x == y };
        match (inside, border || diagonal) {
            (false, _) => background,
            (true, true) => [0, 0, 0],
            (true, false) => [255, 255, 255],
        }
    };
    for algorithm in Algorithm::ALL {
        let frame = render(&scene, algorithm, DisplayMode::HiddenLine, (20, 20), 1);
        let matches =
            |anti| (0..20).all(|y| (0..20).all(|x| frame.srgb8_at(x, y) == expected(anti, x, y)));
        assert!(
            matches(false) || matches(true),
            "{algorithm}: {}",
            ascii(&frame)
        );
    }
}

/// The frame as text, one character per pixel, for failure messages: `#` black, `.` white,
/// ` ` anything else.
fn ascii(frame: &Frame) -> String {
    let mut text = String::from("\n");
    for y in 0..frame.height {
        for x in 0..frame.width {
            text.push(match frame.srgb8_at(x, y) {
                [0, 0, 0] => '#',
                [255, 255, 255] => '.',
                _ => ' ',
            });
        }
        text.push('\n');
    }
    text
}

/// Which pixels of a `wire` frame are edge lines: clearly darker than the `shaded` frame there,
/// below 90% of its bytes (the lines are black; with supersampling, a pixel a line crosses is
/// partly black, and half black in linear light is 73% in sRGB bytes).
fn edge_mask(wire: &Frame, shaded: &Frame) -> Vec<bool> {
    let sum = |c: [u8; 3]| c.iter().map(|&v| v as u32).sum::<u32>();
    (0..wire.height)
        .flat_map(|y| (0..wire.width).map(move |x| (x, y)))
        .map(|(x, y)| 10 * sum(wire.srgb8_at(x, y)) < 9 * sum(shaded.srgb8_at(x, y)))
        .collect()
}

/// The edge mask of `scene` drawn by `algorithm`.
fn wire_mask(scene: &rastray::Scene, algorithm: Algorithm, size: (u32, u32), n: u32) -> Vec<bool> {
    let wire = render(scene, algorithm, DisplayMode::Wire, size, n);
    let shaded = render(scene, algorithm, DisplayMode::Shaded, size, n);
    edge_mask(&wire, &shaded)
}

#[test]
fn wire_edges_from_the_z_buffer_and_the_ray_tracer_agree() {
    // The same hits give the same lines: the masks may differ only where the two algorithms
    // see different triangles at a pixel centre on a silhouette or shared edge. Stated
    // tolerance: under 3% of the edge pixels, and no pixel off by more than one from an edge
    // pixel of the other mask.
    // In perspective and in orthographic projection: the edges' lines follow the projection.
    let cameras = [
        "position = [0.5, 1.2, 4.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 45.0",
        "position = [0.5, 1.2, 4.0]\ntarget = [0.0, 0.0, 0.0]\nprojection = \"orthographic\"\nheight = 2.6",
    ];
    for (camera, samples) in cameras.iter().flat_map(|c| [(c, 1), (c, 2)]) {
        let scene = scene_with(
            camera,
            "[[object]]\ntype = \"icosahedron\"\ncenter = [-0.7, 0.0, 0.0]\nradius = 0.8\nsubdivisions = 1\n\
             [[object]]\ntype = \"box\"\ncenter = [0.8, 0.0, -0.3]\nsize = [0.9, 0.9, 0.9]\nsegments = 2",
        );
        let size = (160, 100);
        let ray = wire_mask(&scene, Algorithm::Ray, size, samples);
        for algorithm in [Algorithm::Gouraud, Algorithm::Phong] {
            let zbuffer = wire_mask(&scene, algorithm, size, samples);
            let edges = ray.iter().filter(|&&e| e).count();
            let differ = ray.iter().zip(&zbuffer).filter(|(a, b)| a != b).count();
            assert!(
                edges > 500,
                "{samples}x: {edges} edge pixels: the scene shows its edges"
            );
            eprintln!("{algorithm} {samples}x: {differ} of {edges} edge pixels differ");
            assert!(
                differ * 100 < edges * 3,
                "{algorithm} {samples}x: {differ} of {edges} edge pixels differ"
            );
            let near = |mask: &[bool], i: usize| {
                let (x, y) = ((i % size.0 as usize) as i64, (i / size.0 as usize) as i64);
                (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| {
                        let (nx, ny) = (x + dx, y + dy);
                        (0..size.0 as i64).contains(&nx)
                            && (0..size.1 as i64).contains(&ny)
                            && mask[(ny * size.0 as i64 + nx) as usize]
                    })
                })
            };
            for i in 0..ray.len() {
                if ray[i] != zbuffer[i] {
                    let (has, other) = if ray[i] {
                        (&ray, &zbuffer)
                    } else {
                        (&zbuffer, &ray)
                    };
                    assert!(has[i] && near(other, i), "{algorithm}: pixel {i} stray");
                }
            }
        }
    }
}

#[test]
fn shaded_with_no_overlays_is_the_image_it_always_was() {
    // `shaded` is the default: asking for it explicitly changes no byte, and wire adds only
    // black lines to that image.
    let scene = common::default_scene();
    for algorithm in Algorithm::ALL {
        let plain = common::draw(&scene, algorithm, 64, 40);
        let shaded = render(&scene, algorithm, DisplayMode::Shaded, (64, 40), 1);
        assert_eq!(plain.pixels, shaded.pixels, "{algorithm}");
        let wire = render(&scene, algorithm, DisplayMode::Wire, (64, 40), 1);
        for (w, s) in wire.pixels.iter().zip(&plain.pixels) {
            assert!(*w == *s || *w == glam::Vec3::ZERO, "{algorithm}");
        }
    }
}

#[test]
fn the_grid_lies_under_the_model_and_is_hidden_by_it() {
    // A unit cube on the grid's plane, seen from above at an angle: the grid's colour shows
    // around the cube and never on its top face.
    let scene = scene_with(
        "position = [0.0, 2.5, 3.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 50.0",
        "[[object]]\ntype = \"box\"\ncenter = [0.0, 0.0, 0.0]\nsize = [1.0, 1.0, 1.0]",
    );
    let options = RenderOptions {
        overlays: Overlays {
            grid: true,
            ..Overlays::default()
        },
        ..RenderOptions::new(Algorithm::Phong, 80, 60)
    };
    let world = common::world(&scene);
    let with_grid = common::render(&world, &scene.camera, options).0;
    let plain = common::draw(&scene, Algorithm::Phong, 80, 60);
    let hits = rastray::render::ground_grid(&world).expect("a grid");
    assert!(
        (hits.level + 0.5).abs() < 1e-6,
        "the grid is at the cube's bottom"
    );
    let changed: Vec<usize> = (0..plain.pixels.len())
        .filter(|&i| plain.pixels[i] != with_grid.pixels[i])
        .collect();
    assert!(changed.len() > 100, "{} grid pixels", changed.len());
    // The centre of the image is the cube's top face: untouched.
    let centre = 30 * 80 + 40;
    assert_eq!(plain.pixels[centre], with_grid.pixels[centre]);
    // Grid lines cross the cube's pixels only along its bottom edges, where the floor meets
    // it in front: fewer than 5% of them.
    let background = plain.pixels[0];
    let cube = (0..plain.pixels.len()).filter(|&i| plain.pixels[i] != background);
    let (on_cube, crossed) = cube.fold((0, 0), |(n, c), i| {
        (n + 1, c + (plain.pixels[i] != with_grid.pixels[i]) as usize)
    });
    assert!(
        crossed * 20 < on_cube,
        "{crossed} of {on_cube} cube pixels under grid lines"
    );
}

fn run(args: &[&str], dir: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs")
}

#[test]
fn the_command_line_takes_modes_and_overlays_and_refuses_unknown_ones() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = dir.path().join("cube.toml");
    std::fs::write(
        &scene,
        "[camera]\nposition = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\n[[object]]\ntype = \"box\"\ncenter = [0.0, 0.0, 0.0]\nsize = [1.0, 1.0, 1.0]\n",
    )
    .expect("scene");
    let scene = scene.to_str().unwrap();
    let o = run(
        &[
            "render", scene, "-s", "32x32", "--mode", "normals", "-o", "n.png",
        ],
        dir.path(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let image = image::open(dir.path().join("n.png"))
        .expect("png")
        .to_rgb8();
    let [r, g, b] = image.get_pixel(16, 16).0;
    assert!(r.abs_diff(128) <= 2 && g.abs_diff(128) <= 2 && b >= 253);

    let o = run(
        &[
            "render",
            scene,
            "-s",
            "32x32",
            "--mode",
            "uv",
            "--overlay",
            "grid,bbox",
            "-o",
            "u.png",
        ],
        dir.path(),
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stderr.contains("1 of 1 objects have no texture coordinates"),
        "{stderr}"
    );
    assert!(stderr.contains("grid: spacing 0.2"), "{stderr}");
    assert!(
        stderr.contains("bounding box: 1.000 x 1.000 x 1.000"),
        "{stderr}"
    );

    for (flag, value, says) in [
        ("--mode", "wireframe", "not a display mode"),
        ("--overlay", "grid,ruler", "`ruler` is not an overlay"),
    ] {
        let o = run(&["render", scene, flag, value, "-o", "x.png"], dir.path());
        assert_eq!(o.status.code(), Some(2));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(says), "{stderr}");
    }
}

#[test]
fn the_outline_runs_on_where_two_strips_meet() {
    // 4096×1400 samples are rendered as strips of 1024 rows (4M samples each). The cube's bottom
    // edge lies on row 1023, just above the seam: its outline's second row is the next strip's
    // first, which sees no cube. In every algorithm, the outline must be exactly the cube's
    // mask grown by 2 pixels (a square reach), less the mask.
    let scene = scene_with(
        "position = [0.0, 0.0, 3.0]\ntarget = [0.0, 0.0, 0.0]\nprojection = \"orthographic\"\nheight = 2.0",
        "[[object]]\ntype = \"box\"\ncenter = [0.0, 0.0386, 0.0]\nsize = [1.0, 1.0, 1.0]",
    );
    let (w, h) = (4096_usize, 1400_usize);
    let world = common::world(&scene);
    for algorithm in [Algorithm::Phong, Algorithm::Ray] {
        let options = RenderOptions {
            alpha: true,
            overlays: Overlays {
                outline: true,
                ..Overlays::default()
            },
            ..RenderOptions::new(algorithm, w as u32, h as u32)
        };
        let frame = common::render(&world, &scene.camera, options).0;
        let on = |x: usize, y: usize| {
            // The outline lies off the object, so it is background in the coverage.
            frame.alpha.as_ref().unwrap()[y * w + x] > 0.5
                && frame.pixels[y * w + x] != rastray::render::overlay_colors::OUTLINE
        };
        let mask: Vec<bool> = (0..w * h).map(|i| on(i % w, i / w)).collect();
        let bottom = (0..h).rev().find(|&y| mask[y * w + w / 2]).unwrap();
        assert_eq!(bottom, 1022, "the cube's last row sits above the seam");
        let near = |x: usize, y: usize| {
            (y.saturating_sub(2)..=(y + 2).min(h - 1))
                .any(|j| (x.saturating_sub(2)..=(x + 2).min(w - 1)).any(|i| mask[j * w + i]))
        };
        let wrong: Vec<(usize, usize)> = (0..w * h)
            .map(|i| (i % w, i / w))
            .filter(|&(x, y)| {
                let drawn = frame.pixels[y * w + x] == rastray::render::overlay_colors::OUTLINE;
                drawn != (!mask[y * w + x] && near(x, y))
            })
            .collect();
        assert!(
            wrong.is_empty(),
            "{algorithm:?}: {} pixels differ, first {:?}",
            wrong.len(),
            &wrong[..wrong.len().min(5)]
        );
    }
}

#[test]
fn the_bounding_box_has_its_lengths_written_beside_it_in_images_that_can_show_them() {
    // A 2 × 1 × 1 box seen from above at an angle: with labels, pixels change near the box and
    // some take the box's colour (the text); without, or in a frame too low to read, none do.
    let scene = scene_with(
        "position = [1.0, 2.0, 4.0]\ntarget = [0.0, 0.0, 0.0]\nfov = 45.0",
        "[[object]]\ntype = \"box\"\ncenter = [0.0, 0.0, 0.0]\nsize = [2.0, 1.0, 1.0]",
    );
    let world = common::world(&scene);
    let bbox = |labels: bool, width: u32, height: u32| {
        let options = RenderOptions {
            overlays: Overlays {
                bbox: true,
                labels,
                ..Overlays::default()
            },
            ..RenderOptions::new(Algorithm::Phong, width, height)
        };
        common::render(&world, &scene.camera, options).0
    };
    let (plain, labelled) = (bbox(false, 320, 240), bbox(true, 320, 240));
    let changed: Vec<usize> = (0..plain.pixels.len())
        .filter(|&i| plain.pixels[i] != labelled.pixels[i])
        .collect();
    let inked = changed
        .iter()
        .filter(|&&i| {
            // Anti-aliased text: nearer the box's colour than the pixel was, and yellow.
            let bounds = rastray::render::overlay_colors::BOUNDS;
            let (p, q) = (labelled.pixels[i], plain.pixels[i]);
            p.distance(bounds) < q.distance(bounds) && p.x > 0.4 && p.z < 0.25
        })
        .count();
    assert!(changed.len() > 100, "{} pixels changed", changed.len());
    assert!(inked > 30, "{inked} pixels of text");
    // `--overlay bbox` asks for the labels.
    let parsed: Overlays = "bbox".parse().unwrap();
    assert!(parsed.labels);
    // Below 120 pixels high, no text.
    assert_eq!(bbox(false, 160, 100).pixels, bbox(true, 160, 100).pixels);
}
