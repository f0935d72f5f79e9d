//! `rastray render IN... -o TEMPLATE`: many inputs in one process, a failing file reported and
//! skipped, shards that together write one run's files byte for byte, turntables rendered as
//! frame ranges and joined into the file one `--turntable` run writes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");

fn rastray(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .current_dir(dir)
        .env("RASTRAY_CONFIG", "/nonexistent/rastray-test-config.toml")
        .output()
        .expect("runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Runs `rastray ARGS` in `dir` and expects success.
fn ok(args: &[&str], dir: &Path) -> Output {
    let o = rastray(args, dir);
    assert!(o.status.success(), "{args:?}: {}", text(&o.stderr));
    o
}

/// Copies the small test models into `dir`: three that load, with distinct stems.
fn three_models(dir: &Path) -> [&'static str; 3] {
    for (from, to) in [
        ("obj/cube.obj", "cube.obj"),
        ("gltf/box.glb", "box.glb"),
        ("stl/cube_binary.stl", "wedge.stl"),
    ] {
        std::fs::copy(Path::new(DATA).join(from), dir.join(to)).unwrap();
    }
    ["cube.obj", "box.glb", "wedge.stl"]
}

/// [`three_models`] and `broken.obj`, which fails on its first line.
fn three_models_and_a_broken_one(dir: &Path) -> [&'static str; 4] {
    let [a, b, c] = three_models(dir);
    std::fs::write(dir.join("broken.obj"), "v 1 2\n").unwrap();
    [a, b, c, "broken.obj"]
}

/// The files under `dir`, sorted, with their bytes.
fn files(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| {
            (
                PathBuf::from(p.file_name().unwrap()),
                std::fs::read(&p).unwrap(),
            )
        })
        .collect();
    out.sort();
    out
}

#[test]
fn three_models_and_a_broken_file_give_three_images_an_error_line_and_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let mut args = vec!["render", "-s", "24x16", "-o", "out/{stem}.png"];
    args.extend(three_models_and_a_broken_one(at));
    let o = rastray(&args, at);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    let written: Vec<PathBuf> = files(&at.join("out")).into_iter().map(|f| f.0).collect();
    assert_eq!(
        written,
        ["box.png", "cube.png", "wedge.png"].map(PathBuf::from),
        "the folder was made and the three images written"
    );
    for (name, bytes) in files(&at.join("out")) {
        let image = image::load_from_memory(&bytes).expect("a PNG");
        assert_eq!((image.width(), image.height()), (24, 16), "{name:?}");
    }
    let stderr = text(&o.stderr);
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    assert!(errors[0].contains("broken.obj:1"), "{stderr}");
    let summary = stderr.lines().last().unwrap();
    assert!(
        summary.contains("3 of 4 inputs") && summary.contains("failed: broken.obj"),
        "{stderr}"
    );
    let stdout = text(&o.stdout);
    assert_eq!(stdout.lines().filter(|l| l.contains("wrote")).count(), 3);
}

#[test]
fn several_inputs_need_a_template_that_tells_them_apart() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let [a, b, _] = three_models(at);
    for template in ["out.png", "{algo}.png", "-"] {
        let o = rastray(&["render", "-s", "8x8", "-o", template, a, b], at);
        assert_eq!(o.status.code(), Some(2), "{template}");
        assert!(
            text(&o.stderr).contains("{stem}, {name} or {index}"),
            "{}",
            text(&o.stderr)
        );
        assert!(o.stdout.is_empty(), "nothing rendered");
    }
    assert!(!at.join("out.png").exists() && !at.join("phong.png").exists());
    // Two inputs with one stem in two folders: refused before anything renders.
    std::fs::create_dir(at.join("again")).unwrap();
    std::fs::copy(at.join(a), at.join("again").join(a)).unwrap();
    let o = rastray(
        &[
            "render",
            "-s",
            "8x8",
            "-o",
            "{stem}.png",
            a,
            "again/cube.obj",
        ],
        at,
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr).contains("again/cube.obj"),
        "{}",
        text(&o.stderr)
    );
    assert!(!at.join("cube.png").exists());
    // {index} counts the sorted inputs from 0; {algo} names the algorithm.
    ok(
        &[
            "render",
            "-s",
            "8x8",
            "-a",
            "gouraud",
            "-o",
            "{index:02}-{algo}.png",
            b,
            a,
        ],
        at,
    );
    assert!(at.join("00-gouraud.png").exists() && at.join("01-gouraud.png").exists());
}

#[test]
fn a_template_never_writes_over_an_input_and_its_fields_need_their_flags() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let [a, b, _] = three_models(at);
    let before = std::fs::read(at.join(a)).unwrap();
    let o = rastray(&["render", "-s", "8x8", "-o", "{name}", a, b], at);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        text(&o.stderr).contains("refusing to write over it"),
        "{}",
        text(&o.stderr)
    );
    assert_eq!(std::fs::read(at.join(a)).unwrap(), before);
    for (args, says) in [
        (&["-o", "{frame}.png"][..], "needs --turntable"),
        (
            &["--turntable", "4", "--frames", "0..1", "-o", "a.gif"],
            "put {frame}",
        ),
        (
            &["--turntable", "4", "--frames", "2..4", "-o", "{frame}.png"],
            "frames 0 to 3",
        ),
        (&["-o", "{stem.png"], "not closed"),
        (&["-o", "{view}.png"], "needs --view"),
        (&["--shard", "3/2"], "I/N"),
    ] {
        let mut all = vec!["render", "-s", "8x8", a];
        all.extend(args);
        let o = rastray(&all, at);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            text(&o.stderr).contains(says),
            "{args:?}: {}",
            text(&o.stderr)
        );
    }
}

#[test]
fn two_shards_write_exactly_the_files_of_one_run() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let models = three_models(at);
    let render = |out: &str, shard: Option<&str>| {
        let template = format!("{out}/{{stem}}.png");
        let mut args = vec!["render", "-s", "20x12", "-o", &template];
        if let Some(shard) = shard {
            args.extend(["--shard", shard]);
        }
        // Listed in another order each time: the shards follow the sorted order.
        let mut listed = models.to_vec();
        if shard == Some("2/2") {
            listed.reverse();
        }
        args.extend(listed);
        ok(&args, at)
    };
    render("whole", None);
    let first = render("parts", Some("1/2"));
    let one = files(&at.join("parts")).len();
    assert!(
        (1..3).contains(&one),
        "shard 1/2 wrote {one}: {}",
        text(&first.stdout)
    );
    render("parts", Some("2/2"));
    assert_eq!(files(&at.join("parts")), files(&at.join("whole")));
}

#[test]
fn a_turntable_in_two_frame_ranges_joins_into_the_file_of_one_run() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let [_, model, _] = three_models(at);
    for (extra, animation) in [(&[][..], "spin.gif"), (&["--transparent"][..], "spin.png")] {
        let common = |more: &[&str]| {
            let mut args = vec!["render", model, "-s", "24x16", "--turntable", "6"];
            args.extend(extra);
            args.extend(more);
            ok(&args, at)
        };
        common(&["-o", animation]);
        let folder = format!("frames-{animation}");
        let template = format!("{folder}/{{frame:04}}.png");
        common(&["--frames", "0..3", "-o", &template]);
        common(&["--frames", "4..5", "-o", &template]);
        let frames: Vec<String> = files(&at.join(&folder))
            .into_iter()
            .map(|(name, _)| format!("{folder}/{}", name.display()))
            .collect();
        assert_eq!(frames.len(), 6);
        assert_eq!(frames[0], format!("{folder}/0000.png"));
        let joined = format!("joined-{animation}");
        let mut args = vec!["join", "-o", &joined];
        args.extend(frames.iter().map(String::as_str));
        ok(&args, at);
        assert!(
            std::fs::read(at.join(&joined)).unwrap() == std::fs::read(at.join(animation)).unwrap(),
            "{joined} differs from {animation}"
        );
    }
}

#[test]
fn join_refuses_frames_that_do_not_match() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let [model, _, _] = three_models(at);
    ok(&["render", model, "-s", "8x8", "-o", "a.png"], at);
    ok(&["render", model, "-s", "9x8", "-o", "b.png"], at);
    ok(
        &[
            "render", model, "-s", "8x8", "--format", "png16", "-o", "deep.png",
        ],
        at,
    );
    std::fs::write(at.join("text.png"), "not a png").unwrap();
    for (frames, says) in [
        (&["a.png", "b.png"][..], "b.png: this frame is 9x8"),
        (&["a.png", "text.png"], "text.png: not a PNG"),
        (&["deep.png"], "8-bit frames"),
    ] {
        let mut args = vec!["join", "-o", "spin.gif"];
        args.extend(frames);
        let o = rastray(&args, at);
        assert_eq!(o.status.code(), Some(2), "{frames:?}");
        assert!(
            text(&o.stderr).contains(says),
            "{frames:?}: {}",
            text(&o.stderr)
        );
        assert!(!at.join("spin.gif").exists(), "nothing left behind");
    }
}

#[cfg(unix)]
#[test]
fn templated_outputs_stream_to_fifos() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let [a, b, _] = three_models(at);
    let readers: Vec<_> = ["box", "cube"]
        .into_iter()
        .map(|stem| {
            let fifo = at.join(format!("{stem}.png"));
            rustix::fs::mknodat(
                rustix::fs::CWD,
                &fifo,
                rustix::fs::FileType::Fifo,
                rustix::fs::Mode::from_raw_mode(0o600),
                0,
            )
            .unwrap();
            std::thread::spawn(move || std::fs::read(fifo).unwrap())
        })
        .collect();
    ok(&["render", "-s", "8x8", "-o", "{stem}.png", a, b], at);
    for reader in readers {
        let bytes = reader.join().unwrap();
        assert!(bytes.starts_with(b"\x89PNG"), "a PNG came down the FIFO");
    }
}

#[test]
fn a_contact_sheet_lays_out_titled_thumbnails_and_skips_a_broken_file() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let mut args = vec!["render", "--sheet", "sheet.png", "--cell", "40x30"];
    args.extend(["--columns", "3"]);
    args.extend(three_models_and_a_broken_one(at));
    let o = rastray(&args, at);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    assert!(
        text(&o.stderr).contains("error: broken.obj:1"),
        "{}",
        text(&o.stderr)
    );
    let sheet = image::open(at.join("sheet.png")).unwrap().to_rgb8();
    // Three thumbnails in three columns: one row of 30 pixels and a 20-pixel title strip.
    assert_eq!(sheet.dimensions(), (120, 50));
    for column in 0..3 {
        let strip = (column * 40..column * 40 + 40)
            .flat_map(|x| (30..50).map(move |y| (x, y)))
            .filter(|&(x, y)| sheet.get_pixel(x, y)[0] > 120)
            .count();
        assert!(strip > 10, "column {column} has a title");
    }
    // Each cell is the model's own 40x30 render.
    ok(&["render", "-s", "40x30", "-o", "alone.png", "box.glb"], at);
    let alone = image::open(at.join("alone.png")).unwrap().to_rgb8();
    for (x, y) in [(5, 5), (20, 15), (35, 25)] {
        assert_eq!(sheet.get_pixel(x, y), alone.get_pixel(x, y), "({x}, {y})");
    }
}

#[test]
fn view_grid_draws_rows_of_titled_thumbnails_and_skips_a_broken_file() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let mut args = vec!["view", "--grid", "--graphics", "halfblock"];
    args.extend(["--width", "41", "--columns", "2"]);
    // The broken file first: the first input is skipped as any other.
    let [a, b, c, broken] = three_models_and_a_broken_one(at);
    args.extend([broken, a, b, c]);
    let o = rastray(&args, at);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o.stderr));
    let stderr = text(&o.stderr);
    assert!(stderr.contains("error: broken.obj:1"), "{stderr}");
    assert!(stderr.contains("failed: broken.obj"), "{stderr}");
    let stdout = text(&o.stdout);
    let lines: Vec<&str> = stdout.lines().collect();
    // Two thumbnails of 20 columns a row, square on 10×20-pixel cells: 10 rows of cells, then
    // the titles. Three models sorted by name make two rows.
    assert_eq!(lines.len(), 22, "{stdout}");
    assert_eq!(lines[10].trim(), "box                  cube");
    assert_eq!(lines[21].trim(), "wedge");
    for picture in lines[..10].iter().chain(&lines[11..21]) {
        assert!(picture.contains('\x1b'), "a picture line: {picture:?}");
    }
    // In pixels: one picture a row.
    args[3] = "kitty";
    let o = rastray(&args, at);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(text(&o.stdout).matches("\x1b_Ga=T").count(), 2);
    // Several inputs without --grid are refused.
    let o = rastray(&["view", "cube.obj", "box.glb"], at);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o.stderr));
}

#[test]
fn turntables_in_one_batch_are_the_files_each_run_alone_writes() {
    // The batch keeps its turntable renderers, frames and threads from one file to the next;
    // nothing of one turntable may reach the next.
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let [a, b, c] = three_models(at);
    let turntable = |output: &str, inputs: &[&str]| {
        let mut args = vec![
            "render",
            "--turntable",
            "4",
            "-s",
            "48x32",
            "--threads",
            "2",
        ];
        args.extend(["-o", output]);
        args.extend(inputs);
        ok(&args, at);
    };
    turntable("batch/{stem}.gif", &[a, b, c]);
    for model in [a, b, c] {
        let stem = Path::new(model).file_stem().unwrap().to_str().unwrap();
        let alone = format!("alone-{stem}.gif");
        turntable(&alone, &[model]);
        let batch = std::fs::read(at.join(format!("batch/{stem}.gif"))).unwrap();
        assert_eq!(batch, std::fs::read(at.join(&alone)).unwrap(), "{model}");
    }
}
