//! Frame pacing for slow links: at most one preview frame in flight, whatever the link buffers.
//!
//! Over SSH the editor cannot feel the link: sshd reads the pty as fast as the editor writes,
//! into a channel window of about 2 MiB, so every frame written is queued and a burst of keys
//! becomes seconds of stale frames. After each frame the editor asks the terminal for the cursor
//! position; a terminal answers only once it has drawn everything sent before the question, so
//! the answer says the frame has arrived. Until then no new frame is written: keys keep changing
//! the state, and the newest state is drawn when the answer comes. A terminal that never answers
//! is not waited for again (today's behaviour: every change is drawn at once).
//!
//! While keys are arriving frames may be cheap (lossy); once input pauses for [`SETTLE`], the
//! exact frame is drawn.
//!
//! The answers also measure the link: a frame of so many bytes took so long from its write to
//! its answer ([`Link`]). A slow link gets cheap frames while keys arrive, and pictures in real
//! pixels sized to cross it in [`PICTURE_TIME`]; a fast one keeps truecolor and full
//! resolution throughout.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::graphics::PIXEL_BUDGET;

/// The query written after a frame: DSR 6, "report the cursor position".
pub const QUERY: &[u8] = b"\x1b[6n";

/// Input pause after which the exact frame replaces the cheap ones drawn while keys arrive.
pub const SETTLE: Duration = Duration::from_millis(150);

/// How long the editor waits, when it quits, for answers still on their way (which would
/// otherwise reach the shell as typed text).
pub const LAST_ANSWER: Duration = Duration::from_millis(300);

/// How long the first answer is awaited before the terminal is taken to answer nothing.
const FIRST_ANSWER: Duration = Duration::from_millis(1500);

/// The slowest link the editor expects, bytes per second: a large frame (a picture in real
/// pixels) adds its bytes at this rate to the time its answer is awaited, so that a picture
/// crossing a slow link is not taken for a terminal that does not answer.
const SLOWEST_LINK: f64 = 16_000.0;

/// How long a later answer is awaited before drawing anyway (an answer lost to a reset, or a
/// link stalled for longer than this): the editor never freezes for good.
const LATER_ANSWER: Duration = Duration::from_secs(4);

/// Below this many bytes per second a link is slow: a truecolor frame of 40 kB would hold it
/// for more than 1/25 s, so frames drawn while keys arrive are cheap (256 colours, reduced
/// pictures). At or above it motion frames stay exact.
pub const SLOW_LINK: f64 = 1_000_000.0;

/// The time a picture in real pixels may take to cross a slow link: its bytes are budgeted at
/// this many seconds of the measured throughput.
pub const PICTURE_TIME: f64 = 0.2;

/// Frames smaller than this are not measured for throughput: their time is the terminal's
/// round trip, which they measure instead.
const MEASURED_FRAME: u64 = 4_000;

/// How many small frames the round trip is the shortest of.
const ROUND_TRIPS: usize = 8;

/// The link's throughput as the answers measure it: bytes and seconds of recent frames, each
/// older frame weighing half as much as the next, their seconds less the round trip (the
/// shortest time of recent small frames, which carry next to no bytes).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Link {
    bytes: f64,
    seconds: f64,
    /// Times of recent small frames, from write to answer, seconds; newest last.
    round_trips: VecDeque<f64>,
}

impl Link {
    /// Adds a frame of `bytes` that took `seconds` from its write to its answer.
    pub fn measure(&mut self, bytes: u64, seconds: f64) {
        if bytes < MEASURED_FRAME {
            if self.round_trips.len() == ROUND_TRIPS {
                self.round_trips.pop_front();
            }
            self.round_trips.push_back(seconds);
            return;
        }
        // No small frame yet: the whole time counts as crossing.
        let round_trip = self
            .round_trips
            .iter()
            .copied()
            .reduce(f64::min)
            .unwrap_or(0.0);
        let crossing = seconds - round_trip.min(seconds);
        self.bytes = 0.5 * self.bytes + bytes as f64;
        self.seconds = 0.5 * self.seconds + crossing.max(1e-4);
    }

    /// Bytes per second, once a frame has been measured.
    pub fn rate(&self) -> Option<f64> {
        (self.seconds > 0.0).then(|| self.bytes / self.seconds)
    }

    /// Whether the link is known to be slow (below [`SLOW_LINK`]).
    pub fn slow(&self) -> bool {
        self.rate().is_some_and(|r| r < SLOW_LINK)
    }

    /// The bytes a picture may have to cross the link in [`PICTURE_TIME`]; `None` when the link
    /// is fast or not measured yet (no limit).
    pub fn picture_bytes(&self) -> Option<u64> {
        self.rate()
            .filter(|&r| r < SLOW_LINK)
            .map(|r| (r * PICTURE_TIME) as u64)
    }

    /// Most pixels a picture may have, given what an earlier one cost: [`PIXEL_BUDGET`] on a
    /// fast link; on a slow one, what fits in [`Link::picture_bytes`] as bytes grow with
    /// pixels ([`BYTES_EXPONENT`]), in steps of 1/√2 (so that a wobbling estimate does not
    /// change the size each time), at least [`FEWEST_PIXELS`].
    pub fn pixel_budget(&self, last: PictureCost) -> u64 {
        let Some(bytes) = self.picture_bytes() else {
            return PIXEL_BUDGET;
        };
        let share = bytes as f64 / last.bytes.max(1) as f64;
        let fits = last.pixels as f64 * share.powf(1.0 / BYTES_EXPONENT);
        let mut budget = PIXEL_BUDGET as f64;
        while budget > fits && budget * std::f64::consts::FRAC_1_SQRT_2 >= FEWEST_PIXELS as f64 {
            budget *= std::f64::consts::FRAC_1_SQRT_2;
        }
        budget as u64
    }
}

/// What a picture sent cost: its pixels and its encoded bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PictureCost {
    pub pixels: u64,
    pub bytes: u64,
}

impl PictureCost {
    /// The guess before any picture has been sent: the default scene at full size.
    pub const GUESS: PictureCost = PictureCost {
        pixels: PIXEL_BUDGET,
        bytes: 130_000,
    };
}

/// How a picture's bytes grow with its pixels, as pixels to this power: a picture of fewer
/// pixels keeps more bytes a pixel (its edges and textures stay). The default scene in PNG:
/// 384,000 pixels 108 kB, 85,000 pixels 45 kB.
pub const BYTES_EXPONENT: f64 = 0.6;

/// The fewest pixels a picture is given on the slowest link: 160×100 or so.
pub const FEWEST_PIXELS: u64 = PIXEL_BUDGET / 32;

/// Whether the terminal answers the pacing query.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Answering {
    /// Not known yet: no answer and no time-out so far.
    Unknown,
    /// It has answered at least once: frames are paced.
    Yes,
    /// It let the first query time out: frames are not paced.
    No,
}

/// Pacing state: queries in flight, and when input last arrived.
#[derive(Debug, Clone)]
pub struct Pacer {
    answering: Answering,
    /// Queries written and not answered yet.
    in_flight: u32,
    /// When the oldest unanswered query was written.
    asked_at: Option<Instant>,
    /// When the last key or mouse event arrived.
    last_input: Option<Instant>,
    /// Whether the frame on screen (or in flight) is a cheap one that the exact frame must replace.
    lossy_shown: bool,
    /// Extra time the answers in flight are awaited, for the large frames before them.
    patience: Duration,
    /// The frames in flight, oldest first: when each was written and its bytes.
    sent: VecDeque<(Instant, u64)>,
    /// When the last answer came.
    answered_at: Option<Instant>,
    /// What the answers measured of the link.
    link: Link,
}

impl Default for Pacer {
    fn default() -> Pacer {
        Pacer::new()
    }
}

impl Pacer {
    /// A pacer that has asked nothing yet.
    pub fn new() -> Pacer {
        Pacer {
            answering: Answering::Unknown,
            in_flight: 0,
            asked_at: None,
            last_input: None,
            lossy_shown: false,
            patience: Duration::ZERO,
            sent: VecDeque::new(),
            answered_at: None,
            link: Link::default(),
        }
    }

    /// What the answers measured of the link.
    pub fn link(&self) -> &Link {
        &self.link
    }

    /// A pacer for a terminal that is known not to answer: nothing is ever held back.
    pub fn unpaced() -> Pacer {
        Pacer {
            answering: Answering::No,
            ..Pacer::new()
        }
    }

    /// What is known of the terminal's answers.
    pub fn answering(&self) -> Answering {
        self.answering
    }

    /// Whether a frame may be written now: nothing is in flight, or the terminal does not answer,
    /// or the wait has timed out.
    pub fn may_draw(&mut self, now: Instant) -> bool {
        let Some(asked) = self.asked_at else {
            return true;
        };
        let limit = match self.answering {
            Answering::No => return true,
            Answering::Unknown => FIRST_ANSWER,
            Answering::Yes => LATER_ANSWER,
        };
        if now.duration_since(asked) < limit + self.patience {
            return false;
        }
        if self.answering == Answering::Unknown {
            self.answering = Answering::No;
        }
        // Give up on what is in flight; late answers are then ignored.
        self.in_flight = 0;
        self.sent.clear();
        self.asked_at = None;
        self.patience = Duration::ZERO;
        true
    }

    /// Whether a query is on its way to a terminal that answers.
    pub fn awaiting(&self) -> bool {
        self.in_flight > 0 && self.answering != Answering::No
    }

    /// Whether a query should follow the frame just written.
    pub fn should_ask(&self) -> bool {
        self.answering != Answering::No
    }

    /// Notes that a frame of `bytes` and its query were written at `now`; `lossy` says whether
    /// the frame was a cheap one.
    pub fn asked(&mut self, now: Instant, lossy: bool, bytes: u64) {
        self.in_flight += 1;
        self.sent.push_back((now, bytes));
        self.asked_at.get_or_insert(now);
        self.lossy_shown = lossy;
    }

    /// Notes that the frame about to be asked after carries `bytes` more than its cells (a
    /// picture): its answer is awaited longer, as if the link carried 16 kB/s.
    pub fn carrying(&mut self, bytes: usize) {
        self.patience += Duration::from_secs_f64(bytes as f64 / SLOWEST_LINK);
    }

    /// Notes a frame written without a query (the terminal does not answer).
    pub fn drew(&mut self, lossy: bool) {
        self.lossy_shown = lossy;
    }

    /// Notes an answer: the oldest frame in flight has been drawn. Answers to queries given up
    /// on are ignored.
    pub fn answered(&mut self, now: Instant) {
        if self.in_flight == 0 {
            return;
        }
        self.answering = Answering::Yes;
        self.in_flight -= 1;
        if let Some((written, bytes)) = self.sent.pop_front() {
            // A frame starts crossing when it is written or when the one before it has arrived.
            let start = self.answered_at.map_or(written, |a| a.max(written));
            self.link
                .measure(bytes, now.saturating_duration_since(start).as_secs_f64());
        }
        self.answered_at = Some(now);
        self.asked_at = (self.in_flight > 0).then_some(now);
        if self.in_flight == 0 {
            self.patience = Duration::ZERO;
        }
    }

    /// Notes a key or mouse event at `now`.
    pub fn input(&mut self, now: Instant) {
        self.last_input = Some(now);
    }

    /// Whether keys are arriving: the next frame may be a cheap one.
    pub fn moving(&self, now: Instant) -> bool {
        self.last_input
            .is_some_and(|at| now.duration_since(at) < SETTLE)
    }

    /// When input counts as paused (the end of [`SETTLE`] after the last key), while that is
    /// still to come.
    pub fn settles_at(&self) -> Option<Instant> {
        self.last_input
            .map(|at| at + SETTLE)
            .filter(|&at| at > Instant::now())
    }

    /// Whether the screen shows a cheap frame that the exact one must replace once input settles.
    pub fn needs_exact(&self, now: Instant) -> bool {
        self.lossy_shown && !self.moving(now)
    }

    /// Whether the frame drawn now may be cheap: keys are arriving over a link measured slow
    /// (on a fast one motion frames stay exact), or `covered` (a picture is on its way that will
    /// cover the preview at once, so the cheap frame on screen stays as it is).
    pub fn cheap(&self, now: Instant, covered: bool) -> bool {
        self.should_ask() && self.link.slow() && (self.moving(now) || covered)
    }

    /// Whether the exact frame is due now: input has settled after cheap frames, and no
    /// picture is on its way that would cover it at once (that picture is the exact frame).
    pub fn exact_due(&self, now: Instant, covered: bool) -> bool {
        self.needs_exact(now) && !covered
    }

    /// When the loop must wake up next without input: the end of the settle pause (to draw the
    /// exact frame) or the query's time-out.
    pub fn wake_at(&self) -> Option<Instant> {
        let settle = self
            .lossy_shown
            .then_some(self.last_input.map(|at| at + SETTLE))
            .flatten();
        let timeout = self.asked_at.map(|at| {
            at + self.patience
                + match self.answering {
                    Answering::Yes => LATER_ANSWER,
                    _ => FIRST_ANSWER,
                }
        });
        match (settle, timeout) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ms(n: u64) -> Duration {
        Duration::from_millis(n)
    }

    #[test]
    fn one_frame_in_flight_until_the_answer() {
        let t = Instant::now();
        let mut p = Pacer::new();
        assert!(p.may_draw(t));
        p.asked(t, false, 0);
        assert!(!p.may_draw(t + ms(100)), "a frame is in flight");
        p.answered(t + ms(300));
        assert_eq!(p.answering(), Answering::Yes);
        assert!(p.may_draw(t + ms(300)));
    }

    #[test]
    fn a_terminal_that_never_answers_is_not_waited_for_again() {
        let t = Instant::now();
        let mut p = Pacer::new();
        p.asked(t, false, 0);
        assert!(!p.may_draw(t + FIRST_ANSWER - ms(1)));
        assert!(p.may_draw(t + FIRST_ANSWER));
        assert_eq!(p.answering(), Answering::No);
        assert!(!p.should_ask());
        assert!(p.may_draw(t + FIRST_ANSWER + ms(1)));
        // A late answer does not turn pacing back on for a query given up on.
        p.answered(t + FIRST_ANSWER + ms(5));
        assert_eq!(p.answering(), Answering::No);
    }

    #[test]
    fn a_lost_answer_stalls_for_a_bounded_time_only() {
        let t = Instant::now();
        let mut p = Pacer::new();
        p.asked(t, false, 0);
        p.answered(t + ms(10));
        p.asked(t + ms(20), false, 0);
        assert!(!p.may_draw(t + ms(20) + LATER_ANSWER - ms(1)));
        assert!(p.may_draw(t + ms(20) + LATER_ANSWER));
        assert_eq!(
            p.answering(),
            Answering::Yes,
            "one lost answer is not a deaf terminal"
        );
    }

    #[test]
    fn the_exact_frame_follows_a_pause_after_cheap_ones() {
        let t = Instant::now();
        let mut p = Pacer::new();
        p.input(t);
        assert!(p.moving(t + ms(50)));
        p.asked(t + ms(10), true, 0);
        p.answered(t + ms(60));
        assert!(!p.needs_exact(t + ms(100)), "keys are still arriving");
        assert_eq!(p.wake_at(), Some(t + SETTLE));
        assert!(p.needs_exact(t + SETTLE));
        p.asked(t + SETTLE, false, 0);
        assert!(!p.needs_exact(t + SETTLE + ms(1)));
    }

    #[test]
    fn a_large_picture_is_awaited_longer() {
        let t = Instant::now();
        let mut p = Pacer::new();
        // 160 kB at the slowest link's 16 kB/s: 10 s more.
        p.carrying(160_000);
        p.asked(t, false, 0);
        assert!(!p.may_draw(t + FIRST_ANSWER + ms(9_000)));
        assert_eq!(p.answering(), Answering::Unknown);
        p.answered(t + FIRST_ANSWER + ms(9_500));
        assert_eq!(p.answering(), Answering::Yes);
        // The next frame, with no picture, gets the usual patience.
        p.asked(t + ms(12_000), false, 0);
        assert!(p.may_draw(t + ms(12_000) + LATER_ANSWER));
    }

    /// A link of `rate` bytes per second: frames of `bytes`, each answered when its last byte
    /// has crossed.
    fn over_link(p: &mut Pacer, t: Instant, rate: f64, frames: &[u64]) -> Instant {
        let mut now = t;
        for &bytes in frames {
            p.asked(now, false, bytes);
            now += Duration::from_secs_f64(bytes as f64 / rate);
            p.answered(now);
        }
        now
    }

    #[test]
    fn the_answers_measure_the_link() {
        let t = Instant::now();
        let mut p = Pacer::new();
        assert_eq!(p.link().rate(), None, "nothing measured yet");
        assert!(!p.link().slow(), "an unmeasured link is taken as fast");
        // 1 Mbit/s: 125 kB/s, frames of 40 kB and 20 kB.
        over_link(&mut p, t, 125_000.0, &[40_000, 20_000, 40_000]);
        let rate = p.link().rate().unwrap();
        assert!((rate - 125_000.0).abs() < 1_000.0, "{rate}");
        assert!(p.link().slow());
        assert_eq!(p.link().picture_bytes(), Some(25_000));
    }

    #[test]
    fn small_frames_measure_the_round_trip_not_the_link() {
        let t = Instant::now();
        let mut p = Pacer::new();
        // A fast link behind a round trip of 10 ms: frames of 300 bytes and of 5 kB are both
        // answered after about 10 ms.
        let mut now = t;
        for bytes in [300, 5_000, 300, 5_000, 300, 5_000] {
            p.asked(now, false, bytes);
            now += ms(10) + Duration::from_secs_f64(bytes as f64 / 20_000_000.0);
            p.answered(now);
        }
        assert!(!p.link().slow(), "{:?}", p.link().rate());
        // The same round trip on a slow link: the 5 kB frames take 40 ms more.
        let mut slow = Pacer::new();
        for bytes in [300, 5_000, 300, 5_000, 300, 5_000] {
            slow.asked(now, false, bytes);
            now += ms(10) + Duration::from_secs_f64(bytes as f64 / 125_000.0);
            slow.answered(now);
        }
        let rate = slow.link().rate().unwrap();
        // Within 10%: the small frames' own bytes count as round trip.
        assert!((rate - 125_000.0).abs() < 12_500.0, "{rate}");
    }

    #[test]
    fn a_frame_queued_behind_another_is_timed_from_its_arrival() {
        let t = Instant::now();
        let mut p = Pacer::new();
        // Two 50 kB frames written at once over 100 kB/s: answers after 0.5 s and 1 s.
        p.asked(t, false, 50_000);
        p.asked(t, false, 50_000);
        p.answered(t + ms(500));
        p.answered(t + ms(1000));
        let rate = p.link().rate().unwrap();
        assert!((rate - 100_000.0).abs() < 1_000.0, "{rate}");
    }

    #[test]
    fn pictures_are_sized_to_a_slow_link_and_full_on_a_fast_one() {
        let t = Instant::now();
        let last = PictureCost {
            pixels: 400_000,
            bytes: 100_000,
        };
        let mut fast = Pacer::new();
        over_link(&mut fast, t, 50_000_000.0, &[100_000, 100_000]);
        assert_eq!(fast.link().pixel_budget(last), PIXEL_BUDGET);
        assert_eq!(
            Pacer::new().link().pixel_budget(last),
            PIXEL_BUDGET,
            "full size before anything is measured"
        );
        let mut slow = Pacer::new();
        over_link(&mut slow, t, 125_000.0, &[100_000, 100_000]);
        // 25 kB is a quarter of the last picture's bytes: 0.25^(1/0.6) of its pixels, 39,700;
        // the budget is the largest step not above.
        let fits = 400_000.0 * 0.25f64.powf(1.0 / BYTES_EXPONENT);
        let budget = slow.link().pixel_budget(last) as f64;
        assert!(
            budget <= fits && budget * std::f64::consts::SQRT_2 > fits,
            "{budget} for {fits}"
        );
        // A slower link still gets a picture, of the fewest pixels.
        let mut crawl = Pacer::new();
        over_link(&mut crawl, t, 5_000.0, &[10_000, 10_000]);
        assert!(crawl.link().pixel_budget(last) >= FEWEST_PIXELS);
        assert!(crawl.link().pixel_budget(last) < FEWEST_PIXELS * 2);
    }

    #[test]
    fn motion_frames_are_cheap_only_over_a_slow_link() {
        let t = Instant::now();
        let mut fast = Pacer::new();
        let now = over_link(&mut fast, t, 50_000_000.0, &[40_000, 40_000]);
        fast.input(now);
        assert!(!fast.cheap(now, false), "a fast link keeps truecolor");
        let mut slow = Pacer::new();
        let now = over_link(&mut slow, t, 125_000.0, &[40_000, 40_000]);
        slow.input(now);
        assert!(slow.cheap(now, false));
        assert!(!slow.cheap(now + SETTLE, false), "the keys have paused");
        let deaf = Pacer::unpaced();
        assert!(
            !deaf.cheap(now, false),
            "an unpaced terminal gets exact frames"
        );
    }

    #[test]
    fn no_exact_frame_is_sent_under_a_picture_on_its_way() {
        let t = Instant::now();
        let mut p = Pacer::new();
        let now = over_link(&mut p, t, 125_000.0, &[40_000]);
        p.input(now);
        p.asked(now, true, 5_000);
        p.answered(now + ms(40));
        let settled = now + SETTLE;
        assert!(p.exact_due(settled, false));
        // The picture rendered for the settled view is the exact frame: the cells under it are
        // not redrawn exact first, and the cheap ones stay until it comes.
        assert!(!p.exact_due(settled, true));
        assert!(p.cheap(settled, true));
    }
}
