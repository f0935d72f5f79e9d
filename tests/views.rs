//! Orthographic and preset views, and `view --spin`, through the built binary: a unit cube
//! seen from the front orthographically is a square in all three algorithms, `iso` shows three
//! faces, several views need a `{view}` field, and a turntable plays a known number of frames.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Output;

/// A unit cube at the origin under one light, seen by a perspective camera from an odd angle
/// (the presets replace it).
const CUBE: &str = r#"
[camera]
position = [3.0, 1.0, 4.0]
target = [0.0, 0.0, 0.0]
up = [0.0, 1.0, 0.0]
fov = 40.0

[[light]]
position = [2.0, 5.0, 3.0]
intensity = 1.0

[[object]]
type = "box"
center = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 1.0]
"#;

mod common;

use common::rastray_in as rastray;

fn succeeds(args: &[&str], dir: &Path) -> Output {
    let o = rastray(args, dir);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn cube(dir: &Path) -> PathBuf {
    let path = dir.join("cube.toml");
    std::fs::write(&path, CUBE).unwrap();
    path
}

/// The pixels that are not the background (the top-left pixel's colour), as a set.
fn mask(image: &image::RgbImage) -> BTreeSet<(u32, u32)> {
    let background = *image.get_pixel(0, 0);
    image
        .enumerate_pixels()
        .filter(|(_, _, p)| **p != background)
        .map(|(x, y, _)| (x, y))
        .collect()
}

fn render(dir: &Path, scene: &Path, extra: &[&str], algorithm: &str) -> image::RgbImage {
    let out = dir.join(format!("{algorithm}.png"));
    let mut args = vec![
        "render",
        scene.to_str().unwrap(),
        "-a",
        algorithm,
        "-s",
        "160x120",
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend(extra);
    succeeds(&args, dir);
    image::open(&out).expect("a PNG").to_rgb8()
}

#[test]
fn a_unit_cube_from_the_front_orthographically_is_the_same_square_in_every_algorithm() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube(dir.path());
    let masks: Vec<_> = ["gouraud", "phong", "ray"]
        .map(|a| {
            mask(&render(
                dir.path(),
                &scene,
                &["--view", "front", "--ortho"],
                a,
            ))
        })
        .into();
    let (xs, ys): (Vec<u32>, Vec<u32>) = masks[0].iter().copied().unzip();
    let width = xs.iter().max().unwrap() - xs.iter().min().unwrap() + 1;
    let height = ys.iter().max().unwrap() - ys.iter().min().unwrap() + 1;
    // The fit leaves a margin of 8%: the cube is 120 / 1.08 ≈ 111 pixels tall, and a square
    // orthographically (the perspective front view shows the sides' taper, not a square).
    assert!(width.abs_diff(height) <= 1, "{width}×{height}");
    assert!((105..=115).contains(&height), "{height}");
    // Filled: every pixel of the square is covered.
    assert_eq!(masks[0].len() as u32, width * height);
    assert_eq!(masks[0], masks[1], "Gouraud and Phong masks differ");
    assert_eq!(masks[1], masks[2], "Phong and ray-traced masks differ");
}

#[test]
fn an_orthographic_scene_camera_agrees_between_the_zbuffer_and_the_ray_tracer() {
    let dir = tempfile::tempdir().unwrap();
    // Seen from an angle, with the camera's plane cutting through the cube (near clipping).
    let scene = dir.path().join("ortho.toml");
    let text = CUBE
        .replace("position = [3.0, 1.0, 4.0]", "position = [0.3, 0.2, 0.1]")
        .replace("target = [0.0, 0.0, 0.0]", "target = [-3.0, -1.0, -4.0]")
        .replace(
            "fov = 40.0",
            "fov = 40.0\nprojection = \"orthographic\"\nheight = 3.0",
        );
    std::fs::write(&scene, text).unwrap();
    let phong = mask(&render(dir.path(), &scene, &[], "phong"));
    let ray = mask(&render(dir.path(), &scene, &[], "ray"));
    assert!(phong.len() > 1000, "{} pixels", phong.len());
    // The cut face is open: both see into the cube's back faces alike, pixel centre for
    // pixel centre, up to the odd centre on a triangle edge decided differently.
    let differ = phong.symmetric_difference(&ray).count();
    assert!(differ <= 4, "{differ} pixels differ");
}

#[test]
fn info_gives_an_orthographic_camera_its_height_and_a_perspective_one_its_fov() {
    let dir = tempfile::tempdir().unwrap();
    let ortho = dir.path().join("ortho.toml");
    let text = CUBE.replace(
        "fov = 40.0",
        "fov = 40.0\nprojection = \"orthographic\"\nheight = 3.0",
    );
    std::fs::write(&ortho, text).unwrap();
    let shown = |path: &Path| {
        let o = succeeds(&["info", path.to_str().unwrap()], dir.path());
        let text = String::from_utf8_lossy(&o.stdout).to_string();
        text.lines()
            .find(|l| l.starts_with("camera"))
            .unwrap()
            .to_string()
    };
    let line = shown(&ortho);
    assert!(line.ends_with("orthographic  height 3"), "{line}");
    let line = shown(&cube(dir.path()));
    assert!(line.ends_with("fov 40°"), "{line}");
}

#[test]
fn iso_shows_three_faces() {
    let dir = tempfile::tempdir().unwrap();
    // A far light and no highlight: each face lit evenly.
    let scene = dir.path().join("far.toml");
    let text = CUBE
        .replace(
            "position = [2.0, 5.0, 3.0]",
            "position = [2000.0, 5000.0, 3000.0]",
        )
        .replace(
            "size = [1.0, 1.0, 1.0]",
            "size = [1.0, 1.0, 1.0]\nmaterial = { specular = 0.0 }",
        );
    std::fs::write(&scene, text).unwrap();
    let image = render(dir.path(), &scene, &["--view", "iso", "--ortho"], "phong");
    let background = *image.get_pixel(0, 0);
    // Each face is one colour (within the quantization of 8 levels): count the colours
    // that cover at least 5% of the picture.
    let mut counts = std::collections::HashMap::new();
    for p in image.pixels().filter(|p| **p != background) {
        *counts.entry(p.0.map(|c| c / 8)).or_insert(0u32) += 1;
    }
    let faces = counts.values().filter(|&&n| n > 160 * 120 / 20).count();
    assert_eq!(faces, 3, "{counts:?}");
}

#[test]
fn several_views_need_a_view_field_and_each_gets_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube(dir.path());
    let refused = rastray(
        &[
            "render",
            scene.to_str().unwrap(),
            "--view",
            "front,iso",
            "-o",
            "one.png",
        ],
        dir.path(),
    );
    assert_eq!(refused.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&refused.stderr).contains("{view}"));
    assert!(!dir.path().join("one.png").exists());
    succeeds(
        &[
            "render",
            scene.to_str().unwrap(),
            "--view",
            "front,iso",
            "-s",
            "32x24",
            "-o",
            "out-{view}.png",
        ],
        dir.path(),
    );
    for view in ["front", "iso"] {
        assert!(
            dir.path().join(format!("out-{view}.png")).exists(),
            "{view}"
        );
    }
    let unknown = rastray(
        &["render", scene.to_str().unwrap(), "--view", "side"],
        dir.path(),
    );
    assert_eq!(unknown.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&unknown.stderr)
            .contains("front, right, back, left, top, bottom, iso")
    );
}

/// What `render` says on stderr of the cube scene with `camera_lines` after its `fov`, which
/// it must refuse with code 2.
fn refusal(dir: &Path, camera_lines: &str) -> String {
    let scene = dir.join("bad.toml");
    let text = CUBE.replace("fov = 40.0", &format!("fov = 40.0\n{camera_lines}"));
    std::fs::write(&scene, text).unwrap();
    let o = rastray(&["render", scene.to_str().unwrap(), "-o", "x.png"], dir);
    assert_eq!(o.status.code(), Some(2));
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn an_orthographic_camera_without_a_height_names_the_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let stderr = refusal(dir.path(), "projection = \"orthographic\"");
    assert!(stderr.contains("camera.height"), "{stderr}");
    let stderr = refusal(dir.path(), "projection = \"fisheye\"");
    assert!(
        stderr.contains("bad.toml:7:") && stderr.contains("fisheye"),
        "{stderr}"
    );
    let stderr = refusal(dir.path(), "projection = \"orthographic\"\nheight = -1.0");
    assert!(
        stderr.contains("bad.toml:8:") && stderr.contains("camera.height"),
        "{stderr}"
    );
}

#[test]
fn spin_writes_one_picture_per_frame_and_exits_when_not_on_a_terminal() {
    let dir = tempfile::tempdir().unwrap();
    let scene = cube(dir.path());
    let o = succeeds(
        &[
            "view",
            scene.to_str().unwrap(),
            "--spin",
            "--frames",
            "12",
            "--loops",
            "1",
            "--graphics",
            "kitty",
            "--width",
            "20",
        ],
        dir.path(),
    );
    let text = String::from_utf8(o.stdout).unwrap();
    // Each kitty picture is transmitted and shown once (`a=T`), in one or more chunks.
    assert_eq!(text.matches("a=T").count(), 12);
    // Two turns of three frames in half blocks: six pictures of the same size.
    let o = succeeds(
        &[
            "view",
            scene.to_str().unwrap(),
            "--spin",
            "--frames",
            "3",
            "--loops",
            "2",
            "--graphics",
            "halfblock",
            "--width",
            "16",
        ],
        dir.path(),
    );
    assert!(!o.stdout.is_empty());
}

#[test]
fn watch_draws_again_when_the_scene_changes_and_stops_on_sigterm() {
    use std::io::Read;
    let dir = tempfile::tempdir().unwrap();
    let scene = cube(dir.path());
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args([
            "view",
            scene.to_str().unwrap(),
            "--watch",
            "--graphics",
            "kitty",
            "--width",
            "10",
        ])
        .current_dir(dir.path())
        .stdout(std::process::Stdio::piped())
        .spawn()
        .expect("runs");
    let mut stdout = child.stdout.take().unwrap();
    let (send, pictures) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut bytes = [0u8; 65536];
        let mut all = Vec::new();
        while let Ok(n) = stdout.read(&mut bytes) {
            if n == 0 {
                break;
            }
            all.extend_from_slice(&bytes[..n]);
            let _ = send.send(String::from_utf8_lossy(&all).matches("a=T").count());
        }
    });
    let wait_for = |n: usize| loop {
        let seen = pictures
            .recv_timeout(std::time::Duration::from_secs(60))
            .expect("a picture in time");
        if seen >= n {
            break;
        }
    };
    wait_for(1);
    // A later modification time, whatever the file system's resolution.
    std::thread::sleep(std::time::Duration::from_millis(1100));
    std::fs::write(&scene, CUBE.replace("intensity = 1.0", "intensity = 0.5")).unwrap();
    wait_for(2);
    rustix::process::kill_process(
        rustix::process::Pid::from_child(&child),
        rustix::process::Signal::TERM,
    )
    .unwrap();
    // Stopped by SIGTERM: 128 + 15, as a shell expects of an interrupted command.
    assert_eq!(child.wait().unwrap().code(), Some(143));
}
