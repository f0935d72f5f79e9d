//! The editor's export dialog writing a turntable: the frame count field, and the format the
//! file name asks for.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rastray::export::{AnimationFormat, ImageFormat, Output, PngDepth, Turntable};
use rastray::scene::default_scene;
use rastray::tui::action::Action;
use rastray::tui::app::App;
use rastray::tui::export_job::export_output;
use rastray::tui::update::apply;

/// A bound on waiting for the export thread, so a broken one fails the test instead of hanging.
const PATIENCE: Duration = Duration::from_secs(120);

fn type_text(app: &mut App, text: &str) {
    apply(app, Action::ClearInput);
    for c in text.chars() {
        apply(app, Action::Input(c));
    }
}

#[test]
fn the_dialog_writes_a_turntable_of_the_typed_frame_count() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("spin.gif");
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    apply(&mut app, Action::Export);
    type_text(&mut app, path.to_str().unwrap());
    apply(&mut app, Action::Down);
    type_text(&mut app, "40x24");
    // Past the algorithm and the samples to the turntable field.
    for _ in 0..3 {
        apply(&mut app, Action::Down);
    }
    type_text(&mut app, "3");
    apply(&mut app, Action::Submit);
    let started = Instant::now();
    while !path.exists() {
        assert!(started.elapsed() < PATIENCE, "the export finishes");
        std::thread::sleep(Duration::from_millis(5));
        apply(&mut app, Action::Tick);
    }
    let file = std::io::BufReader::new(std::fs::File::open(&path).unwrap());
    let decoder = image::codecs::gif::GifDecoder::new(file).expect("a GIF");
    let frames = image::AnimationDecoder::into_frames(decoder)
        .collect_frames()
        .expect("frames decode");
    assert_eq!(frames.len(), 3);
    assert_eq!(frames[0].buffer().dimensions(), (40, 24));
}

#[test]
fn the_file_name_and_frame_count_choose_what_is_written() {
    let at = |name: &str, frames: &str| export_output(Path::new(name), frames);
    assert_eq!(at("a.png", "0"), Ok(Output::Image(ImageFormat::PNG8)));
    assert_eq!(at("a.exr", " 0 "), Ok(Output::Image(ImageFormat::Exr)));
    assert_eq!(
        at("a.gif", "12"),
        Ok(Output::Turntable(Turntable::new(12), AnimationFormat::Gif))
    );
    assert_eq!(
        at("a.png", "12"),
        Ok(Output::Turntable(
            Turntable::new(12),
            AnimationFormat::Apng(PngDepth::Eight)
        ))
    );
    for (name, frames, says) in [
        ("a.gif", "0", "turntables only"),
        ("a.exr", "12", "a turntable is written as .gif or .png"),
        ("a.jpg", "0", "`.jpg` is none of them"),
        (
            "a.gif",
            "twelve",
            "`twelve` is not a number of turntable frames",
        ),
        ("a.gif", "100000", "1 to 3600 frames"),
    ] {
        let error = at(name, frames).expect_err(name);
        assert!(error.contains(says), "{name} {frames}: {error}");
    }
}
