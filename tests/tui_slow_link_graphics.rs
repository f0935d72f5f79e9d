//! The editor drawing kitty pictures over a slow link (see `tui_slow_link.rs` for the link):
//! a picture is a frame like any other, one in flight at a time; frames while keys arrive are
//! half blocks, and the exact picture follows the keys. Nothing here is timed: the checks are on
//! bytes and frames.

mod link;

use std::time::Duration;

use link::SlowLink;

/// 60 kB/s: a picture takes seconds to cross, longer than the editor waits for a first answer
/// to a frame of cells alone.
const RATE: f64 = 60_000.0;

fn pictures(bytes: &[u8]) -> usize {
    bytes.windows(7).filter(|w| w == b"\x1b_Ga=T,").count()
}

#[test]
fn pictures_are_paced_and_keys_get_half_blocks_until_they_pause() {
    let dir = tempfile::tempdir().unwrap();
    let mut link = SlowLink::start(dir.path(), &["--graphics", "kitty"], 120, 40, RATE);
    assert!(
        link.run_until_quiet(Duration::from_millis(1500), Duration::from_secs(90)),
        "the editor's first screen never settled"
    );
    let first: usize = link.frames.iter().map(|f| pictures(&f.bytes)).sum();
    assert_eq!(first, 1, "one picture for the first screen");
    let before = link.frames.len();
    for _ in 0..20 {
        link.keys(b"]");
        link.run_for(Duration::from_millis(30));
    }
    assert!(
        link.run_until_quiet(Duration::from_millis(1500), Duration::from_secs(90)),
        "the editor kept writing after the keys stopped"
    );
    assert_eq!(
        link.written_in_flight, 0,
        "the editor wrote while a frame was still on its way to the terminal"
    );
    let burst = &link.frames[before..];
    assert!(burst.len() < 20, "{} frames for 20 keys", burst.len());
    let (last, moving) = burst.split_last().expect("frames after the keys");
    assert!(
        moving
            .iter()
            .any(|f| pictures(&f.bytes) == 0 && f.bytes.windows(3).any(|w| w == "▀".as_bytes())),
        "no half-block frame while keys arrived"
    );
    assert_eq!(
        burst.iter().map(|f| pictures(&f.bytes)).sum::<usize>(),
        1,
        "one picture, after the keys"
    );
    assert_eq!(
        pictures(&last.bytes),
        1,
        "the last frame is the exact picture"
    );
    // Send no frame that the next covers at once: no exact half-block frame before the picture.
    for frame in moving {
        let cells = frame.bytes.windows(3).any(|w| w == "▀".as_bytes());
        assert!(
            !cells || frame.has_palette_colours(),
            "an exact half-block frame of {} bytes went out under the picture",
            frame.bytes.len()
        );
    }
    // The picture is sized to the link: the first screen's went out at full size, before the
    // link was measured; the one after the keys fits about 0.2 s of the link's 60 kB/s.
    let first_picture = link.frames[..before]
        .iter()
        .find(|f| pictures(&f.bytes) == 1)
        .map(|f| f.bytes.len())
        .unwrap();
    assert!(
        last.bytes.len() < first_picture / 2 && last.bytes.len() < 30_000,
        "the picture after the keys has {} bytes, the first {first_picture}",
        last.bytes.len()
    );
    let shown = link.shown();
    link.run_for(Duration::from_millis(1500));
    assert_eq!(link.shown(), shown, "the editor wrote while idle");
    assert_eq!(link.quit(), Some(0));
}
