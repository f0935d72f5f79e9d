//! Welding: vertices with bit-identical keys (a position, or a position and a colour) merged
//! into one, so that normals computed from the faces can smooth across the seams exporters
//! split vertices at. One open-addressing table of `u64` slots, each the index of a kept key and
//! a tag of its hash: a probe reads the key only when the tags agree, and the table stays at
//! most half full.

/// Keys of `N` 32-bit words, merged when every bit agrees, with the index each was given.
///
/// Invariant: `keys` holds each distinct key once, in order of first sight; every non-zero slot
/// is `tag << 32 | (index + 1)` for a key at `keys[index]` whose hash has `tag` in its high bits;
/// fewer than half the slots are full; every `recent` entry with a non-zero `index + 1` holds a
/// key and the index it was given.
#[derive(Debug)]
pub struct Welder<const N: usize> {
    slots: Vec<u64>,
    keys: Vec<[u32; N]>,
    /// The keys met lately, by the high bits of their hash (direct-mapped, 16 Ki entries, or
    /// as many as `slots` when that is fewer): a mesh names each corner about six times, mostly
    /// in faces close together in the file, so most lookups end here without touching the
    /// large table.
    recent: Vec<([u32; N], u32)>,
    /// 64 − the bits of the hash that choose an entry of `recent`.
    recent_shift: u32,
}

/// Most bits of the hash that choose an entry of [`Welder::recent`]. A small mesh gets fewer,
/// so that measuring each of 313,713 boxes does not clear 256 KiB each (80 GB in all: most of
/// `info`'s 43 s on that scene).
const RECENT_BITS: u32 = 14;

/// Keys looked up together by [`Welder::index_all`].
pub const BATCH: usize = 16;

impl<const N: usize> Welder<N> {
    /// A welder expecting about `distinct` keys (it grows past that as needed).
    pub fn with_capacity(distinct: usize) -> Welder<N> {
        let slots = (2 * distinct.max(8)).next_power_of_two();
        let recent_bits = RECENT_BITS.min(slots.trailing_zeros());
        Welder {
            slots: vec![0; slots],
            keys: Vec::with_capacity(distinct),
            recent: vec![([0; N], 0); 1 << recent_bits],
            recent_shift: 64 - recent_bits,
        }
    }

    /// The index of `key`: the one it was given when first seen, or the next one now.
    #[inline]
    pub fn index(&mut self, key: [u32; N]) -> u32 {
        let hash = hash(&key);
        let entry = (hash >> self.recent_shift) as usize;
        let (seen, plus_one) = self.recent[entry];
        if plus_one != 0 && seen == key {
            return plus_one - 1;
        }
        let index = self.probe(key, hash);
        self.recent[entry] = (key, index + 1);
        index
    }

    /// The indices of `keys` (at most [`BATCH`] of them), written to `out`: [`Welder::index`]
    /// of each in turn, with the large table's slots for the keys not met lately read first,
    /// together. A large table misses the cache (and the TLB) on nearly every probe; loads that
    /// do not wait on one another overlap, so a batch waits about as long as one probe.
    #[inline]
    pub fn index_all(&mut self, keys: &[[u32; N]], out: &mut [u32]) {
        let mask = self.slots.len() - 1;
        let mut warm = 0u64;
        for key in keys {
            let hash = hash(key);
            let (seen, plus_one) = self.recent[(hash >> self.recent_shift) as usize];
            if plus_one == 0 || seen != *key {
                let slot = self.slots[hash as usize & mask];
                // The key a full slot names is read by the probe too.
                let index = (slot as u32).wrapping_sub(1) as usize;
                warm ^= slot ^ self.keys.get(index).map_or(0, |k| k[0] as u64);
            }
        }
        std::hint::black_box(warm);
        for (key, out) in keys.iter().zip(out) {
            *out = self.index(*key);
        }
    }

    /// The index of `key` (whose hash is `hash`) in the large table, added when missing.
    fn probe(&mut self, key: [u32; N], hash: u64) -> u32 {
        let tag = hash >> 32;
        let mask = self.slots.len() - 1;
        let mut at = hash as usize & mask;
        loop {
            let slot = self.slots[at];
            if slot == 0 {
                break;
            }
            if slot >> 32 == tag {
                let index = (slot as u32 - 1) as usize;
                if self.keys[index] == key {
                    return index as u32;
                }
            }
            at = (at + 1) & mask;
        }
        let index = self.keys.len() as u32;
        self.slots[at] = tag << 32 | (index as u64 + 1);
        self.keys.push(key);
        if 2 * self.keys.len() >= self.slots.len() {
            self.grow();
        }
        index
    }

    /// The distinct keys, in order of first sight (key `i` was given index `i`).
    pub fn into_keys(self) -> Vec<[u32; N]> {
        self.keys
    }

    /// Doubles the table, placing every key again.
    fn grow(&mut self) {
        let mut slots = vec![0u64; self.slots.len() * 2];
        let mask = slots.len() - 1;
        for (index, key) in self.keys.iter().enumerate() {
            let hash = hash(key);
            let mut at = hash as usize & mask;
            while slots[at] != 0 {
                at = (at + 1) & mask;
            }
            slots[at] = (hash >> 32) << 32 | (index as u64 + 1);
        }
        self.slots = slots;
    }
}

/// The positions whose coordinates have the bits of `keys`.
pub fn positions_of(keys: Vec<[u32; 3]>) -> Vec<glam::Vec3> {
    keys.into_iter()
        .map(|k| glam::Vec3::from_array(k.map(f32::from_bits)))
        .collect()
}

/// A multiply-xorshift hash of a key's words: the low bits choose the slot, the high 32 are
/// the tag.
#[inline]
pub fn hash<const N: usize>(key: &[u32; N]) -> u64 {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut h = 0u64;
    for pair in key.chunks(2) {
        let word = pair[0] as u64 | (pair.get(1).copied().unwrap_or(0) as u64) << 32;
        h = (h ^ word).wrapping_mul(K);
        h ^= h >> 29;
    }
    h.wrapping_mul(K)
}

/// The bits of a coordinate as welding compares them: −0 as 0, so that the two spellings of
/// zero meet.
#[inline]
pub fn coordinate_bits(x: f32) -> u32 {
    (x + 0.0).to_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_keys_share_an_index_in_order_of_first_sight_through_growth() {
        let mut welder = Welder::<3>::with_capacity(1);
        let keys: Vec<[u32; 3]> = (0..1000u32).map(|i| [i % 300, i % 7, 0]).collect();
        let mut indices = vec![0; keys.len()];
        for (keys, out) in keys.chunks(BATCH).zip(indices.chunks_mut(BATCH)) {
            welder.index_all(keys, out);
        }
        let distinct = welder.into_keys();
        for (key, index) in keys.iter().zip(&indices) {
            assert_eq!(&distinct[*index as usize], key);
        }
        let mut sorted = distinct.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), distinct.len(), "each key once");
        assert_eq!(indices[0], 0);
        assert_eq!(indices[1], 1);
        // Looked up one at a time, the same keys give the same indices.
        for (key, index) in keys.iter().zip(&indices) {
            assert_eq!(welder_again(&distinct, *key), *index);
        }
    }

    fn welder_again(distinct: &[[u32; 3]], key: [u32; 3]) -> u32 {
        let mut welder = Welder::<3>::with_capacity(1);
        for &k in distinct {
            welder.index(k);
        }
        welder.index(key)
    }

    #[test]
    fn negative_zero_welds_with_zero() {
        assert_eq!(coordinate_bits(-0.0), coordinate_bits(0.0));
        assert_ne!(coordinate_bits(1.0), coordinate_bits(-1.0));
    }
}
