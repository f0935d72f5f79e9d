//! Measurements of a triangle mesh as an engineer checks a part: bounding-box size, surface area,
//! whether it is closed, its non-manifold edges and degenerate triangles, and for a closed mesh
//! its volume by the divergence theorem.
//!
//! Topology is read on welded positions: corners at bit-identical coordinates (−0 as 0) are one
//! vertex, so a cube whose faces each have their own vertices (as flat shading and most exporters
//! leave it) is still closed. An edge used by one triangle is a boundary edge, by more than two a
//! non-manifold one. A closed mesh (no boundary or non-manifold edge) whose neighbouring
//! triangles all wind the same way bounds a volume: V = Σ a·(b × c) / 6 over its triangles, in
//! `f64` so that a million triangles lose no digits.

use std::borrow::Cow;

use glam::{DVec3, Vec3};

use rayon::prelude::*;

use super::face_list::has_zero_area;
use super::weld::{self, Repeats, coordinate_bits};
use crate::huge_pages;

/// What [`measure`] finds. Lengths in the mesh's units, areas in their square, volumes in their
/// cube.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Measurements {
    /// Axis-aligned bounds (min, max); `None` for no triangles.
    pub bounds: Option<(Vec3, Vec3)>,
    /// Triangles measured.
    pub triangles: usize,
    /// Sum of the triangles' areas.
    pub area: f64,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Edges used by three or more triangles.
    pub non_manifold_edges: usize,
    /// Edges whose two triangles run along them the same way (one of them is turned over).
    pub misoriented_edges: usize,
    /// Triangles with zero area (corners that coincide or lie on one line).
    pub degenerate_triangles: usize,
    /// The enclosed volume, for a closed and consistently wound mesh; positive whichever way its
    /// triangles face.
    pub volume: Option<f64>,
}

impl Measurements {
    /// No boundary and no non-manifold edge, and at least one triangle.
    pub fn closed(&self) -> bool {
        self.triangles > 0 && self.boundary_edges == 0 && self.non_manifold_edges == 0
    }

    /// The bounding box's size (width, height, depth); zero when empty.
    pub fn size(&self) -> Vec3 {
        self.bounds.map_or(Vec3::ZERO, |(lo, hi)| hi - lo)
    }

    /// `closed` or `open (N boundary edges)`, as `rastray info` and the editor say it.
    pub fn closure(&self) -> String {
        if self.closed() {
            "closed".into()
        } else {
            format!("open ({} boundary edges)", self.boundary_edges)
        }
    }

    /// These measurements with lengths divided by `scale` > 0 (areas by its square, volumes by
    /// its cube): a scaled mesh measured in its file's units.
    pub fn unscaled(self, scale: f32) -> Measurements {
        let s = scale as f64;
        Measurements {
            bounds: self.bounds.map(|(lo, hi)| (lo / scale, hi / scale)),
            area: self.area / (s * s),
            volume: self.volume.map(|v| v / (s * s * s)),
            ..self
        }
    }

    /// Several objects together (a scene): bounds joined, counts and areas added, volume the sum
    /// of the closed ones' (`None` when none is closed).
    pub fn total(all: &[Measurements]) -> Measurements {
        let bounds = all
            .iter()
            .filter_map(|m| m.bounds)
            .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)));
        let volumes: Vec<f64> = all.iter().filter_map(|m| m.volume).collect();
        Measurements {
            bounds,
            triangles: all.iter().map(|m| m.triangles).sum(),
            area: all.iter().map(|m| m.area).sum(),
            boundary_edges: all.iter().map(|m| m.boundary_edges).sum(),
            non_manifold_edges: all.iter().map(|m| m.non_manifold_edges).sum(),
            misoriented_edges: all.iter().map(|m| m.misoriented_edges).sum(),
            degenerate_triangles: all.iter().map(|m| m.degenerate_triangles).sum(),
            volume: (!volumes.is_empty()).then(|| volumes.iter().sum()),
        }
    }
}

/// Triangles summed as one piece, in order: partial sums of fixed pieces added in order make
/// the totals the same whatever the number of threads. Small enough that a mesh of a hundred
/// thousand triangles (the Stanford bunny's 69,451) is shared among the cores: pieces of 65,536
/// left it to one. Each piece is a task of its own (`with_max_len(1)`), here and for the edge
/// count's vertices: rayon would otherwise cut the pieces into one half a thread, and a thread
/// that woke late (on a 2-core virtual machine, often) found its half already taken by the
/// other, which then did all the work.
const PIECE: usize = 1 << 13;

/// Measures the triangles of `parts` (each a position list and triangles indexing it) as one
/// mesh, welded across parts. Sums, edges and the sort run on the current rayon pool.
pub fn measure(parts: &[(&[Vec3], &[[u32; 3]])]) -> Measurements {
    // The parts' positions one after another (one part's borrowed as they are).
    let positions: Cow<[Vec3]> = match parts {
        [(positions, _)] => Cow::Borrowed(positions),
        _ => Cow::Owned(parts.iter().flat_map(|(p, _)| p.iter().copied()).collect()),
    };
    let welded = weld(&positions);
    let mut m = Measurements::default();
    let mut six_volumes = Vec::new();
    for (part_positions, triangles) in parts {
        let pieces: Vec<(Measurements, f64)> = triangles
            .par_chunks(PIECE)
            .with_max_len(1)
            .map(|piece| measure_piece(part_positions, piece))
            .collect();
        for (piece, six_volume) in pieces {
            six_volumes.push(six_volume);
            m.bounds = match (m.bounds, piece.bounds) {
                (Some((lo, hi)), Some((a, b))) => Some((lo.min(a), hi.max(b))),
                (bounds, None) | (None, bounds) => bounds,
            };
            m.triangles += piece.triangles;
            m.degenerate_triangles += piece.degenerate_triangles;
            m.area += piece.area;
        }
    }
    // The triangles on welded ids: the parts' own when their positions are all distinct and
    // there is one part (as in a file that shares its vertices), with no copy.
    let renumbered: Vec<[u32; 3]>;
    let welded_triangles: &[[u32; 3]] = match (&welded.ids, parts) {
        (None, [(_, triangles)]) => triangles,
        _ => {
            let mut all = Vec::with_capacity(parts.iter().map(|(_, t)| t.len()).sum());
            let mut first = 0;
            for (part_positions, triangles) in parts {
                let id = |i: u32| match &welded.ids {
                    Some(ids) => ids[first + i as usize],
                    None => (first + i as usize) as u32,
                };
                all.par_extend(triangles.par_iter().map(|t| t.map(id)));
                first += part_positions.len();
            }
            renumbered = all;
            &renumbered
        }
    };
    let edges = edge_counts(welded_triangles, welded.count);
    m.boundary_edges = edges.boundary;
    m.non_manifold_edges = edges.non_manifold;
    m.misoriented_edges = edges.misoriented;
    // One part of distinct positions: its pieces' volumes are the welded mesh's, piece by piece.
    if m.closed() && m.misoriented_edges == 0 && welded.ids.is_none() && parts.len() == 1 {
        let six_v: f64 = six_volumes.iter().sum();
        m.volume = Some((six_v / 6.0).abs());
    } else if m.closed() && m.misoriented_edges == 0 {
        let pieces: Vec<f64> = welded_triangles
            .par_chunks(PIECE)
            .map(|piece| {
                piece
                    .iter()
                    .map(|t| {
                        let [a, b, c] = t.map(|i| welded.position(&positions, i));
                        a.dot(b.cross(c))
                    })
                    .sum()
            })
            .collect();
        let six_v: f64 = pieces.iter().sum();
        m.volume = Some((six_v / 6.0).abs());
    }
    m
}

/// The positions of several parts welded: how many distinct ones, and each one's id.
struct Welded {
    /// Distinct positions: ids are below this.
    count: usize,
    /// Each position's id (the parts' positions one after another), and for each id the
    /// position of its first (as `f64`); `None` when the positions are all distinct, each its
    /// own id (its place among the parts' positions).
    ids: Option<Vec<u32>>,
    firsts: Vec<DVec3>,
}

impl Welded {
    /// The position of id `id` (`positions`: the parts' positions welded).
    #[inline]
    fn position(&self, positions: &[Vec3], id: u32) -> DVec3 {
        match self.ids {
            Some(_) => self.firsts[id as usize],
            None => positions[id as usize].as_dvec3(),
        }
    }
}

/// `positions` welded by the loaders' welder ([`weld::weld`]): positions whose coordinates
/// have the same bits (−0 as 0) share an id, numbered in order of first sight, the first of
/// them giving its position.
fn weld(positions: &[Vec3]) -> Welded {
    let mut ids = vec![0u32; positions.len()];
    let firsts = weld::weld(
        &mut ids,
        Repeats::Rare,
        |i| positions[i].to_array().map(coordinate_bits),
        |_| true,
        |i| i as u32,
    );
    if firsts.len() == positions.len() {
        return Welded {
            count: positions.len(),
            ids: None,
            firsts: Vec::new(),
        };
    }
    Welded {
        count: firsts.len(),
        ids: Some(ids),
        firsts: firsts
            .par_iter()
            .map(|&i| positions[i as usize].as_dvec3())
            .collect(),
    }
}

/// Bounds, count, degenerate count and area of `triangles` (indexing `positions`).
/// Also six times the signed volume the triangles bound with the origin, Σ a·(b × c): the
/// volume of a closed mesh, summed while its corners are at hand.
fn measure_piece(positions: &[Vec3], triangles: &[[u32; 3]]) -> (Measurements, f64) {
    let mut m = Measurements::default();
    let mut six_volume = 0.0;
    for &[a, b, c] in triangles {
        let [pa, pb, pc] = [a, b, c].map(|i| positions[i as usize]);
        m.bounds = Some(match m.bounds {
            None => (pa.min(pb).min(pc), pa.max(pb).max(pc)),
            Some((lo, hi)) => (lo.min(pa).min(pb).min(pc), hi.max(pa).max(pb).max(pc)),
        });
        m.triangles += 1;
        if has_zero_area(pa, pb, pc) {
            m.degenerate_triangles += 1;
        }
        let [da, db, dc] = [pa, pb, pc].map(Vec3::as_dvec3);
        m.area += 0.5 * (db - da).cross(dc - da).length();
        six_volume += da.dot(db.cross(dc));
    }
    (m, six_volume)
}

/// How the edges of a welded mesh are shared.
#[derive(Default)]
struct EdgeCounts {
    boundary: usize,
    non_manifold: usize,
    misoriented: usize,
}

/// Counts the edges by how many triangles use them. A triangle with a repeated corner adds no
/// edge between equal corners. Vertex ids are below 2³¹ (a world holds at most a few tens of
/// millions), so an edge's higher end and direction fit one `u32`.
///
/// The triangles are cut into one run a core, and each run gathers its edges by their lower
/// end on its own (a counting sort: two passes, no comparisons; [`RunRows`]), reading each
/// triangle once a pass. Then each vertex's few edges, taken from every run's row, are sorted on
/// their own, the vertices shared out among the cores. (Splitting the vertices among the cores
/// instead had every core read every triangle, twice; one set of rows that all runs wrote into
/// had two cores writing to the same cache lines.)
fn edge_counts(triangles: &[[u32; 3]], vertices: usize) -> EdgeCounts {
    let runs = rayon::current_num_threads().clamp(1, MAX_RUNS);
    let per_run = triangles.len().div_ceil(runs).max(1);
    let runs: Vec<RunRows> = triangles
        .par_chunks(per_run)
        .map(|run| RunRows::of(run, vertices))
        .collect();
    (0..vertices.div_ceil(ROW_VERTICES))
        .into_par_iter()
        .with_max_len(1)
        .map(|k| {
            let mut counts = EdgeCounts::default();
            let mut row = Vec::with_capacity(SHORT_ROW);
            for v in k * ROW_VERTICES..((k + 1) * ROW_VERTICES).min(vertices) {
                row.clear();
                for run in &runs {
                    row.extend_from_slice(run.row(v));
                }
                count_row(&mut row, &mut counts);
            }
            counts
        })
        .reduce(EdgeCounts::default, |a, b| EdgeCounts {
            boundary: a.boundary + b.boundary,
            non_manifold: a.non_manifold + b.non_manifold,
            misoriented: a.misoriented + b.misoriented,
        })
}

/// Most runs [`edge_counts`] cuts the triangles into: each holds a row start per vertex.
const MAX_RUNS: usize = 8;

/// Vertices whose edges one task of [`edge_counts`] counts.
const ROW_VERTICES: usize = 1 << 13;

/// The edges of some triangles by lower end, as compressed rows: each edge's higher end shifted
/// left one bit, and its direction in bit 0, so that the two uses of one edge sort side by side.
struct RunRows {
    /// Where each vertex's row ends in `edges` (row `v` starts where row `v - 1` ends, row 0
    /// at 0).
    row_ends: Vec<u32>,
    /// The rows one after another.
    edges: Vec<u32>,
}

impl RunRows {
    /// The rows of `triangles`' edges (vertex ids below `vertices`), each in triangle order.
    /// Both arrays are in 2 MiB pages: the 1.31M-triangle icosphere's rows fill 21 MB, which
    /// took a quarter of `rastray info`'s page faults in 4 KiB pages.
    fn of(triangles: &[[u32; 3]], vertices: usize) -> RunRows {
        let mut row_ends = huge_pages::filled(vertices, 0u32);
        by_lower_end(triangles, |lower, _| row_ends[lower] += 1);
        // Where each row starts; filling a row moves its entry on to where it ends.
        let mut at = 0;
        for row in &mut row_ends {
            (*row, at) = (at, at + *row);
        }
        let mut edges = huge_pages::filled(at as usize, 0u32);
        by_lower_end(triangles, |lower, end| {
            edges[row_ends[lower] as usize] = end;
            row_ends[lower] += 1;
        });
        RunRows { row_ends, edges }
    }

    /// The edges whose lower end is vertex `v`.
    fn row(&self, v: usize) -> &[u32] {
        let start = if v == 0 { 0 } else { self.row_ends[v - 1] };
        &self.edges[start as usize..self.row_ends[v] as usize]
    }
}

/// Calls `edge(lower, end)` for each edge of `triangles`, in triangle order: `lower` is its
/// lower end, `end` its higher end shifted left one bit, with its direction (whether it runs
/// from higher to lower) in bit 0.
#[inline(always)]
fn by_lower_end(triangles: &[[u32; 3]], mut edge: impl FnMut(usize, u32)) {
    for &[a, b, c] in triangles {
        for (from, to) in [(a, b), (b, c), (c, a)] {
            let (lo, hi) = (from.min(to), from.max(to));
            debug_assert!(hi < 1 << 31, "vertex ids fit in 31 bits");
            if from != to {
                edge(lo as usize, hi << 1 | (from > to) as u32);
            }
        }
    }
}

/// Rows of at most this many edge uses are sorted by insertion, in line: a closed mesh's row
/// holds about six, and calling the library sort for each of them (with a binary search for
/// each edge's uses) made `rastray info` on the 1.31M-triangle icosphere about 3% slower.
const SHORT_ROW: usize = 16;

/// Counts the edges of one vertex's row (higher ends and directions, see [`edge_counts`]).
fn count_row(row: &mut [u32], counts: &mut EdgeCounts) {
    if row.len() <= SHORT_ROW {
        insertion_sort(row);
    } else {
        row.sort_unstable();
    }
    let mut start = 0;
    while start < row.len() {
        let edge = row[start] >> 1;
        // Uses of one edge are few (two in a closed mesh): found one by one.
        let mut end = start + 1;
        while end < row.len() && row[end] >> 1 == edge {
            end += 1;
        }
        match end - start {
            1 => counts.boundary += 1,
            2 if row[start] == row[start + 1] => counts.misoriented += 1,
            2 => {}
            _ => counts.non_manifold += 1,
        }
        start = end;
    }
}

/// Sorts the few numbers of `row` in ascending order.
#[inline]
fn insertion_sort(row: &mut [u32]) {
    for i in 1..row.len() {
        let value = row[i];
        let mut j = i;
        while j > 0 && row[j - 1] > value {
            row[j] = row[j - 1];
            j -= 1;
        }
        row[j] = value;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{cuboid, icosahedron};
    use crate::test_draws::draws;

    /// `triangles` with every triangle given its own three corners, as a flat-shaded export.
    fn unshared(positions: &[Vec3], triangles: &[[u32; 3]]) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let corners: Vec<Vec3> = triangles
            .iter()
            .flat_map(|t| t.map(|i| positions[i as usize]))
            .collect();
        let split = (0..triangles.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        (corners, split)
    }

    #[test]
    fn a_unit_cube_of_unshared_faces_is_closed_with_volume_one() {
        let cube = cuboid(Vec3::ONE, 3);
        let (positions, triangles) = unshared(&cube.positions, &cube.triangles);
        let m = measure(&[(&positions, &triangles)]);
        assert!(m.closed(), "{m:?}");
        assert_eq!(m.closure(), "closed");
        assert!((m.volume.unwrap() - 1.0).abs() < 1e-9, "{m:?}");
        assert!((m.area - 6.0).abs() < 1e-9);
        assert_eq!(m.size(), Vec3::ONE);
        assert_eq!((m.non_manifold_edges, m.degenerate_triangles), (0, 0));
    }

    #[test]
    fn an_icosphere_is_within_half_a_percent_of_the_sphere() {
        let sphere = icosahedron(2.0, 5);
        let m = measure(&[(&sphere.positions, &sphere.triangles)]);
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
        let error = (m.volume.unwrap() - exact).abs() / exact;
        assert!(error < 0.005, "{error}");
        // The polyhedron lies inside the sphere.
        assert!(m.volume.unwrap() < exact);
    }

    #[test]
    fn a_missing_face_opens_the_cube_and_a_fin_is_non_manifold() {
        let cube = cuboid(Vec3::ONE, 1);
        let open = &cube.triangles[2..];
        let m = measure(&[(&cube.positions, open)]);
        assert_eq!(m.closure(), "open (4 boundary edges)");
        assert_eq!(m.volume, None);
        // A third triangle on one of the cube's edges: that edge is shared by three.
        let [a, b, _] = cube.triangles[0];
        let mut positions = cube.positions.clone();
        positions.push(Vec3::splat(5.0));
        let mut fin = cube.triangles.clone();
        fin.push([a, b, positions.len() as u32 - 1]);
        let m = measure(&[(&positions, &fin)]);
        assert_eq!(m.non_manifold_edges, 1);
        assert!(!m.closed());
    }

    #[test]
    fn a_turned_over_face_gives_no_volume_and_degenerate_triangles_are_counted() {
        let cube = cuboid(Vec3::ONE, 1);
        let mut flipped = cube.triangles.clone();
        flipped[0].swap(1, 2);
        let m = measure(&[(&cube.positions, &flipped)]);
        assert!(m.closed());
        assert!(m.misoriented_edges > 0);
        assert_eq!(m.volume, None);
        let line = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        let m = measure(&[(&line, &[[0, 1, 2], [0, 0, 1]])]);
        assert_eq!(m.degenerate_triangles, 2);
    }

    #[test]
    fn parts_weld_together_and_scale_divides_out() {
        // The cube's triangles in two parts, each with its own copy of the positions.
        let cube = cuboid(Vec3::splat(2.0), 1);
        let (first, second) = cube.triangles.split_at(5);
        let m = measure(&[(&cube.positions, first), (&cube.positions, second)]);
        assert!((m.volume.unwrap() - 8.0).abs() < 1e-9);
        let file = m.unscaled(2.0);
        assert!((file.volume.unwrap() - 1.0).abs() < 1e-9);
        assert!((file.area - 6.0).abs() < 1e-9);
        assert_eq!(file.size(), Vec3::ONE);
        let total = Measurements::total(&[m, file]);
        assert!((total.volume.unwrap() - 9.0).abs() < 1e-9);
    }

    #[test]
    fn parts_of_distinct_positions_are_measured_as_one_mesh() {
        // Two unit cubes side by side, apart: each part's positions its own, none shared.
        let cube = cuboid(Vec3::ONE, 2);
        let moved: Vec<Vec3> = cube.positions.iter().map(|&p| p + Vec3::X * 3.0).collect();
        let m = measure(&[
            (&cube.positions, &cube.triangles),
            (&moved, &cube.triangles),
        ]);
        assert!(m.closed(), "{m:?}");
        assert!((m.volume.unwrap() - 2.0).abs() < 1e-9, "{m:?}");
        assert!((m.area - 12.0).abs() < 1e-9);
        assert_eq!(m.size(), Vec3::new(4.0, 1.0, 1.0));
        // The second part alone: its ids start from its own first position.
        let alone = measure(&[(&moved, &cube.triangles)]);
        assert!((alone.volume.unwrap() - 1.0).abs() < 1e-9);
    }

    /// Boundary, non-manifold and misoriented edges of `triangles`, each undirected edge's
    /// uses counted by direction one triangle at a time.
    fn counted_in_a_table(triangles: &[[u32; 3]]) -> (usize, usize, usize) {
        let mut uses = std::collections::HashMap::<(u32, u32), (usize, usize)>::new();
        for &[a, b, c] in triangles {
            for (from, to) in [(a, b), (b, c), (c, a)] {
                if from != to {
                    let entry = uses.entry((from.min(to), from.max(to))).or_default();
                    if from < to {
                        entry.0 += 1
                    } else {
                        entry.1 += 1
                    }
                }
            }
        }
        let boundary = uses.values().filter(|(f, b)| f + b == 1).count();
        let non_manifold = uses.values().filter(|(f, b)| f + b > 2).count();
        let misoriented = uses
            .values()
            .filter(|&&u| u == (2, 0) || u == (0, 2))
            .count();
        (boundary, non_manifold, misoriented)
    }

    /// Checks [`edge_counts`] of `triangles` on each number of `threads` against
    /// [`counted_in_a_table`], on triangles that have boundary, non-manifold and misoriented
    /// edges.
    fn counted_as_in_a_table(triangles: &[[u32; 3]], vertices: usize, threads: &[usize]) {
        let expected = counted_in_a_table(triangles);
        for &threads in threads {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let edges = pool.install(|| edge_counts(triangles, vertices));
            let counted = (edges.boundary, edges.non_manifold, edges.misoriented);
            assert_eq!(counted, expected, "{threads} threads");
        }
        let (boundary, non_manifold, misoriented) = expected;
        assert!(boundary > 0 && non_manifold > 0 && misoriented > 0);
    }

    #[test]
    fn edges_are_counted_alike_whatever_the_number_of_runs() {
        // Random triangles on few vertices: shared, repeated, turned-over and degenerate edges.
        let mut draw = draws(11);
        let mut next = |n: u64| (draw() % n) as u32;
        let triangles: Vec<[u32; 3]> = (0..400).map(|_| [next(97), next(97), next(97)]).collect();
        counted_as_in_a_table(&triangles, 97, &[1, 3, 8, 9]);
    }

    #[test]
    fn vertices_counted_in_several_tasks_count_as_one_table_does() {
        // A strip of triangles over 3.5 tasks' vertices, its second half wound the other way,
        // a few of its triangles repeated and some corners drawn anywhere.
        let vertices = 7 * ROW_VERTICES / 2;
        let mut draw = draws(3);
        let mut triangles: Vec<[u32; 3]> = (0..vertices as u32 - 2)
            .map(|i| match i % 2 == 0 && i < vertices as u32 / 2 {
                true => [i, i + 1, i + 2],
                false => [i, i + 2, i + 1],
            })
            .collect();
        for _ in 0..500 {
            let k = (draw() % triangles.len() as u64) as usize;
            triangles.push(triangles[k]);
            triangles[k][0] = (draw() % vertices as u64) as u32;
        }
        counted_as_in_a_table(&triangles, vertices, &[1, 2, 5]);
    }

    #[test]
    fn short_rows_are_sorted_as_the_library_sorts_them() {
        let mut draw = draws(5);
        for len in 0..=SHORT_ROW + 1 {
            for _ in 0..50 {
                // Few distinct values: repeats, as the two uses of one edge are.
                let mut row: Vec<u32> = (0..len).map(|_| (draw() % 8) as u32).collect();
                let mut sorted = row.clone();
                sorted.sort_unstable();
                insertion_sort(&mut row);
                assert_eq!(row, sorted);
            }
        }
    }

    #[test]
    fn welding_joins_exactly_the_positions_of_equal_bits_and_keeps_the_first() {
        // Positions drawn from a few values, ±0 among them: two parts' one after another.
        let values = [0.0, -0.0, 1.0, 0.5, -2.0];
        let mut draw = draws(7);
        let mut next = move || values[draw() as usize % values.len()];
        let a: Vec<Vec3> = (0..300)
            .map(|_| Vec3::new(next(), next(), next()))
            .collect();
        let b: Vec<Vec3> = (0..200)
            .map(|_| Vec3::new(next(), next(), next()))
            .collect();
        let all: Vec<Vec3> = a.iter().chain(&b).copied().collect();
        let welded = weld(&all);
        let (ids, positions) = (welded.ids.unwrap(), welded.firsts);
        let key = |p: Vec3| p.to_array().map(coordinate_bits);
        for (i, &p) in all.iter().enumerate() {
            let first = all.iter().position(|&q| key(q) == key(p)).unwrap();
            // The same id as the first of its bits, which it carries to the bit (−0 kept).
            assert_eq!(ids[i], ids[first], "{i}");
            let kept = positions[ids[i] as usize];
            assert_eq!(
                kept.to_array().map(f64::to_bits),
                all[first].as_dvec3().to_array().map(f64::to_bits)
            );
            for (j, &q) in all.iter().enumerate() {
                assert_eq!(ids[i] == ids[j], key(p) == key(q), "{i} {j}");
            }
        }
        // −0 and 0 met: at most 4³ ids where the signed bits give 5³.
        assert!(
            positions.len() <= 64 && positions.len() > 20,
            "{}",
            positions.len()
        );
    }
}
