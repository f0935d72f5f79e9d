//! `rastray render` writing each format: the extension or `--format` chooses it, a mismatch is
//! refused before anything renders, `--transparent` adds alpha and `--turntable` animates.

use std::path::Path;
use std::process::{Command, Output};

fn rastray(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(["render", "-s", "32x18"])
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Runs `rastray render` and expects it to succeed.
fn render(args: &[&str], dir: &Path) -> String {
    let o = rastray(args, dir);
    assert!(o.status.success(), "{args:?}: {}", text(&o.stderr));
    text(&o.stdout)
}

#[test]
fn the_extension_or_format_chooses_the_encoding() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    render(&["-o", "plain.png"], at);
    render(&["--format", "png16", "-o", "deep.png"], at);
    render(&["-o", "linear.exr"], at);
    render(&["--transparent", "--samples", "2", "-o", "clear.png"], at);
    let color = |name: &str| image::open(at.join(name)).expect(name).color();
    assert_eq!(color("plain.png"), image::ColorType::Rgb8);
    assert_eq!(color("deep.png"), image::ColorType::Rgb16);
    assert_eq!(color("linear.exr"), image::ColorType::Rgb32F);
    assert_eq!(color("clear.png"), image::ColorType::Rgba8);
    let clear = image::open(at.join("clear.png")).unwrap().to_rgba8();
    assert_eq!(clear.get_pixel(0, 0)[3], 0, "the sky is transparent");
}

#[test]
fn a_name_that_does_not_match_the_format_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    for (args, says) in [
        (&["-o", "out.jpg"][..], "`.jpg` is none of them"),
        (
            &["--format", "exr", "-o", "out.png"],
            "format exr writes .exr files",
        ),
        (&["-o", "still.gif"], "turntables only"),
        (
            &["--turntable", "4", "-o", "spin.exr"],
            "a turntable is written as .gif or .png",
        ),
    ] {
        let o = rastray(args, at);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let stderr = text(&o.stderr);
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "one clear line: {stderr}");
    }
    let listing = text(&rastray(&["-o", "out.jpg"], at).stderr);
    for format in [".png", ".exr", ".gif", "out.jpg"] {
        assert!(listing.contains(format), "names {format}: {listing}");
    }
    assert_eq!(std::fs::read_dir(at).unwrap().count(), 0, "nothing written");
    let o = rastray(&["--fps", "10", "-o", "x.png"], at);
    assert_eq!(o.status.code(), Some(2), "--fps needs --turntable");
}

#[test]
fn a_turntable_is_written_and_reported() {
    let dir = tempfile::tempdir().unwrap();
    let at = dir.path();
    let stdout = render(&["--turntable", "5", "--fps", "10", "-o", "spin.gif"], at);
    assert!(
        stdout.contains("5 frames") && stdout.contains("spin.gif"),
        "{stdout}"
    );
    let file = std::io::BufReader::new(std::fs::File::open(at.join("spin.gif")).unwrap());
    let decoder = image::codecs::gif::GifDecoder::new(file).expect("a GIF");
    let frames = image::AnimationDecoder::into_frames(decoder)
        .collect_frames()
        .expect("frames decode");
    assert_eq!(frames.len(), 5);
    assert_eq!(
        frames[0].delay().numer_denom_ms(),
        (100, 1),
        "10 frames per second"
    );
    assert_eq!(frames[0].buffer().dimensions(), (32, 18));
}
