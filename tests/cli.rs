//! The headless command line as a user meets it: `render`, `info`, and bad input refused with
//! one clear message and exit code 2.

use std::path::Path;
use std::process::{Command, Output};

fn rastray(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs")
}

fn scenes() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn render_writes_a_png_of_the_requested_size_and_reports_the_time() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = scenes().join("default.toml");
    for algorithm in ["gouraud", "phong"] {
        let out = dir.path().join(format!("{algorithm}.png"));
        let o = rastray(
            &[
                "render",
                scene.to_str().unwrap(),
                "-a",
                algorithm,
                "-s",
                "64x48",
                "--samples",
                "2",
                "-o",
                out.to_str().unwrap(),
            ],
            dir.path(),
        );
        assert!(o.status.success(), "{}", stderr(&o));
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(
            stdout.contains("ms") && stdout.contains(out.to_str().unwrap()),
            "{stdout}"
        );
        let image = image::open(&out).expect("a PNG").to_rgb8();
        assert_eq!(image.dimensions(), (64, 48));
        // Not a blank image: the scene's objects show in several colours.
        let distinct: std::collections::HashSet<_> = image.pixels().map(|p| p.0).collect();
        assert!(
            distinct.len() > 50,
            "{algorithm}: only {} colours",
            distinct.len()
        );
    }
}

#[test]
fn info_lists_objects_triangles_and_bounds() {
    let o = rastray(
        &["info", scenes().join("default.toml").to_str().unwrap()],
        Path::new("."),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    for needle in ["floor", "icosahedron", "prism", "triangles 352", "bounds"] {
        assert!(text.contains(needle), "missing {needle}: {text}");
    }
}

/// Runs `render` on a scene file with `contents` and returns stderr; the command must fail with 2.
fn refused_scene(contents: &str) -> String {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("broken.toml"), contents).expect("write");
    let o = rastray(
        &["render", "broken.toml", "-s", "32x32", "-o", "x.png"],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let message = stderr(&o);
    assert!(!message.contains("panicked"), "{message}");
    assert_eq!(
        message.trim().lines().count(),
        1,
        "one clear message: {message}"
    );
    assert!(!dir.path().join("x.png").exists(), "no image is written");
    message
}

#[test]
fn bad_scene_files_give_one_message_and_exit_code_2() {
    let m = refused_scene("[camera\nposition = [0.0, 0.0, 5.0]\n");
    assert!(m.contains("broken.toml:1"), "{m}");
    let m = refused_scene("[[object]]\ntype = \"box\"\nsize = [1.0, -1.0, 1.0]\n");
    assert!(
        m.contains("broken.toml:3") && m.contains("object[0].size"),
        "{m}"
    );
    let m = refused_scene("[[object]]\ntype = \"icosahedron\"\nradius = nan\n");
    assert!(m.contains("broken.toml:3") && m.contains("radius"), "{m}");
    let m = refused_scene(
        "[[object]]\ntype = \"icosahedron\"\nradius = 1.0\ncolour = [1.0, 0.0, 0.0]\n",
    );
    assert!(m.contains("broken.toml:4") && m.contains("colour"), "{m}");
    let m = refused_scene("[[object]]\ntype = \"mesh\"\npath = \"missing.obj\"\n");
    assert!(m.contains("missing.obj"), "{m}");
}

#[test]
fn a_missing_scene_file_is_named() {
    let o = rastray(
        &["render", "no-such-scene.toml", "-o", "x.png"],
        Path::new(env!("CARGO_MANIFEST_DIR")),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("no-such-scene.toml"), "{}", stderr(&o));
}

#[test]
fn absurd_sizes_are_refused_before_any_allocation_with_the_limit_stated() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = scenes().join("default.toml");
    for (size, samples, needle) in [
        ("100000x100000", "1", "16384"),
        (
            "0x10",
            "1",
            "0x10 is out of range: width and height must each be between 1",
        ),
        ("12x", "1", "WIDTHxHEIGHT"),
        ("8000x8000", "4", "limit"),
    ] {
        let o = rastray(
            &[
                "render",
                scene.to_str().unwrap(),
                "-s",
                size,
                "--samples",
                samples,
                "-o",
                "x.png",
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{size}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{size}: {}", stderr(&o));
    }
}

#[test]
fn thread_counts_past_the_limit_are_refused_before_any_thread_starts() {
    let dir = tempfile::tempdir().expect("tempdir");
    let scene = scenes().join("default.toml");
    // `--threads 20000` had started its threads one by one, still at it when a 30-second
    // timeout stopped it; 1024 is the limit the config file's `threads` has too.
    for (threads, problem) in [
        ("0", "threads is out of range"),
        ("1025", "threads is out of range"),
        ("100000", "threads is out of range"),
        ("two", "is not a thread count"),
    ] {
        let o = rastray(
            &[
                "render",
                scene.to_str().unwrap(),
                "-s",
                "16x16",
                "--threads",
                threads,
                "-o",
                "x.png",
            ],
            dir.path(),
        );
        assert_eq!(o.status.code(), Some(2), "{threads}: {}", stderr(&o));
        let expected = format!("`{threads}` {problem}: use 1 to 1024");
        assert!(stderr(&o).contains(&expected), "{threads}: {}", stderr(&o));
        assert!(!dir.path().join("x.png").exists(), "{threads}");
    }
}

/// Runs `args` in a directory holding `scene.toml` with `contents`; returns (stdout, stderr).
fn run_on_scene(contents: &str, args: &[&str]) -> (String, String) {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("scene.toml"), contents).expect("write");
    let o = rastray(args, dir.path());
    assert!(o.status.success(), "{}", stderr(&o));
    (String::from_utf8_lossy(&o.stdout).into_owned(), stderr(&o))
}

#[test]
fn render_and_info_print_the_scene_warnings_on_stderr() {
    let scene = "[camera]\nposition = [0.0, 0.0, 5.0]\n\
                 [[object]]\ntype = \"box\"\nname = \"seen\"\nsize = [1.0, 1.0, 1.0]\n\
                 [[object]]\ntype = \"box\"\nname = \"hidden\"\ncenter = [0.0, 0.0, 8.0]\nsize = [1.0, 1.0, 1.0]\n";
    let expected = "warning: the scene has no lights; only ambient light will show\n\
                    warning: object[1] \"hidden\" is entirely behind the camera and will not show\n";
    let render = [
        "render",
        "scene.toml",
        "-a",
        "gouraud",
        "-s",
        "32x24",
        "-o",
        "x.png",
    ];
    let (stdout, stderr) = run_on_scene(scene, &render);
    assert_eq!(stderr, expected);
    assert!(stdout.contains("wrote x.png"), "{stdout}");
    let (stdout, stderr) = run_on_scene(scene, &["info", "scene.toml"]);
    assert_eq!(stderr, expected);
    assert!(stdout.contains("hidden"), "{stdout}");
}

#[test]
fn a_scene_without_problems_prints_no_warning() {
    let (_, stderr) = run_on_scene(
        &std::fs::read_to_string(scenes().join("default.toml")).expect("default.toml"),
        &["info", "scene.toml"],
    );
    assert_eq!(stderr, "");
}
