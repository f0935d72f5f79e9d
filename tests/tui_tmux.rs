//! End to end: the real binary in a detached tmux session, driven with keys like a user would.
//! Adds a box, colours it, switches to ray tracing, exports a PNG, saves and quits, then checks
//! the screen, the PNG and the saved scene. Skipped with a message when tmux is not installed.

use std::path::Path;
use std::process::{Command, Output};
use std::time::{Duration, Instant};

/// How long any one expected screen may take to appear (slow CI machines included).
const TIMEOUT: Duration = Duration::from_secs(60);

/// A tmux server of our own (its own socket), killed on drop.
struct Tmux {
    socket: String,
}

impl Tmux {
    fn run(&self, args: &[&str]) -> Output {
        Command::new("tmux")
            .args(["-L", &self.socket])
            .args(args)
            .output()
            .expect("tmux runs")
    }

    fn keys(&self, keys: &[&str]) {
        let mut args = vec!["send-keys", "-t", "e2e"];
        args.extend(keys);
        assert!(self.run(&args).status.success(), "send-keys {keys:?}");
    }

    fn text(&self, text: &str) {
        assert!(
            self.run(&["send-keys", "-t", "e2e", "-l", text])
                .status
                .success()
        );
    }

    fn screen(&self) -> String {
        String::from_utf8_lossy(&self.run(&["capture-pane", "-p", "-t", "e2e"]).stdout).into_owned()
    }

    /// Polls the screen until it contains `needle`; panics with the last screen on timeout.
    fn wait_for(&self, needle: &str) -> String {
        let start = Instant::now();
        loop {
            let screen = self.screen();
            if screen.contains(needle) {
                return screen;
            }
            if start.elapsed() > TIMEOUT {
                panic!("`{needle}` did not appear within {TIMEOUT:?}; the screen was:\n{screen}");
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Tmux {
    fn drop(&mut self) {
        let _ = self.run(&["kill-server"]);
    }
}

fn tmux_available() -> bool {
    Command::new("tmux")
        .arg("-V")
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn add_colour_ray_export_save_quit() {
    if !tmux_available() {
        eprintln!(
            "tui_tmux: tmux is not installed; skipping the end-to-end editor test (.ci/run installs it)"
        );
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let tmux = Tmux {
        socket: format!("rastray-e2e-{}", std::process::id()),
    };
    let command = format!(
        "{}; echo EXITED $?; sleep 600",
        env!("CARGO_BIN_EXE_rastray")
    );
    let status = tmux.run(&[
        "new-session",
        "-d",
        "-s",
        "e2e",
        "-x",
        "120",
        "-y",
        "40",
        "-c",
        dir.path().to_str().unwrap(),
        &command,
    ]);
    assert!(status.status.success(), "tmux new-session: {status:?}");
    tmux.wait_for("camera & scene");
    tmux.wait_for(" ms │");

    // Add a box: the default scene has two, so this is "box 3", selected.
    tmux.keys(&["a", "b"]);
    tmux.wait_for("added box 3");

    // Its properties: name, center ×3, size ×3, segments, rotation ×3, then color.r.
    tmux.keys(&["Tab"]);
    for _ in 0..11 {
        tmux.keys(&["j"]);
    }
    tmux.keys(&["Enter", "C-u"]);
    tmux.text("0.1");
    tmux.keys(&["Enter"]);
    let screen = tmux.wait_for("color.r         0.1 ");
    assert!(screen.contains("● modified"), "{screen}");

    // Ray tracing.
    tmux.keys(&["3"]);
    tmux.wait_for("Preview · Ray");

    // Export a small PNG with the ray tracer.
    tmux.keys(&["e"]);
    tmux.wait_for("┏ Export ━");
    tmux.keys(&["C-u"]);
    tmux.text("out.png");
    tmux.keys(&["Down", "C-u"]);
    tmux.text("160x90");
    tmux.keys(&["Enter"]);
    tmux.wait_for("exported out.png");

    // Save: the built-in scene has no file, so a path is asked for.
    tmux.keys(&["s"]);
    tmux.wait_for("Save scene as");
    tmux.keys(&["C-u"]);
    tmux.text("mine.toml");
    tmux.keys(&["Enter"]);
    let screen = tmux.wait_for("saved mine.toml");
    assert!(!screen.contains("● modified"), "{screen}");

    tmux.keys(&["q"]);
    tmux.wait_for("EXITED 0");

    let png = dir.path().join("out.png");
    let image = image::open(&png).expect("the exported PNG decodes");
    assert_eq!((image.width(), image.height()), (160, 90));

    let saved =
        rastray::scene::load(&dir.path().join("mine.toml")).expect("the saved scene parses");
    let added = saved
        .objects
        .iter()
        .find(|o| o.name.as_deref() == Some("box 3"))
        .expect("the saved scene holds the new box");
    assert_eq!(added.shape.kind(), rastray::scene::ShapeKind::Box);
    assert_eq!(added.material.color.x, 0.1);
    assert!(Path::new(&dir.path().join("mine.toml")).is_file());
}
