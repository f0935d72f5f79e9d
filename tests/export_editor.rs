//! The editor's export dialog: a turntable of the typed frame count, a 16-bit PNG with alpha
//! chosen in its fields, and the format the file name asks for.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rastray::export::{AnimationFormat, ImageFormat, Output, PngDepth, Turntable};
use rastray::scene::default_scene;
use rastray::tui::input::action::Action;
use rastray::tui::persistence::export_job::export_output;
use rastray::tui::state::app::App;
use rastray::tui::state::mode::Mode;
use rastray::tui::update::apply;

/// A bound on waiting for the export thread, so a broken one fails the test instead of hanging.
const PATIENCE: Duration = Duration::from_secs(120);

fn type_text(app: &mut App, text: &str) {
    apply(app, Action::ClearInput);
    for c in text.chars() {
        apply(app, Action::Input(c));
    }
}

fn down(app: &mut App, fields: usize) {
    for _ in 0..fields {
        apply(app, Action::Down);
    }
}

/// Starts the export and ticks the editor until the file exists.
fn submit_and_wait(app: &mut App, path: &Path) {
    apply(app, Action::Submit);
    assert!(
        matches!(app.mode(), Mode::Normal),
        "the dialog closes on a valid export: {:?}",
        app.mode()
    );
    let started = Instant::now();
    while !path.exists() {
        assert!(started.elapsed() < PATIENCE, "the export finishes");
        std::thread::sleep(Duration::from_millis(5));
        apply(app, Action::Tick);
    }
}

#[test]
fn the_dialog_writes_a_16_bit_png_with_coverage_as_alpha() {
    let dir = tempfile::tempdir().unwrap();
    let typed = dir.path().join("still.exr");
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    apply(&mut app, Action::Export);
    type_text(&mut app, typed.to_str().unwrap());
    down(&mut app, 1);
    type_text(&mut app, "32x18");
    // Past the algorithm and the samples to the format: by extension → png8 → png16; a named
    // format renames the file to match.
    down(&mut app, 3);
    apply(&mut app, Action::Step(1));
    apply(&mut app, Action::Step(1));
    let path = dir.path().join("still.png");
    match app.mode() {
        Mode::Export(form) => {
            assert_eq!(form.format, Some(ImageFormat::PNG16));
            assert_eq!(Path::new(&form.path), path);
        }
        other => panic!("the export dialog stays open: {other:?}"),
    }
    // The background.
    down(&mut app, 1);
    apply(&mut app, Action::Step(1));
    submit_and_wait(&mut app, &path);
    let image = image::open(&path).expect("a PNG that decodes");
    assert_eq!(image.color(), image::ColorType::Rgba16);
    assert_eq!((image.width(), image.height()), (32, 18));
    let pixels = image.to_rgba16();
    // The default scene leaves its top-left corner empty and covers its centre.
    assert_eq!(
        pixels.get_pixel(0, 0)[3],
        0,
        "the background is transparent"
    );
    assert_eq!(pixels.get_pixel(16, 9)[3], u16::MAX, "an object is opaque");
}

#[test]
fn the_dialog_writes_a_turntable_of_the_typed_frame_count() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("spin.gif");
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    apply(&mut app, Action::Export);
    type_text(&mut app, path.to_str().unwrap());
    down(&mut app, 1);
    type_text(&mut app, "40x24");
    // Past the algorithm, the samples, the format and the background to the turntable field.
    down(&mut app, 5);
    type_text(&mut app, "3");
    submit_and_wait(&mut app, &path);
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
    let at = |name: &str, frames: &str| export_output(Path::new(name), None, frames);
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
    let png16 = Some(ImageFormat::PNG16);
    assert_eq!(
        export_output(Path::new("a.png"), png16, "0"),
        Ok(Output::Image(ImageFormat::PNG16))
    );
    let error = export_output(Path::new("a.exr"), png16, "0").expect_err("png16 as .exr");
    assert!(error.contains("format png16 writes .png files"), "{error}");
}
