//! The habits of a command-line tool: shell completions and a man page, a config file whose
//! defaults a flag always overrides, the CPU features in `--version`, mistyped commands caught,
//! and a model read from standard input.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");

/// `rastray ARGS` in `dir` with the config file at `config`.
fn rastray_with(config: &Path, args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .env("RASTRAY_CONFIG", config)
        .stdin(Stdio::null())
        .output()
        .expect("runs")
}

/// `rastray ARGS` in `dir` with no config file.
fn rastray(args: &[&str], dir: &Path) -> Output {
    rastray_with(&dir.join("no-such-config.toml"), args, dir)
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

fn has(program: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {program}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn completions_load_in_bash_and_the_man_page_renders() {
    let bin = env!("CARGO_BIN_EXE_rastray");
    let o = Command::new("bash")
        .args([
            "-c",
            &format!("source <('{bin}' completions bash) && complete -p rastray"),
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o.stderr));
    assert!(text(&o.stdout).contains("rastray"), "{}", text(&o.stdout));
    let dir = tempfile::tempdir().unwrap();
    for shell in ["zsh", "fish", "elvish", "powershell"] {
        let o = rastray(&["completions", shell], dir.path());
        assert!(o.status.success() && o.stdout.len() > 100, "{shell}");
        assert!(text(&o.stdout).contains("render"), "{shell}");
    }
    let page = rastray(&["man"], dir.path());
    assert!(page.status.success());
    assert!(text(&page.stdout).contains(".TH rastray"), "a roff page");
    if has("man") {
        let o = Command::new("sh")
            .args(["-c", &format!("'{bin}' man | man -l -")])
            .env("MANPAGER", "cat")
            .env("MANWIDTH", "80")
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", text(&o.stderr));
        assert!(text(&o.stdout).contains("NAME"), "{}", text(&o.stdout));
    }
}

#[test]
fn the_config_file_sets_defaults_that_flags_and_no_config_override() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let config = at.join("config.toml");
    std::fs::write(&config, "# mine\nalgorithm = \"ray\"\nsize = \"16x8\"\n").unwrap();
    let model = format!("{DATA}/obj/cube.obj");
    let render = |extra: &[&str]| {
        let mut args = vec!["render", &model, "-o", "out.png"];
        args.extend(extra);
        let o = rastray_with(&config, &args, at);
        assert!(o.status.success(), "{extra:?}: {}", text(&o.stderr));
        let size = image::image_dimensions(at.join("out.png")).unwrap();
        (text(&o.stdout), size)
    };
    let (said, size) = render(&[]);
    assert!(said.starts_with("Ray 16x8"), "{said}");
    assert_eq!(size, (16, 8));
    let (said, _) = render(&["-a", "gouraud"]);
    assert!(said.starts_with("Gouraud 16x8"), "the flag wins: {said}");
    let (said, size) = render(&["--no-config", "-s", "8x4"]);
    assert!(said.starts_with("Phong 8x4"), "no config: {said}");
    assert_eq!(size, (8, 4));
    let shown = rastray_with(&config, &["config"], at);
    let shown = text(&shown.stdout);
    assert!(
        shown.contains("config.toml (from RASTRAY_CONFIG)")
            && shown.contains("algorithm = \"ray\"")
            && shown.contains("size = \"16x8\""),
        "{shown}"
    );
    assert!(
        !shown.contains("samples"),
        "only the values it sets: {shown}"
    );
    let none = text(&rastray_with(&config, &["config", "--no-config"], at).stdout);
    assert!(none.contains("--no-config"), "{none}");
    // A bad key: the file, its line and the key, exit code 2, nothing rendered.
    std::fs::write(&config, "size = \"16x8\"\n\nalgoritm = \"ray\"\n").unwrap();
    let o = rastray_with(&config, &["render", &model, "-o", "bad.png"], at);
    assert_eq!(o.status.code(), Some(2));
    let stderr = text(&o.stderr);
    assert!(stderr.contains("config.toml:3: key `algoritm`"), "{stderr}");
    assert!(!at.join("bad.png").exists());
    std::fs::write(&config, "samples = 12\n").unwrap();
    let o = rastray_with(&config, &["config"], at);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr).contains(":1: key `samples`"),
        "{}",
        text(&o.stderr)
    );
}

#[test]
fn the_version_names_the_cpu_features_in_use() {
    let dir = tempfile::tempdir().unwrap();
    let o = rastray(&["--version"], dir.path());
    let said = text(&o.stdout);
    assert!(said.starts_with("rastray 0."), "{said}");
    assert!(said.contains("CPU features in use: "), "{said}");
    #[cfg(target_arch = "x86_64")]
    {
        let avx2 = std::arch::is_x86_feature_detected!("avx2");
        assert_eq!(said.contains("AVX2"), avx2, "{said}");
        if !std::arch::is_x86_feature_detected!("avx512f") {
            assert!(!said.contains("AVX-512"), "{said}");
        }
    }
}

#[test]
fn a_mistyped_command_is_caught_and_a_new_scene_needs_a_toml_name() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    for (args, says) in [
        (&["veiw"][..], "did you mean 'view'?"),
        (&["rendr", "x.png"], "did you mean 'render'?"),
        (&["ifno"], "did you mean 'info'?"),
        (&["myscene"], "a new scene needs a .toml name"),
    ] {
        let o = rastray(args, at);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            text(&o.stderr).contains(says),
            "{args:?}: {}",
            text(&o.stderr)
        );
        assert!(!at.join(args[0]).exists(), "no scene made");
    }
}

#[test]
fn a_model_is_read_from_standard_input() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let pipe = |format: &str, bytes: &[u8], out: &str| {
        let mut child = Command::new(env!("CARGO_BIN_EXE_rastray"))
            .args([
                "--no-config",
                "render",
                "-",
                "--input-format",
                format,
                "-s",
                "12x12",
            ])
            .args(["-o", out])
            .current_dir(at)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        child.stdin.take().unwrap().write_all(bytes).unwrap();
        child.wait_with_output().unwrap()
    };
    for (format, file) in [
        ("glb", "gltf/box.glb"),
        ("obj", "obj/cube.obj"),
        ("stl", "stl/cube_binary.stl"),
        ("ply", "ply/cube_colors_binary.ply"),
    ] {
        let bytes = std::fs::read(Path::new(DATA).join(file)).unwrap();
        let o = pipe(format, &bytes, "piped.png");
        assert!(o.status.success(), "{format}: {}", text(&o.stderr));
        let from_pipe = std::fs::read(at.join("piped.png")).unwrap();
        let o = rastray(
            &[
                "render",
                &format!("{DATA}/{file}"),
                "-s",
                "12x12",
                "-o",
                "file.png",
            ],
            at,
        );
        assert!(o.status.success());
        assert_eq!(
            from_pipe,
            std::fs::read(at.join("file.png")).unwrap(),
            "{format}"
        );
    }
    // A broken model from a pipe is named `-`, with its line.
    let o = pipe("obj", b"v 1 2\n", "x.png");
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o.stderr).contains("-:1:"), "{}", text(&o.stderr));
    let o = rastray(&["render", "-", "-o", "x.png"], at);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr).contains("--input-format"),
        "{}",
        text(&o.stderr)
    );
}
