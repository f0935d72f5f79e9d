//! The editor over a 1 Mbit/s link with sshd's buffering (everything written is queued), as in
//! the README's SSH section: 30 orbit keys typed 50 ms apart on the default scene at 160×48
//! truecolor cells. Prints how long after the last key the terminal has the exact final frame,
//! the largest frame drawn while keys arrived, the bytes per key, and the bytes sent while idle.
//!
//! `cargo bench --bench slow_link`

#[path = "../tests/link/mod.rs"]
mod link;

use std::time::{Duration, Instant};

use link::SlowLink;

/// 1 Mbit/s.
const RATE: f64 = 125_000.0;
const KEYS: usize = 30;

fn main() {
    let dir = std::env::current_dir().expect("a working directory");
    let mut link = SlowLink::start(&dir, &["scenes/default.toml"], 160, 48, RATE);
    link.run_until_quiet(Duration::from_millis(1000), Duration::from_secs(60));
    let (before, shown_before) = (link.frames.len(), link.shown());
    let mut last_key = Instant::now();
    for _ in 0..KEYS {
        link.keys(b"]");
        last_key = Instant::now();
        link.run_for(Duration::from_millis(50));
    }
    link.run_until_quiet(Duration::from_millis(1500), Duration::from_secs(120));
    let burst = &link.frames[before..];
    let last = burst.last().expect("frames after the keys");
    let lag = last.shown_at.saturating_duration_since(last_key);
    let largest_cheap = burst
        .iter()
        .filter(|f| f.has_palette_colours())
        .map(|f| f.bytes.len())
        .max()
        .unwrap_or(0);
    let (frames, exact) = (burst.len(), !last.has_palette_colours());
    let sent = link.shown() - shown_before;
    let idle_from = link.shown();
    link.run_for(Duration::from_secs(5));
    let idle = link.shown() - idle_from;
    println!(
        "slow link: 1 Mbit/s, sshd-style buffering, {KEYS} orbit keys 50 ms apart, 160x48 truecolor, default scene"
    );
    println!(
        "| exact final frame after the last key | largest motion frame | per key | frames | idle 5 s |"
    );
    println!("|---|---|---|---|---|");
    println!(
        "| {:.2} s | {:.1} kB | {:.1} kB | {} | {} B |",
        lag.as_secs_f64(),
        largest_cheap as f64 / 1000.0,
        sent as f64 / 1000.0 / KEYS as f64,
        frames,
        idle
    );
    println!("final frame exact: {exact}");
    let _ = link.quit();
}
