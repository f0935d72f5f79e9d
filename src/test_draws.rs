//! Pseudo-random numbers for tests: the same every run, from a seed, so that a failing case
//! can be found again. One generator for every test that draws its inputs.

/// Numbers below 2³¹ from `seed`: the high bits of a 64-bit linear congruential generator
/// (Knuth's MMIX constants).
pub fn draws(seed: u64) -> impl FnMut() -> u64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        state >> 33
    }
}

/// Numbers below `n` (> 0) from `seed`: [`draws`] taken modulo `n`.
pub fn below(seed: u64) -> impl FnMut(u64) -> u64 {
    let mut draw = draws(seed);
    move |n| draw() % n
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_repeat_from_a_seed_and_spread_below_their_bound() {
        let first: Vec<u64> = std::iter::repeat_with(draws(3)).take(1000).collect();
        let again: Vec<u64> = std::iter::repeat_with(draws(3)).take(1000).collect();
        assert_eq!(first, again);
        assert!(first.iter().all(|&x| x < 1 << 31));
        // Every residue below 10 turns up, and none far more than its share.
        let mut counts = [0; 10];
        let mut next = below(9);
        for _ in 0..10_000 {
            counts[next(10) as usize] += 1;
        }
        assert!(
            counts.iter().all(|&c| (800..1200).contains(&c)),
            "{counts:?}"
        );
    }
}
