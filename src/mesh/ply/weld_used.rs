//! Welding a PLY's vertices: the vertices some triangle uses, with bit-identical keys (a
//! position, or a position and a colour) merged into the first of them in the file, kept in
//! file order. Scans list each vertex once, so nearly every key is new: rather than one large
//! table that misses the cache on every key, the keys are split by their hash into buckets
//! small enough that each bucket's table stays in the cache of one core, and the buckets are
//! welded in parallel.

use rayon::prelude::*;

use crate::mesh::weld::hash;

/// Keys a bucket holds on average: its table (twice as many `u32` slots) fits in 32 KiB.
const BUCKET_KEYS: usize = 1 << 12;

/// The vertices `triangles` use with distinct keys (`key(&vertices[i])` is vertex `i`'s), in
/// file order (each key at the place of the first used vertex that has it), and the triangles
/// re-indexed onto them. When every vertex is used and no key repeats, both come back as they
/// were, uncopied.
pub fn weld_used<T: Copy + Send + Sync, const N: usize>(
    vertices: Vec<T>,
    key: impl Fn(&T) -> [u32; N] + Sync,
    mut triangles: Vec<[u32; 3]>,
) -> (Vec<T>, Vec<[u32; 3]>) {
    let used = used_vertices(vertices.len(), &triangles);
    let repeats = repeated_keys(&vertices, &key, &used);
    let all_used = used.iter().map(|w| w.count_ones() as usize).sum::<usize>() == vertices.len();
    if all_used && repeats.is_empty() {
        return (vertices, triangles);
    }
    let keys = vertices;
    // Each kept vertex's new index; a repeat takes its first's.
    const REPEAT: u32 = u32::MAX;
    let mut index = vec![REPEAT; keys.len()];
    for &(repeat, _) in &repeats {
        index[repeat as usize] = REPEAT - 1;
    }
    let mut kept = Vec::with_capacity(keys.len() - repeats.len());
    for (i, key) in keys.iter().enumerate() {
        if is_used(&used, i) && index[i] == REPEAT {
            index[i] = kept.len() as u32;
            kept.push(*key);
        }
    }
    for &(repeat, first) in &repeats {
        index[repeat as usize] = index[first as usize];
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
    (kept, triangles)
}

/// One bit a vertex, set when a triangle uses it.
fn used_vertices(vertices: usize, triangles: &[[u32; 3]]) -> Vec<u64> {
    let words = vertices.div_ceil(64);
    let share = triangles
        .len()
        .div_ceil(rayon::current_num_threads())
        .max(1);
    triangles
        .par_chunks(share)
        .map(|part| {
            let mut bits = vec![0u64; words];
            for &i in part.iter().flatten() {
                bits[i as usize / 64] |= 1 << (i % 64);
            }
            bits
        })
        .reduce(
            || vec![0u64; words],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(a, b)| *a |= b);
                a
            },
        )
}

fn is_used(used: &[u64], i: usize) -> bool {
    used[i / 64] >> (i % 64) & 1 == 1
}

/// Each used vertex whose key an earlier used vertex has, with that earlier vertex (the first
/// that has it), in no particular order.
fn repeated_keys<T: Sync, const N: usize>(
    vertices: &[T],
    key: &(impl Fn(&T) -> [u32; N] + Sync),
    used: &[u64],
) -> Vec<(u32, u32)> {
    let count = used.iter().map(|w| w.count_ones() as usize).sum::<usize>();
    let bits = (count / BUCKET_KEYS).max(1).ilog2().min(12);
    let bucket = |h: u64| {
        if bits == 0 {
            0
        } else {
            (h >> (64 - bits)) as usize
        }
    };
    let used_keys = || {
        vertices
            .iter()
            .enumerate()
            .filter(|&(i, _)| is_used(used, i))
            .map(|(i, v)| (hash(&key(v)), i as u32))
    };
    // The used vertices split by bucket, in file order within each.
    let mut starts = vec![0usize; (1 << bits) + 1];
    for (h, _) in used_keys() {
        starts[bucket(h) + 1] += 1;
    }
    for b in 1..starts.len() {
        starts[b] += starts[b - 1];
    }
    // The hash's low half (it picks a slot) and the vertex: 8 bytes a vertex.
    let mut entries = vec![(0u32, 0u32); count];
    let mut next = starts.clone();
    for (h, i) in used_keys() {
        let b = bucket(h);
        entries[next[b]] = (h as u32, i);
        next[b] += 1;
    }
    let mut buckets = Vec::with_capacity(1 << bits);
    let mut rest = &entries[..];
    for w in starts.windows(2) {
        let (bucket, after) = rest.split_at(w[1] - w[0]);
        buckets.push(bucket);
        rest = after;
    }
    buckets
        .into_par_iter()
        .map(|bucket| repeats_in(vertices, key, bucket))
        .reduce(Vec::new, |mut a, mut b| {
            a.append(&mut b);
            a
        })
}

/// The repeats among `bucket`'s vertices (hash and index, in file order), each with the first
/// vertex of its key.
fn repeats_in<T, const N: usize>(
    vertices: &[T],
    key: impl Fn(&T) -> [u32; N],
    bucket: &[(u32, u32)],
) -> Vec<(u32, u32)> {
    let mut repeats = Vec::new();
    let slots = (2 * bucket.len()).next_power_of_two().max(2);
    let mask = slots - 1;
    // Open addressing on the hash's low bits: each slot the index + 1 of a first vertex.
    let mut table = vec![0u32; slots];
    for &(h, i) in bucket {
        let mut at = h as usize & mask;
        loop {
            let slot = table[at];
            if slot == 0 {
                table[at] = i + 1;
                break;
            }
            if key(&vertices[slot as usize - 1]) == key(&vertices[i as usize]) {
                repeats.push((i, slot - 1));
                break;
            }
            at = (at + 1) & mask;
        }
    }
    repeats
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unused_vertices_go_and_repeats_join_the_first_in_file_order() {
        // Vertex 1 is unused; 3 repeats 0's key; 4 repeats 2's.
        let keys = vec![[5, 0], [9, 9], [7, 0], [5, 0], [7, 0]];
        let triangles = vec![[3, 2, 4], [0, 4, 2]];
        let (kept, triangles) = weld_used(keys, |k| *k, triangles);
        assert_eq!(kept, vec![[5, 0], [7, 0]]);
        assert_eq!(triangles, vec![[0, 1, 1], [0, 1, 1]]);
    }

    #[test]
    fn many_keys_across_buckets_weld_as_one_table_would() {
        // 40,000 vertices whose keys repeat every 15,000: enough for several buckets.
        let keys: Vec<[u32; 3]> = (0..40_000u32).map(|i| [i % 15_000, 1, 2]).collect();
        let triangles: Vec<[u32; 3]> = (0..39_998u32).map(|i| [i, i + 1, i + 2]).collect();
        let (kept, welded) = weld_used(keys.clone(), |k| *k, triangles.clone());
        assert_eq!(kept.len(), 15_000);
        assert_eq!(kept, keys[..15_000]);
        for (old, new) in triangles.iter().zip(&welded) {
            assert_eq!(old.map(|i| keys[i as usize]), new.map(|i| kept[i as usize]));
        }
    }
}
