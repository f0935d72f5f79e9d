//! `--frames A..B`: the frames of a turntable to render, counted from 0, both ends included.

use std::ops::RangeInclusive;

/// Frames `first` to `last` of a turntable, both included, counted from 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FrameRange {
    pub first: u32,
    pub last: u32,
}

impl FrameRange {
    /// The frames as a range.
    pub fn frames(self) -> RangeInclusive<u32> {
        self.first..=self.last
    }
}

/// Parses `A..B` (A ≤ B) or a single frame `A` for clap.
pub fn parse_frames(s: &str) -> Result<FrameRange, String> {
    let refuse =
        || format!("`{s}` is not a range of frames: write A..B (from 0, both included), as 0..11");
    let (first, last) = s.split_once("..").unwrap_or((s, s));
    let number = |n: &str| n.trim().parse::<u32>().map_err(|_| refuse());
    let (first, last) = (number(first)?, number(last)?);
    if first > last {
        return Err(refuse());
    }
    Ok(FrameRange { first, last })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_include_both_ends() {
        assert_eq!(parse_frames("0..11"), Ok(FrameRange { first: 0, last: 11 }));
        assert_eq!(parse_frames("5"), Ok(FrameRange { first: 5, last: 5 }));
        assert_eq!(parse_frames("3..3").unwrap().frames().count(), 1);
        for bad in ["4..2", "a..b", "..3", "1..=3", "-1..2"] {
            assert!(parse_frames(bad).unwrap_err().contains("A..B"), "{bad}");
        }
    }
}
