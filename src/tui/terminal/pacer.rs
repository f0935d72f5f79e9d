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

use std::time::{Duration, Instant};

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
        }
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

    /// Notes that a frame and its query were written at `now`; `lossy` says whether the frame
    /// was a cheap one.
    pub fn asked(&mut self, now: Instant, lossy: bool) {
        self.in_flight += 1;
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
        p.asked(t, false);
        assert!(!p.may_draw(t + ms(100)), "a frame is in flight");
        p.answered(t + ms(300));
        assert_eq!(p.answering(), Answering::Yes);
        assert!(p.may_draw(t + ms(300)));
    }

    #[test]
    fn a_terminal_that_never_answers_is_not_waited_for_again() {
        let t = Instant::now();
        let mut p = Pacer::new();
        p.asked(t, false);
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
        p.asked(t, false);
        p.answered(t + ms(10));
        p.asked(t + ms(20), false);
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
        p.asked(t + ms(10), true);
        p.answered(t + ms(60));
        assert!(!p.needs_exact(t + ms(100)), "keys are still arriving");
        assert_eq!(p.wake_at(), Some(t + SETTLE));
        assert!(p.needs_exact(t + SETTLE));
        p.asked(t + SETTLE, false);
        assert!(!p.needs_exact(t + SETTLE + ms(1)));
    }

    #[test]
    fn a_large_picture_is_awaited_longer() {
        let t = Instant::now();
        let mut p = Pacer::new();
        // 160 kB at the slowest link's 16 kB/s: 10 s more.
        p.carrying(160_000);
        p.asked(t, false);
        assert!(!p.may_draw(t + FIRST_ANSWER + ms(9_000)));
        assert_eq!(p.answering(), Answering::Unknown);
        p.answered(t + FIRST_ANSWER + ms(9_500));
        assert_eq!(p.answering(), Answering::Yes);
        // The next frame, with no picture, gets the usual patience.
        p.asked(t + ms(12_000), false);
        assert!(p.may_draw(t + ms(12_000) + LATER_ANSWER));
    }
}
