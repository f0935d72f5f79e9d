//! Welding: keys (a position's coordinate bits, or a position's and a colour's) that agree in
//! every bit merged into one, numbered in order of first sight, so that normals computed from
//! the faces can smooth across the seams exporters split vertices at. One welder serves every
//! format: a binary STL's corners (each position named about six times), an ASCII STL's and a
//! PLY's vertices.
//!
//! A table of a large mesh's keys misses the cache on nearly every look-up, so the keys are
//! split by their hash into buckets small enough that each bucket's table stays in one core's
//! cache, and the buckets are welded in parallel. Each bucket holds its keys in file order, so
//! the first of equal keys it meets is the first in the file; the distinct keys are then
//! numbered by the place of that first one, which is their order of first sight.

use std::ops::Range;
use std::sync::atomic::{AtomicU8, Ordering};

use rayon::prelude::*;

use crate::huge_pages::{collected, filled};

/// Keys a bucket holds on average: its keys and table stay within a core's 2 MiB cache.
const BUCKET_KEYS: usize = 1 << 13;

/// Most bits of the hash that choose a bucket (4,096 buckets, 16 bits a key to name one).
const MOST_BUCKET_BITS: u32 = 12;

/// Keys one part of a pass takes, at least; parts are whole 64-bit words of [`Firsts`].
const LEAST_PART: usize = 1 << 14;

/// The bucket of a key that is not used.
const UNUSED: u16 = u16::MAX;

/// The bucket of a key equal to one met shortly before in its part.
const SAME: u16 = u16::MAX - 1;

/// Entries of the table of keys met lately, in each part: a mesh names each position about six
/// times, mostly in faces close together in the file, so most repeats are found there and
/// never reach a bucket.
const RECENT: usize = 1 << 12;

/// The number [`weld`] gives a key that is not used.
pub const NOT_USED: u32 = u32::MAX;

/// Where a welder's input repeats its keys, which chooses whether it first looks for each key
/// among the keys met lately.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Repeats {
    /// Equal keys mostly come a few faces apart (a triangle soup's corners: STL): the table of
    /// keys met lately finds most of them before they reach a bucket.
    Near,
    /// Keys are mostly distinct (an indexed mesh's vertices: PLY): the look-back would find
    /// nothing, and on the load bench cost PLY about 18% of its time.
    Rare,
}

/// Welds the keys `0..index.len()` (`key(i)` is key `i`; only those where `used(i)` count):
/// writes to `index[i]` the number of key `i`'s distinct key, numbered in order of first sight
/// (or [`NOT_USED`]), and returns `kept(first)` for the first key `first` of each distinct
/// key, in that order (so `kept` is called on ascending keys `i` with `index[i]` 0, 1, 2, …).
pub fn weld<const N: usize, T: Copy + Default + Send>(
    index: &mut [u32],
    repeats: Repeats,
    key: impl Fn(usize) -> [u32; N] + Sync,
    used: impl Fn(usize) -> bool + Sync,
    kept: impl Fn(usize) -> T + Sync,
) -> Vec<T> {
    let count = index.len();
    let part = count
        .div_ceil(4 * rayon::current_num_threads())
        .max(LEAST_PART)
        .next_multiple_of(64);
    let parts: Vec<Range<usize>> = (0..count)
        .step_by(part)
        .map(|start| start..(start + part).min(count))
        .collect();
    let bits = (count / BUCKET_KEYS).max(1).ilog2().min(MOST_BUCKET_BITS);
    // Each key's bucket (or [`SAME`], with the earlier key it equals in `index`), and how many
    // keys of each part each bucket takes.
    let mut buckets = filled(count, 0u16);
    let counts: Vec<Vec<u32>> = buckets
        .par_chunks_mut(part)
        .zip(index.par_chunks_mut(part))
        .zip(&parts)
        .map(|((out, same), range)| {
            let mut counts = vec![0u32; 1 << bits];
            let look_back = repeats == Repeats::Near;
            let slots = if look_back { RECENT } else { 1 };
            let mut recent = vec![([0u32; N], u32::MAX); slots];
            for ((b, same), i) in out.iter_mut().zip(same).zip(range.clone()) {
                *b = if used(i) {
                    let k = key(i);
                    let h = hash(&k);
                    let seen = &mut recent[(h >> 20) as usize & (slots - 1)];
                    if look_back && seen.1 != u32::MAX && seen.0 == k {
                        *same = seen.1;
                        SAME
                    } else {
                        if look_back {
                            *seen = (k, i as u32);
                        }
                        let b = if bits == 0 {
                            0
                        } else {
                            (h >> (64 - bits)) as usize
                        };
                        counts[b] += 1;
                        b as u16
                    }
                } else {
                    UNUSED
                };
            }
            counts
        })
        .collect();
    // Where each part's keys begin in each bucket: buckets one after another, each holding its
    // parts' keys in part order.
    let mut starts = vec![vec![0usize; 1 << bits]; parts.len()];
    let mut total = 0;
    for b in 0..1 << bits {
        for p in 0..parts.len() {
            starts[p][b] = total;
            total += counts[p][b] as usize;
        }
    }
    let mut keys = filled(total, [0u32; N]);
    let mut at = filled(total, 0u32);
    scatter(&mut keys, &mut at, &counts, &parts, &buckets, &key);
    // Each bucket's keys, welded: `at` becomes the first of each key's equals.
    let firsts = Firsts::new(count);
    let mut bucket_keys = Vec::with_capacity(1 << bits);
    let (mut keys_left, mut at_left) = (&keys[..], &mut at[..]);
    for b in 0..1 << bits {
        let n = counts.iter().map(|c| c[b] as usize).sum();
        let (k, rest) = keys_left.split_at(n);
        let (a, rest_at) = at_left.split_at_mut(n);
        bucket_keys.push((k, a));
        (keys_left, at_left) = (rest, rest_at);
    }
    bucket_keys
        .into_par_iter()
        .for_each_init(Vec::new, |table, (keys, at)| {
            weld_bucket(keys, at, table, &firsts)
        });
    drop(keys);
    let ranks = firsts.ranks();
    let mut order = filled(ranks.distinct() as usize, T::default());
    let mut order_parts = Vec::with_capacity(parts.len());
    let mut order_left = &mut order[..];
    for range in &parts {
        let (mine, rest) =
            order_left.split_at_mut((ranks.rank(range.end) - ranks.rank(range.start)) as usize);
        order_parts.push(mine);
        order_left = rest;
    }
    // Each key's number: the rank of its first among the firsts.
    index
        .par_chunks_mut(part)
        .zip(buckets.par_chunks(part))
        .zip(order_parts)
        .zip(starts)
        .zip(&parts)
        .for_each(|((((index, buckets), order), mut next), range)| {
            let base = ranks.rank(range.start);
            for (j, (&b, i)) in buckets.iter().zip(range.clone()).enumerate() {
                index[j] = match b {
                    UNUSED => NOT_USED,
                    SAME => index[index[j] as usize - range.start],
                    _ => {
                        let first = at[next[b as usize]];
                        next[b as usize] += 1;
                        let number = ranks.rank(first as usize);
                        if first as usize == i {
                            order[(number - base) as usize] = kept(i);
                        }
                        number
                    }
                };
            }
        });
    order
}

/// One part's share of one bucket: keys and their places.
type Stretch<'a, const N: usize> = (&'a mut [[u32; N]], &'a mut [u32]);

/// Copies each used key, and its place, into its bucket's stretch of `keys` and `at` (each part
/// in its own stretch of the bucket, in file order).
fn scatter<const N: usize>(
    keys: &mut [[u32; N]],
    at: &mut [u32],
    counts: &[Vec<u32>],
    parts: &[Range<usize>],
    buckets: &[u16],
    key: &(impl Fn(usize) -> [u32; N] + Sync),
) {
    let mut stretches: Vec<Vec<Stretch<N>>> = parts.iter().map(|_| Vec::new()).collect();
    let (mut keys, mut at) = (keys, at);
    for b in 0..counts.first().map_or(0, Vec::len) {
        for (p, counts) in counts.iter().enumerate() {
            let n = counts[b] as usize;
            let (k, rest) = std::mem::take(&mut keys).split_at_mut(n);
            let (a, rest_at) = std::mem::take(&mut at).split_at_mut(n);
            stretches[p].push((k, a));
            (keys, at) = (rest, rest_at);
        }
    }
    stretches
        .into_par_iter()
        .zip(parts)
        .for_each(|(mut stretches, range)| {
            let mut next = vec![0usize; stretches.len()];
            for i in range.clone() {
                let b = buckets[i];
                if b != UNUSED && b != SAME {
                    let (keys, at) = &mut stretches[b as usize];
                    let n = &mut next[b as usize];
                    keys[*n] = key(i);
                    at[*n] = i as u32;
                    *n += 1;
                }
            }
        });
}

/// Welds one bucket's keys (in file order, `at` their places): each place becomes the place of
/// the first equal key, and each first is marked in `firsts`. `table` is scratch space.
fn weld_bucket<const N: usize>(
    keys: &[[u32; N]],
    at: &mut [u32],
    table: &mut Vec<u32>,
    firsts: &Firsts,
) {
    let slots = (2 * keys.len()).next_power_of_two().max(2);
    let mask = slots - 1;
    table.clear();
    table.resize(slots, 0);
    // Open addressing on the hash's low bits: each full slot is the index + 1 of a first.
    for (e, key) in keys.iter().enumerate() {
        let mut slot = hash(key) as usize & mask;
        loop {
            let first = table[slot];
            if first == 0 {
                table[slot] = e as u32 + 1;
                firsts.mark(at[e] as usize);
                break;
            }
            if keys[first as usize - 1] == *key {
                at[e] = at[first as usize - 1];
                break;
            }
            slot = (slot + 1) & mask;
        }
    }
}

/// One flag a key, set for the first of each distinct key. A byte a key, stored without a
/// locked instruction: buckets welded on different cores mark places scattered over the file,
/// and a shared bit set's atomic `fetch_or` took 9% of a big PLY's load (profile of
/// `examples/model_load`).
struct Firsts(Vec<AtomicU8>);

impl Firsts {
    fn new(count: usize) -> Firsts {
        Firsts(collected(
            (0..count).into_par_iter().map(|_| AtomicU8::new(0)),
        ))
    }

    fn mark(&self, i: usize) {
        self.0[i].store(1, Ordering::Relaxed);
    }

    fn ranks(self) -> Ranks {
        let words: Vec<u64> = self
            .0
            .par_chunks(64)
            .map(|flags| {
                flags.iter().enumerate().fold(0u64, |word, (bit, flag)| {
                    word | u64::from(flag.load(Ordering::Relaxed)) << bit
                })
            })
            .collect();
        let mut before = Vec::with_capacity(words.len() + 1);
        let mut sum = 0u32;
        for w in &words {
            before.push(sum);
            sum += w.count_ones();
        }
        before.push(sum);
        Ranks { words, before }
    }
}

/// The firsts, counted: how many lie before any key.
struct Ranks {
    words: Vec<u64>,
    /// Firsts before each word (and, last, all of them).
    before: Vec<u32>,
}

impl Ranks {
    /// Firsts among keys `0..i`.
    #[inline]
    fn rank(&self, i: usize) -> u32 {
        let (w, bit) = (i / 64, i % 64);
        if bit == 0 {
            return self.before[w];
        }
        self.before[w] + (self.words[w] & ((1u64 << bit) - 1)).count_ones()
    }

    fn distinct(&self) -> u32 {
        *self.before.last().expect("one count a word, and the total")
    }
}

/// Vertices (or their keys), and triangles as indices into them.
pub type Indexed<T> = (Vec<T>, Vec<[u32; 3]>);

/// The vertices used (where `used(i)`) with distinct keys (`key(&vertices[i])` is vertex `i`'s),
/// in file order (each key at the place of the first used vertex that has it), and the
/// triangles re-indexed onto them. When every vertex is used and no key repeats, both come back
/// as they were, uncopied. A caller that knows which vertices its triangles use says so and
/// saves the pass that finds them (an ASCII STL's corners, each a triangle's, pass `|_| true`;
/// others pass [`super::used_vertices::used_bits`]).
pub fn weld_where<T: Copy + Send + Sync, const N: usize>(
    vertices: Vec<T>,
    key: impl Fn(&T) -> [u32; N] + Sync,
    triangles: Vec<[u32; 3]>,
    repeats: Repeats,
    used: impl Fn(usize) -> bool + Sync,
) -> Indexed<T> {
    let count = vertices.len();
    match weld_indices(count, |i| key(&vertices[i]), triangles, repeats, used) {
        (None, triangles) => (vertices, triangles),
        (Some(kept), triangles) => (kept_of(&vertices, &kept), triangles),
    }
}

/// As [`weld_where`], for `count` vertices held apart (`key(i)` is vertex `i`'s key): the
/// numbers of the vertices kept, in order (`None` when every vertex is used and no key repeats,
/// so that nothing need be copied), and the triangles re-indexed onto them.
pub fn weld_indices<const N: usize>(
    count: usize,
    key: impl Fn(usize) -> [u32; N] + Sync,
    mut triangles: Vec<[u32; 3]>,
    repeats: Repeats,
    used: impl Fn(usize) -> bool + Sync,
) -> (Option<Vec<u32>>, Vec<[u32; 3]>) {
    let mut index = filled(count, 0u32);
    let kept = weld(&mut index, repeats, key, used, |i| i as u32);
    if kept.len() == count {
        return (None, triangles);
    }
    let share = triangles
        .len()
        .div_ceil(rayon::current_num_threads())
        .max(1);
    triangles.par_chunks_mut(share).for_each(|part| {
        for t in part {
            *t = t.map(|i| index[i as usize]);
        }
    });
    (Some(kept), triangles)
}

/// The values of `values` at the numbers `kept`, in order.
pub fn kept_of<T: Copy + Send + Sync>(values: &[T], kept: &[u32]) -> Vec<T> {
    collected(kept.par_iter().map(|&i| values[i as usize]))
}

/// The positions whose coordinates have the bits `keys`.
pub fn positions_of(keys: &[[u32; 3]]) -> Vec<glam::Vec3> {
    keys.par_iter()
        .map(|k| glam::Vec3::from_array(k.map(f32::from_bits)))
        .collect()
}

/// A multiply-xorshift hash of a key's words: the high bits choose the bucket, the low bits
/// the slot.
#[inline]
fn hash<const N: usize>(key: &[u32; N]) -> u64 {
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
    use crate::mesh::used_vertices::used_bits;

    /// [`weld_where`] on the vertices `triangles` use.
    fn weld_used<T: Copy + Send + Sync, const N: usize>(
        vertices: Vec<T>,
        key: impl Fn(&T) -> [u32; N] + Sync,
        triangles: Vec<[u32; 3]>,
        repeats: Repeats,
    ) -> Indexed<T> {
        let used = used_bits(&triangles, vertices.len());
        weld_where(vertices, key, triangles, repeats, |i| {
            used[i / 64] >> (i % 64) & 1 == 1
        })
    }

    /// What one table, looked up key by key, gives.
    fn welded_one_by_one(keys: &[[u32; 3]], used: impl Fn(usize) -> bool) -> (Vec<u32>, Vec<u32>) {
        let mut seen = std::collections::HashMap::new();
        let mut firsts = Vec::new();
        let index = (0..keys.len())
            .map(|i| {
                if !used(i) {
                    return NOT_USED;
                }
                *seen.entry(keys[i]).or_insert_with(|| {
                    firsts.push(i as u32);
                    firsts.len() as u32 - 1
                })
            })
            .collect();
        (index, firsts)
    }

    #[test]
    fn equal_keys_share_a_number_in_order_of_first_sight_across_buckets_and_parts() {
        // 300,000 keys whose values repeat in a scattered order: many buckets and parts.
        let keys: Vec<[u32; 3]> = (0..300_000u32)
            .map(|i| [(i * 7919) % 65_537, i % 3, 0])
            .collect();
        let used = |i: usize| i % 11 != 5;
        let (expected_index, expected_firsts) = welded_one_by_one(&keys, used);
        for repeats in [Repeats::Near, Repeats::Rare] {
            let mut index = vec![0; keys.len()];
            let firsts = weld(&mut index, repeats, |i| keys[i], used, |i| i as u32);
            assert_eq!(firsts, expected_firsts, "{repeats:?}");
            assert_eq!(index, expected_index, "{repeats:?}");
        }
    }

    #[test]
    fn a_few_keys_weld_in_one_bucket() {
        let keys = [[1, 2, 3], [4, 5, 6], [1, 2, 3], [7, 8, 9], [4, 5, 6]];
        for repeats in [Repeats::Near, Repeats::Rare] {
            let mut index = vec![0; keys.len()];
            let firsts = weld(&mut index, repeats, |i| keys[i], |_| true, |i| i as u32);
            assert_eq!(index, vec![0, 1, 0, 2, 1], "{repeats:?}");
            assert_eq!(firsts, vec![0, 1, 3], "{repeats:?}");
        }
    }

    #[test]
    fn unused_vertices_go_and_repeats_join_the_first_in_file_order() {
        // Vertex 1 is unused; 3 repeats 0's key; 4 repeats 2's.
        let keys = vec![[5, 0], [9, 9], [7, 0], [5, 0], [7, 0]];
        let triangles = vec![[3, 2, 4], [0, 4, 2]];
        for repeats in [Repeats::Near, Repeats::Rare] {
            let (kept, welded) = weld_used(keys.clone(), |k| *k, triangles.clone(), repeats);
            assert_eq!(kept, vec![[5, 0], [7, 0]], "{repeats:?}");
            assert_eq!(welded, vec![[0, 1, 1], [0, 1, 1]], "{repeats:?}");
        }
    }

    #[test]
    fn a_soup_of_corners_welds_alike_with_or_without_the_used_pass() {
        // Every corner its own vertex, as an ASCII STL reads them: 3,000 triangles on 1,000 keys.
        let keys: Vec<[u32; 3]> = (0..9_000u32).map(|i| [(i * 7) % 1_000, 3, 4]).collect();
        let triangles: Vec<[u32; 3]> = (0..3_000u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        for repeats in [Repeats::Near, Repeats::Rare] {
            let all = weld_where(keys.clone(), |k| *k, triangles.clone(), repeats, |_| true);
            let used = weld_used(keys.clone(), |k| *k, triangles.clone(), repeats);
            assert_eq!(all.0.len(), 1_000, "{repeats:?}");
            assert_eq!(all, used, "{repeats:?}");
        }
    }

    #[test]
    fn many_keys_across_buckets_weld_as_one_table_would() {
        // 40,000 vertices whose keys repeat every 15,000: enough for several buckets.
        let keys: Vec<[u32; 3]> = (0..40_000u32).map(|i| [i % 15_000, 1, 2]).collect();
        let triangles: Vec<[u32; 3]> = (0..39_998u32).map(|i| [i, i + 1, i + 2]).collect();
        for repeats in [Repeats::Near, Repeats::Rare] {
            let (kept, welded) = weld_used(keys.clone(), |k| *k, triangles.clone(), repeats);
            assert_eq!(kept.len(), 15_000);
            assert_eq!(kept, keys[..15_000]);
            for (old, new) in triangles.iter().zip(&welded) {
                assert_eq!(old.map(|i| keys[i as usize]), new.map(|i| kept[i as usize]));
            }
        }
    }

    #[test]
    fn distinct_used_keys_come_back_uncopied() {
        let keys = vec![[1u32, 0], [2, 0], [3, 0]];
        let triangles = vec![[0, 1, 2]];
        let (kept, same) = weld_used(keys.clone(), |k| *k, triangles.clone(), Repeats::Rare);
        assert_eq!((kept, same), (keys, triangles));
    }

    #[test]
    fn negative_zero_welds_with_zero() {
        assert_eq!(coordinate_bits(-0.0), coordinate_bits(0.0));
        assert_ne!(coordinate_bits(1.0), coordinate_bits(-1.0));
    }
}
