//! The editor over a slow link (a pty drained at a fixed byte rate, as sshd and a slow network
//! do): at most one frame in flight, cheap frames while keys arrive, the exact frame after them,
//! and silence when idle. Nothing here is timed: the checks are on bytes and frames.

mod link;

use std::time::Duration;

use link::SlowLink;

/// 60 kB/s: slow enough that a burst of keys outruns the link, fast enough that the first
/// frame's answer comes well within the editor's patience for a terminal's first answer.
const RATE: f64 = 60_000.0;

#[test]
fn a_burst_of_orbit_keys_over_a_slow_link_keeps_one_frame_in_flight_and_ends_exact() {
    let dir = tempfile::tempdir().unwrap();
    let mut link = SlowLink::start(dir.path(), &[], 120, 40, RATE);
    assert!(
        link.run_until_quiet(Duration::from_millis(800), Duration::from_secs(60)),
        "the editor's first screen never settled"
    );
    assert!(
        !link.frames.is_empty(),
        "the editor never asked the terminal anything"
    );
    let before = link.frames.len();
    // 20 orbit keys, faster than the link can carry frames.
    for _ in 0..20 {
        link.keys(b"]");
        link.run_for(Duration::from_millis(30));
    }
    assert!(
        link.run_until_quiet(Duration::from_millis(1000), Duration::from_secs(60)),
        "the editor kept writing after the keys stopped"
    );
    let burst = &link.frames[before..];
    assert_eq!(
        link.written_in_flight, 0,
        "the editor wrote while a frame was still on its way to the terminal"
    );
    assert!(
        burst.len() < 20,
        "{} frames for 20 keys: frames were not merged",
        burst.len()
    );
    assert!(
        burst.iter().any(|f| f.has_palette_colours()),
        "no cheap frame was drawn while keys arrived"
    );
    let last = burst.last().expect("frames after the keys");
    assert!(!last.has_palette_colours(), "the final frame is not exact");
    // Idle costs nothing.
    let shown = link.shown();
    link.run_for(Duration::from_millis(1500));
    assert_eq!(link.shown(), shown, "the editor wrote while idle");
    assert_eq!(link.quit(), Some(0));
}

#[test]
fn over_a_fast_link_keys_get_exact_truecolor_frames() {
    let dir = tempfile::tempdir().unwrap();
    // 50 MB/s: a frame crosses in well under a millisecond.
    let mut link = SlowLink::start(dir.path(), &[], 120, 40, 50_000_000.0);
    let burst = link.orbit_burst(10, Duration::from_millis(60));
    assert!(
        burst
            .iter()
            .any(|f| f.bytes.windows(5).any(|w| w == b"48;2;")),
        "no frame drew the moving preview"
    );
    assert!(
        burst.iter().all(|f| !f.has_palette_colours()),
        "a motion frame fell to the 256-colour palette on a fast link"
    );
    assert_eq!(link.quit(), Some(0));
}
