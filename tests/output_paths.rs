//! Where `rastray render -o PATH` writes, whatever PATH is: a regular file is replaced
//! atomically with the umask's mode, a symlink's target is replaced and the link kept, a
//! character device, FIFO or `-` is written as a stream, an input of the scene is refused, and a
//! signal during the write leaves no temporary file behind. CI runs this as root, where a rename
//! over `/dev/null` would replace the device.

mod common;

use std::os::unix::fs::{FileTypeExt, PermissionsExt};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const PNG_MAGIC: &[u8] = b"\x89PNG\r\n\x1a\n";

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml")
}

fn rastray(dir: &Path) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rastray"));
    command.current_dir(dir);
    command
}

/// `rastray render SCENE -s 32x24 EXTRA… -o OUT` in `dir`.
fn render(dir: &Path, scene: &Path, out: &str, extra: &[&str]) -> Output {
    rastray(dir)
        .arg("render")
        .arg(scene)
        .args(["-s", "32x24"])
        .args(extra)
        .args(["-o", out])
        .output()
        .expect("runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The hidden temporary files left in `dir`.
fn leftovers(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .expect("readable")
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with(".rastray-"))
        .collect()
}

#[test]
fn dev_null_is_written_as_a_stream_and_stays_a_device() {
    let dir = tempfile::tempdir().unwrap();
    let o = render(dir.path(), &scene(), "/dev/null", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let meta = std::fs::metadata("/dev/null").unwrap();
    assert!(meta.file_type().is_char_device(), "/dev/null was replaced");
    assert_eq!(meta.len(), 0);
}

#[test]
fn a_full_device_reports_the_write_error() {
    let dir = tempfile::tempdir().unwrap();
    let o = render(dir.path(), &scene(), "/dev/full", &[]);
    assert_eq!(o.status.code(), Some(2));
    let m = stderr(&o);
    assert!(
        m.starts_with("error: /dev/full: ") && m.contains("No space left on device"),
        "{m}"
    );
    assert!(
        std::fs::metadata("/dev/full")
            .unwrap()
            .file_type()
            .is_char_device()
    );
}

#[test]
fn dash_writes_png_or_the_requested_format_to_standard_output() {
    let dir = tempfile::tempdir().unwrap();
    let o = render(dir.path(), &scene(), "-", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stdout.starts_with(PNG_MAGIC), "stdout is a PNG");
    let image = image::load_from_memory(&o.stdout).expect("decodes");
    assert_eq!((image.width(), image.height()), (32, 24));
    // The summary goes to stderr, so the stream holds the image alone.
    assert!(stderr(&o).contains("wrote -"), "{}", stderr(&o));

    let exr = render(dir.path(), &scene(), "-", &["--format", "exr"]);
    assert!(exr.status.success(), "{}", stderr(&exr));
    assert!(exr.stdout.starts_with(&[0x76, 0x2f, 0x31, 0x01]), "an EXR");

    let spin = render(dir.path(), &scene(), "-", &["--turntable", "2"]);
    assert!(spin.status.success(), "{}", stderr(&spin));
    assert!(spin.stdout.starts_with(PNG_MAGIC), "an animated PNG");
    assert!(leftovers(dir.path()).is_empty());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn a_fifo_is_written_as_a_stream() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("pipe.png");
    common::mkfifo(&fifo);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).expect("reads the FIFO"))
    };
    let o = render(dir.path(), &scene(), "pipe.png", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bytes = reader.join().unwrap();
    assert!(bytes.starts_with(PNG_MAGIC));
    assert!(
        std::fs::symlink_metadata(&fifo)
            .unwrap()
            .file_type()
            .is_fifo()
    );
    assert!(leftovers(dir.path()).is_empty());
}

#[test]
fn a_symlink_is_followed_and_its_target_replaced_beside_it() {
    let dir = tempfile::tempdir().unwrap();
    let elsewhere = tempfile::tempdir().unwrap();
    let target = elsewhere.path().join("target.png");
    std::fs::write(&target, "old").unwrap();
    std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o640)).unwrap();
    std::os::unix::fs::symlink(&target, dir.path().join("link.png")).unwrap();
    let o = render(dir.path(), &scene(), "link.png", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let link = std::fs::symlink_metadata(dir.path().join("link.png")).unwrap();
    assert!(link.file_type().is_symlink(), "the link is kept");
    assert!(std::fs::read(&target).unwrap().starts_with(PNG_MAGIC));
    let mode = std::fs::metadata(&target).unwrap().permissions().mode() & 0o777;
    assert_eq!(mode, 0o640, "the replaced file keeps its mode");
    assert!(leftovers(dir.path()).is_empty() && leftovers(elsewhere.path()).is_empty());

    // A dangling link names the file to create.
    std::os::unix::fs::symlink("made.png", dir.path().join("dangling.png")).unwrap();
    let o = render(dir.path(), &scene(), "dangling.png", &[]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        std::fs::symlink_metadata(dir.path().join("dangling.png"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(
        std::fs::read(dir.path().join("made.png"))
            .unwrap()
            .starts_with(PNG_MAGIC)
    );
}

#[test]
fn new_files_honour_the_umask() {
    let dir = tempfile::tempdir().unwrap();
    for (umask, expected) in [("077", 0o600), ("022", 0o644), ("002", 0o664)] {
        let name = format!("out-{umask}.png");
        let o = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "umask {umask} && exec \"$0\" render \"$1\" -s 16x12 -o \"$2\""
            ))
            .arg(env!("CARGO_BIN_EXE_rastray"))
            .arg(scene())
            .arg(&name)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        let mode = std::fs::metadata(dir.path().join(&name))
            .unwrap()
            .permissions()
            .mode()
            & 0o777;
        assert_eq!(mode, expected, "umask {umask}");
    }
}

#[test]
fn the_scene_and_its_models_are_refused_as_outputs() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("s.toml");
    // An OBJ file whose name says PNG: still a model of the scene.
    std::fs::write(
        dir.path().join("model.png"),
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    std::fs::write(
        &scene,
        "[[light]]\nposition = [0.0, 2.0, 4.0]\n[[object]]\ntype = \"mesh\"\npath = \"model.png\"\n",
    )
    .unwrap();
    let before = std::fs::read(&scene).unwrap();

    let o = render(dir.path(), &scene, "s.toml", &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("an input of the scene"),
        "{}",
        stderr(&o)
    );

    std::os::unix::fs::symlink("s.toml", dir.path().join("out.png")).unwrap();
    let o = render(dir.path(), &scene, "out.png", &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("an input of the scene"),
        "{}",
        stderr(&o)
    );

    let o = render(dir.path(), &scene, "model.png", &[]);
    assert_eq!(o.status.code(), Some(2));
    let m = stderr(&o);
    assert!(
        m.contains("model.png") && m.contains("an input of the scene"),
        "{m}"
    );

    assert_eq!(std::fs::read(&scene).unwrap(), before);
    assert!(
        std::fs::read(dir.path().join("model.png"))
            .unwrap()
            .starts_with(b"v 0 0 0")
    );
    assert!(leftovers(dir.path()).is_empty());
}

#[test]
fn an_unknown_extension_names_the_formats() {
    let dir = tempfile::tempdir().unwrap();
    let o = render(dir.path(), &scene(), "out.jpg", &[]);
    assert_eq!(o.status.code(), Some(2));
    let m = stderr(&o);
    assert!(
        m.contains("`.jpg` is none of them") && m.contains(".png") && m.contains(".exr"),
        "{m}"
    );
    assert!(!dir.path().join("out.jpg").exists());
}

/// The files in `dir` that process `pid` has open, as `/proc` names them: a temporary file
/// with no name yet (`O_TMPFILE`) shows as `dir/#1234 (deleted)`.
fn open_in(pid: u32, dir: &Path) -> Vec<String> {
    let Ok(fds) = std::fs::read_dir(format!("/proc/{pid}/fd")) else {
        return Vec::new();
    };
    fds.filter_map(|fd| std::fs::read_link(fd.ok()?.path()).ok())
        .filter(|target| target.starts_with(dir))
        .map(|target| target.display().to_string())
        .collect()
}

/// Starts a long turntable into `dir/spin.gif`, waits until its temporary file is open, sends
/// `signal`, and returns how the process ended.
fn signal_during_write(dir: &Path, signal: rustix::process::Signal) -> (Output, Vec<String>) {
    let child = rastray(dir)
        .arg("render")
        .arg(scene())
        .args(["-s", "320x240", "--turntable", "3600", "-o", "spin.gif"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("starts");
    let started = Instant::now();
    let seen = loop {
        let found = open_in(child.id(), dir);
        if !found.is_empty() || started.elapsed() > Duration::from_secs(60) {
            break found;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let pid = rustix::process::Pid::from_raw(child.id() as i32).expect("a pid");
    rustix::process::kill_process(pid, signal).expect("signals");
    (child.wait_with_output().expect("ends"), seen)
}

#[test]
fn a_signal_during_the_write_leaves_no_temporary_file() {
    use rustix::process::Signal;
    for (signal, code) in [(Signal::TERM, 143), (Signal::INT, 130)] {
        let dir = tempfile::tempdir().unwrap();
        let (o, seen) = signal_during_write(dir.path(), signal);
        assert_eq!(seen.len(), 1, "the temporary file existed: {seen:?}");
        assert_eq!(
            o.status.code(),
            Some(code),
            "{:?} {}",
            o.status.signal(),
            stderr(&o)
        );
        assert!(stderr(&o).contains("not written"), "{}", stderr(&o));
        assert!(
            leftovers(dir.path()).is_empty(),
            "{:?}",
            leftovers(dir.path())
        );
        assert!(!dir.path().join("spin.gif").exists());
    }
}

#[test]
fn sigkill_in_the_middle_of_a_turntable_leaves_no_file() {
    let dir = tempfile::tempdir().unwrap();
    let (o, seen) = signal_during_write(dir.path(), rustix::process::Signal::KILL);
    assert_eq!(seen.len(), 1, "the temporary file was open: {seen:?}");
    assert_eq!(o.status.signal(), Some(9));
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert!(names.is_empty(), "nothing left in the folder: {names:?}");
}
