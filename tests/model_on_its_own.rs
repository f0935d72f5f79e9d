//! A model file given where a scene is expected: `render`, `info` and the library's scene for it
//! show the model whole, centred in the picture; a model with nothing to show is refused with a
//! message that names it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rastray::model_scene::{FIT_RADIUS, scene_for_model};
use rastray::world::World;

fn rastray(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .output()
        .expect("runs")
}

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

#[test]
fn the_model_is_scaled_into_the_unit_sphere_about_the_origin() {
    for model in ["suzanne.obj", "gltf/box.glb"] {
        let path = data(model);
        let scene =
            scene_for_model(&path, Default::default()).unwrap_or_else(|e| panic!("{model}: {e}"));
        let world = World::build(&scene, path.parent().unwrap()).expect("builds");
        let (lo, hi) = world.bounds().expect("something to show");
        let radius = (hi - lo).length() / 2.0;
        // Fitted to the bounding box's half diagonal, up to float rounding.
        assert!(
            (radius - FIT_RADIUS).abs() < 1e-3,
            "{model}: radius {radius}"
        );
        assert!(
            ((lo + hi) / 2.0).length() < 1e-3,
            "{model}: centre {}",
            (lo + hi) / 2.0
        );
    }
}

#[test]
fn render_shows_a_model_file_whole_and_centred() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("suzanne.png");
    let model = data("suzanne.obj");
    let o = rastray(&[
        "render",
        model.to_str().unwrap(),
        "-a",
        "phong",
        "-s",
        "96x64",
        "--transparent",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let image = image::open(&out).expect("a PNG").to_rgba8();
    let covered: Vec<(u32, u32)> = image
        .enumerate_pixels()
        .filter(|(_, _, p)| p[3] > 0)
        .map(|(x, y, _)| (x, y))
        .collect();
    assert!(
        covered.len() > 96 * 64 / 12,
        "the model fills a good part of the picture: {} pixels",
        covered.len()
    );
    // Whole: nothing touches the border. Centred: the covered box's middle is near the image's.
    let (xs, ys): (Vec<u32>, Vec<u32>) = covered.into_iter().unzip();
    let (x0, x1) = (*xs.iter().min().unwrap(), *xs.iter().max().unwrap());
    let (y0, y1) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
    assert!(
        x0 > 0 && y0 > 0 && x1 < 95 && y1 < 63,
        "({x0},{y0})–({x1},{y1})"
    );
    let (cx, cy) = ((x0 + x1) as f32 / 2.0, (y0 + y1) as f32 / 2.0);
    assert!(
        (cx - 47.5).abs() < 10.0 && (cy - 31.5).abs() < 8.0,
        "centre ({cx}, {cy})"
    );
}

#[test]
fn info_lists_a_gltf_file_given_on_its_own() {
    let model = data("gltf/box.glb");
    let o = rastray(&["info", model.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("12 triangles"), "{stdout}");
    assert!(stdout.contains("box.glb"), "{stdout}");
}

#[test]
fn a_model_with_nothing_to_show_is_refused_by_name() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.obj");
    std::fs::write(&empty, "# no faces\nv 0 0 0\n").unwrap();
    let out = dir.path().join("x.png");
    let o = rastray(&[
        "render",
        empty.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("empty.obj"), "{stderr}");
    assert!(stderr.contains("no faces"), "{stderr}");
    assert_eq!(
        stderr.matches("empty.obj").count(),
        1,
        "named once: {stderr}"
    );
    assert!(!out.exists());
}

/// `info` reads a model once, keyed by the path its scene names it by: given by a bare name in
/// the current folder, as `./name` or by its full path, it lists the same model, and a broken
/// one is refused naming the file and line.
#[test]
fn info_on_a_model_reads_it_the_same_whatever_the_path_form() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(data("obj/cube.obj"), dir.path().join("cube.obj")).unwrap();
    std::fs::write(
        dir.path().join("bad.obj"),
        "v 0 0 0\nv 1 0 0\nv 0 x 0\nf 1 2 3\n",
    )
    .unwrap();
    let info = |name: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_rastray"))
            .args(["info", name])
            .current_dir(dir.path())
            .output()
            .expect("runs");
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        // Everything after the first line, which is the path as given.
        let listing = stdout.lines().skip(1).collect::<Vec<_>>().join("\n");
        (o.status.code(), listing, stderr)
    };
    let full = dir.path().join("cube.obj");
    let expected = info(full.to_str().unwrap());
    assert_eq!(expected.0, Some(0), "{}", expected.2);
    assert!(expected.1.contains("12 triangles"), "{}", expected.1);
    assert_eq!(info("cube.obj"), expected);
    assert_eq!(info("./cube.obj"), expected);
    let (code, _, stderr) = info("bad.obj");
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("bad.obj:3"), "{stderr}");
}
