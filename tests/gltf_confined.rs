//! A glTF model reads files from its own folder and below it, and nothing else: buffer URIs that
//! climb out with `..`, absolute paths, percent-encoded escapes and symlinks out of the folder are
//! refused with exit code 2 and a message naming the model and the URI. The file outside is a
//! FIFO: opening it for reading would block until a writer came, so a run that returns at all
//! (within the time limit) has not opened it.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use serde_json::{Value, json};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/gltf")
        .join(name)
}

/// A folder `outside/` holding a FIFO `secret.bin`, and beside it `model/` with the box's buffer
/// and a scene showing `model/box.gltf`.
struct Layout {
    dir: tempfile::TempDir,
}

impl Layout {
    fn new() -> Layout {
        let dir = tempfile::tempdir().expect("tempdir");
        std::fs::create_dir(dir.path().join("outside")).expect("outside");
        std::fs::create_dir(dir.path().join("model")).expect("model");
        rustix::fs::mkfifoat(
            rustix::fs::CWD,
            dir.path().join("outside/secret.bin"),
            rustix::fs::Mode::from_raw_mode(0o644),
        )
        .expect("fifo");
        std::fs::copy(data("box data.bin"), dir.path().join("model/box data.bin")).expect("copy");
        std::fs::write(
            dir.path().join("model/scene.toml"),
            "[camera]\nposition = [0.0, 0.0, 6.0]\n[[light]]\nposition = [0.0, 3.0, 6.0]\n\
             [[object]]\ntype = \"mesh\"\npath = \"box.gltf\"\n",
        )
        .expect("scene");
        Layout { dir }
    }

    fn model(&self) -> PathBuf {
        self.dir.path().join("model")
    }

    fn write_model(&self, uri: &str) {
        let mut doc: Value =
            serde_json::from_slice(&std::fs::read(data("box.gltf")).expect("box.gltf"))
                .expect("JSON");
        doc["buffers"][0]["uri"] = json!(uri);
        std::fs::write(self.model().join("box.gltf"), doc.to_string()).expect("write");
    }

    /// Runs rastray in the model's folder; a run still going after 20 s is killed and fails the
    /// test (it would be waiting on the FIFO outside).
    fn run(&self, args: &[&str]) -> Output {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rastray"))
            .args(args)
            .current_dir(self.model())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("spawn");
        let start = Instant::now();
        while child.try_wait().expect("wait").is_none() {
            if start.elapsed() > Duration::from_secs(20) {
                child.kill().ok();
                panic!("{args:?} hung: it opened the FIFO outside the model's folder");
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        child.wait_with_output().expect("output")
    }

    /// `info` and `render` refuse the model with exit 2 and one line naming the model and `uri`.
    fn refused(&self, uri: &str) {
        self.write_model(uri);
        for args in [
            &["info", "scene.toml"][..],
            &["render", "scene.toml", "-s", "16x16", "-o", "out.png"],
            &["info", "box.gltf"],
        ] {
            let o = self.run(args);
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{uri} {args:?}: {stderr}");
            assert!(stderr.starts_with("error: "), "{stderr}");
            assert!(!stderr.contains("panicked"), "{stderr}");
            assert!(stderr.contains("box.gltf"), "names the model: {stderr}");
            assert!(
                stderr.contains(&format!("`{uri}`")),
                "names the URI: {stderr}"
            );
            assert!(
                stderr.contains("outside the model's folder"),
                "says why: {stderr}"
            );
        }
        assert!(!self.model().join("out.png").exists());
    }
}

#[test]
fn buffer_uris_that_climb_out_are_refused_without_opening_the_file() {
    let layout = Layout::new();
    layout.refused("../outside/secret.bin");
    layout.refused("%2e%2e/outside/secret.bin");
    layout.refused("%2E%2E%2Foutside%2Fsecret.bin");
    layout.refused("sub/../../outside/secret.bin");
    let absolute = layout.dir.path().join("outside/secret.bin");
    layout.refused(absolute.to_str().expect("UTF-8 path"));
    layout.refused("/etc/passwd");
}

#[test]
fn a_symlink_out_of_the_folder_is_refused_and_one_within_is_followed() {
    let layout = Layout::new();
    let model = layout.model();
    std::os::unix::fs::symlink(
        layout.dir.path().join("outside/secret.bin"),
        model.join("link.bin"),
    )
    .expect("link");
    layout.refused("link.bin");
    std::os::unix::fs::symlink(layout.dir.path().join("outside"), model.join("door"))
        .expect("link");
    layout.refused("door/secret.bin");

    // A link that stays inside the folder is an ordinary file.
    std::fs::create_dir(model.join("buffers")).expect("dir");
    std::fs::rename(model.join("box data.bin"), model.join("buffers/box.bin")).expect("move");
    std::os::unix::fs::symlink(model.join("buffers/box.bin"), model.join("inside.bin"))
        .expect("link");
    for uri in ["inside.bin", "buffers/box.bin", "./buffers/../inside.bin"] {
        layout.write_model(uri);
        let o = layout.run(&["info", "scene.toml"]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{uri}: {stderr}");
    }
}

#[test]
fn a_model_named_from_elsewhere_reads_from_its_own_folder() {
    // The scene may name a model anywhere: confinement is to the model's folder, not the scene's.
    let layout = Layout::new();
    layout.write_model("box%20data.bin");
    let elsewhere = layout.dir.path().join("outside/scene.toml");
    std::fs::write(
        &elsewhere,
        "[camera]\nposition = [0.0, 0.0, 6.0]\n[[light]]\nposition = [0.0, 3.0, 6.0]\n\
         [[object]]\ntype = \"mesh\"\npath = \"../model/box.gltf\"\n",
    )
    .expect("scene");
    let o = layout.run(&["info", elsewhere.to_str().expect("UTF-8")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}
