//! Whether every vertex of a mesh is used by some triangle: a model read from a file nearly
//! always uses them all, and then needs no renumbering.

use rayon::prelude::*;

/// Triangles a core marks in one go.
const CHUNK: usize = 1 << 16;

/// One bit a vertex (bit `i % 64` of word `i / 64`), set when vertex `i` of the `vertices` is
/// a corner of some triangle of `triangles` (indices at or past `vertices` mark nothing). Each
/// core marks its triangles' corners in a bit set of its own (82 KB for 655,362 vertices: it
/// stays in the cache, where one shared array of flags took a pass of random writes on one
/// core), and the sets are joined.
pub fn used_bits(triangles: &[[u32; 3]], vertices: usize) -> Vec<u64> {
    let words = vertices.div_ceil(64);
    triangles
        .par_chunks(CHUNK)
        .fold(
            || vec![0u64; words],
            |mut marks, chunk| {
                for &i in chunk.iter().flatten() {
                    if let Some(word) = marks.get_mut(i as usize / 64) {
                        *word |= 1 << (i % 64);
                    }
                }
                marks
            },
        )
        .reduce(
            || vec![0u64; words],
            |mut a, b| {
                a.iter_mut().zip(&b).for_each(|(x, y)| *x |= y);
                a
            },
        )
}

/// Whether `marks` ([`used_bits`] of `vertices` vertices) has every vertex's bit set.
fn every_vertex_marked(marks: &[u64], vertices: usize) -> bool {
    let words = vertices.div_ceil(64);
    // Bits past the last vertex are never set (their indices are out of range).
    let last = match vertices % 64 {
        0 => u64::MAX,
        partial => (1 << partial) - 1,
    };
    marks
        .iter()
        .enumerate()
        .all(|(k, &word)| word == if k + 1 == words { last } else { u64::MAX })
}

/// A model's unused vertices left out: when some of the `vertices` is no corner of
/// `triangles` (indices below `vertices`), renumbers the triangles onto the vertices they use,
/// kept in their order, and returns the old number of each kept vertex. `None`, the triangles
/// as they were, when every vertex is used (as in nearly every model file). One pass on every
/// core marks the used vertices for both the question and the renumbering.
pub fn drop_unused(triangles: &mut [[u32; 3]], vertices: usize) -> Option<Vec<u32>> {
    let marks = used_bits(triangles, vertices);
    if every_vertex_marked(&marks, vertices) {
        return None;
    }
    let mut new_index = vec![u32::MAX; vertices];
    let mut kept = Vec::new();
    for (word_index, &word) in marks.iter().enumerate() {
        let mut bits = word;
        while bits != 0 {
            let old = word_index * 64 + bits.trailing_zeros() as usize;
            new_index[old] = kept.len() as u32;
            kept.push(old as u32);
            bits &= bits - 1;
        }
    }
    triangles
        .par_iter_mut()
        .for_each(|t| *t = t.map(|i| new_index[i as usize]));
    Some(kept)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether each of the `vertices` vertices is a corner of some triangle of `triangles`.
    fn all_used(triangles: &[[u32; 3]], vertices: usize) -> bool {
        every_vertex_marked(&used_bits(triangles, vertices), vertices)
    }

    #[test]
    fn a_vertex_no_triangle_names_is_found_wherever_it_lies() {
        for vertices in [3usize, 63, 64, 65, 200_000] {
            // A fan over every vertex, in many chunks for the largest.
            let fan: Vec<[u32; 3]> = (1..vertices as u32 - 1).map(|k| [0, k, k + 1]).collect();
            assert!(all_used(&fan, vertices), "{vertices}");
            for missing in [0, vertices / 2, vertices - 1] {
                let without: Vec<[u32; 3]> = fan
                    .iter()
                    .map(|t| {
                        t.map(|i| {
                            if i as usize == missing {
                                (missing as u32 + 1) % vertices as u32
                            } else {
                                i
                            }
                        })
                    })
                    .collect();
                assert!(!all_used(&without, vertices), "{vertices} {missing}");
            }
        }
        // An index out of range marks nothing.
        assert!(all_used(&[[0, 1, 2]], 3));
        assert!(!all_used(&[[0, 1, 5]], 3));
        assert!(all_used(&[], 0));
    }

    #[test]
    fn keeping_the_used_vertices_renumbers_them_in_order() {
        // Vertices 0, 2 and 5 of 7 unused.
        let mut triangles = vec![[1, 3, 4], [4, 3, 6], [6, 1, 1]];
        let kept = drop_unused(&mut triangles, 7);
        assert_eq!(kept.as_deref(), Some(&[1, 3, 4, 6][..]));
        assert_eq!(triangles, [[0, 1, 2], [2, 1, 3], [3, 0, 0]]);
        // Every vertex used: nothing renumbered.
        let kept = drop_unused(&mut triangles, 4);
        assert_eq!(kept, None);
        assert_eq!(triangles, [[0, 1, 2], [2, 1, 3], [3, 0, 0]]);
        // Many words of marks, the unused ones scattered among them.
        let vertices = 1000;
        let unused = |v: u32| v % 7 == 3 || v == 999;
        let used: Vec<u32> = (0..vertices).filter(|&v| !unused(v)).collect();
        let mut triangles: Vec<[u32; 3]> = used
            .chunks(3)
            .map(|c| [c[0], c[c.len() / 2], c[c.len() - 1]])
            .collect();
        let before = triangles.clone();
        let kept = drop_unused(&mut triangles, vertices as usize).unwrap();
        assert_eq!(kept, used);
        for (new, old) in triangles.iter().zip(&before) {
            assert_eq!(new.map(|i| kept[i as usize]), *old);
        }
    }
}
