//! `--shard I/N`: the I-th of N slices of a batch's outputs, so that N machines (or N jobs of a
//! job runner) each render a part and together render all of it, each file once.

use std::fmt;
use std::ops::Range;

/// The slice `index` of `count` (1 ≤ index ≤ count): outputs in order, cut into `count`
/// contiguous runs whose lengths differ by at most one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: usize,
    pub count: usize,
}

impl Shard {
    /// The positions of this shard's outputs among `total`.
    pub fn range(self, total: usize) -> Range<usize> {
        let start = |i: usize| i * total / self.count;
        start(self.index - 1)..start(self.index)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Parses `I/N` with 1 ≤ I ≤ N for clap.
pub fn parse_shard(s: &str) -> Result<Shard, String> {
    let refuse = || format!("`{s}` is not a shard: write I/N with 1 ≤ I ≤ N, as 2/8");
    let (index, count) = s.split_once('/').ok_or_else(refuse)?;
    let (index, count) = (
        index.trim().parse::<usize>().map_err(|_| refuse())?,
        count.trim().parse::<usize>().map_err(|_| refuse())?,
    );
    if index == 0 || index > count {
        return Err(refuse());
    }
    Ok(Shard { index, count })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_cover_every_position_once() {
        for total in [0, 1, 5, 7, 24] {
            for count in 1..=6 {
                let mut seen = Vec::new();
                for index in 1..=count {
                    seen.extend(Shard { index, count }.range(total));
                }
                assert_eq!(seen, (0..total).collect::<Vec<_>>(), "{total} in {count}");
            }
        }
        assert_eq!(Shard { index: 2, count: 2 }.range(5), 2..5);
    }

    #[test]
    fn shards_parse_as_i_of_n() {
        assert_eq!(parse_shard("1/2"), Ok(Shard { index: 1, count: 2 }));
        for bad in ["0/2", "3/2", "1", "a/b", "1/0", "-1/2"] {
            assert!(parse_shard(bad).unwrap_err().contains("I/N"), "{bad}");
        }
    }
}
