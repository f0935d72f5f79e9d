//! The GNU parallel recipes of docs/scale-out.md, run as written with 2 local jobs: their files
//! are byte for byte those of one run. CI installs GNU parallel (.ci/run); elsewhere, a machine
//! without it fails here with a message that says so.

use std::path::Path;
use std::process::Command;

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// Fails with an explanation when GNU parallel is not installed.
fn require_parallel() {
    let found = Command::new("parallel")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success() && String::from_utf8_lossy(&o.stdout).contains("GNU"));
    assert!(
        found,
        "GNU parallel is not installed: this test runs the recipe of docs/scale-out.md with it \
         (apt-get install parallel; CI's .ci/run installs it)"
    );
}

/// Runs `command` in `dir` with RASTRAY naming the built binary, and expects success.
fn run(command: &mut Command, dir: &Path) {
    let o = command
        .current_dir(dir)
        .env("RASTRAY", env!("CARGO_BIN_EXE_rastray"))
        .env("RASTRAY_CONFIG", "/nonexistent/rastray-test-config.toml")
        .output()
        .expect("runs");
    assert!(
        o.status.success(),
        "{command:?}: {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

fn script(name: &str) -> Command {
    Command::new(Path::new(ROOT).join("scripts/scale-out").join(name))
}

fn rastray() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
}

/// The files of `dir`, sorted by name, with their bytes.
fn files(dir: &Path) -> Vec<(std::ffi::OsString, Vec<u8>)> {
    let mut out: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .map(|e| (e.file_name(), std::fs::read(e.path()).unwrap()))
        .collect();
    out.sort();
    out
}

#[test]
fn a_turntable_split_over_two_parallel_jobs_is_the_file_of_one_run() {
    require_parallel();
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let scene = Path::new(ROOT).join("scenes/default.toml");
    let scene = scene.to_str().unwrap();
    let flags = ["-s", "32x18", "-a", "gouraud"];
    run(
        script("parallel-turntable.sh")
            .args([scene, "10", "2", "parallel.gif"])
            .args(flags),
        at,
    );
    run(
        rastray()
            .args(["render", scene, "--turntable", "10", "-o", "one.gif"])
            .args(flags),
        at,
    );
    let (parallel, one) = (
        std::fs::read(at.join("parallel.gif")).unwrap(),
        std::fs::read(at.join("one.gif")).unwrap(),
    );
    assert!(
        parallel == one,
        "the joined turntable differs from one run's"
    );
}

#[test]
fn thumbnails_split_over_two_parallel_jobs_are_the_files_of_one_run() {
    require_parallel();
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let data = Path::new(ROOT).join("tests/data");
    let models: Vec<String> = [
        "obj/cube.obj",
        "gltf/box.glb",
        "stl/cube_binary.stl",
        "ply/cube_colors_binary.ply",
        "gltf/BoxVertexColors.glb",
    ]
    .iter()
    .map(|m| data.join(m).to_str().unwrap().to_string())
    .collect();
    run(
        script("parallel-thumbnails.sh")
            .args(["parallel", "2"])
            .args(&models)
            .args(["--", "-s", "24x24"]),
        at,
    );
    run(
        rastray()
            .args(["render", "-s", "24x24", "-o", "one/{stem}.png"])
            .args(&models),
        at,
    );
    let one = files(&at.join("one"));
    assert_eq!(one.len(), 5);
    assert_eq!(files(&at.join("parallel")), one);
}
