//! The values of a run of PLY vertices, one array an attribute: positions, and the normals,
//! colours and texture coordinates the vertex element gives. Runs read apart (in parallel) and
//! appended in file order equal the run read at once.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::error::PlyProblem;
use super::plan::{NX, RED, SLOTS, U, VertexAttributes, X};
use super::scalar::Scalar;
use crate::mesh::srgb::{srgb_byte_to_linear, srgb_to_linear};
use crate::scene::limits::COORDINATE;

/// The vertices of a run, in file order.
///
/// Invariant: the optional arrays are as long as `positions` (or `None`).
#[derive(Debug, Clone, PartialEq)]
pub struct VertexColumns {
    /// Number (from 1) of the run's first vertex, for messages.
    pub first: u64,
    pub positions: Vec<Vec3>,
    /// Unit normals, while every vertex so far has a finite, non-zero one.
    pub normals: Option<Vec<Vec3>>,
    /// Linear RGB.
    pub colors: Option<Vec<Vec3>>,
    /// (u, v) as written: (0, 0) is the image's bottom-left.
    pub uvs: Option<Vec<Vec2>>,
}

impl VertexColumns {
    /// An empty run whose first vertex is number `first` (from 1), with room for `n`, keeping
    /// what `attributes` says the element gives.
    pub fn new(first: u64, n: usize, attributes: VertexAttributes) -> VertexColumns {
        VertexColumns {
            first,
            positions: Vec::with_capacity(n),
            normals: attributes.normals.then(|| Vec::with_capacity(n)),
            colors: attributes.colors.map(|_| Vec::with_capacity(n)),
            uvs: attributes.uvs.then(|| Vec::with_capacity(n)),
        }
    }

    /// Takes one vertex record (its values by slot); `colors`: the type colours are written in.
    /// Errors name the vertex (from 1).
    #[inline]
    pub fn push(
        &mut self,
        values: &[f64; SLOTS],
        colors: Option<Scalar>,
    ) -> Result<(), PlyProblem> {
        let vertex = self.first + self.positions.len() as u64;
        let mut p = [0f32; 3];
        for (c, out) in p.iter_mut().enumerate() {
            let value = values[X + c];
            let single = value as f32;
            if !COORDINATE.accepts(single) {
                return Err(if value.is_finite() {
                    PlyProblem::OutOfRange {
                        vertex,
                        value: single,
                    }
                } else {
                    PlyProblem::NonFinite { vertex }
                });
            }
            *out = single;
        }
        self.positions.push(Vec3::from_array(p));
        if let Some(normals) = &mut self.normals {
            let n = Vec3::new(
                values[NX] as f32,
                values[NX + 1] as f32,
                values[NX + 2] as f32,
            )
            .normalize_or_zero();
            if n.is_finite() && n != Vec3::ZERO {
                normals.push(n);
            } else {
                self.normals = None;
            }
        }
        if let (Some(out), Some(ty)) = (&mut self.colors, colors) {
            let channel = |v: f64| match ty {
                Scalar::U8 => srgb_byte_to_linear(v as u8),
                _ => srgb_to_linear((v / ty.full_scale()) as f32),
            };
            out.push(Vec3::new(
                channel(values[RED]),
                channel(values[RED + 1]),
                channel(values[RED + 2]),
            ));
        }
        if let Some(uvs) = &mut self.uvs {
            let uv = Vec2::new(values[U] as f32, values[U + 1] as f32);
            if !uv.is_finite() {
                return Err(PlyProblem::NonFiniteUv { vertex });
            }
            uvs.push(uv);
        }
        Ok(())
    }

    /// Appends `runs`, the runs that follow this one in the file, one after another; every run
    /// but the last holds `RUN` vertices (a power of two). An attribute any run has lost is lost
    /// for all. The values are copied on every core, each straight to its place.
    pub fn append_runs<const RUN: usize>(&mut self, runs: &[VertexColumns]) {
        debug_assert!(RUN.is_power_of_two());
        debug_assert!(
            runs.iter().enumerate().all(|(k, r)| {
                let before = self.positions.len() + k * RUN;
                r.first == self.first + before as u64
                    && (r.positions.len() == RUN || k + 1 == runs.len())
            }),
            "runs follow one another, all but the last whole"
        );
        let positions: Vec<&[Vec3]> = runs.iter().map(|r| &r.positions[..]).collect();
        append_parts::<Vec3, RUN>(&mut self.positions, &positions);
        join::<_, RUN>(&mut self.normals, runs, |r| r.normals.as_deref());
        join::<_, RUN>(&mut self.colors, runs, |r| r.colors.as_deref());
        join::<_, RUN>(&mut self.uvs, runs, |r| r.uvs.as_deref());
    }
}

/// `ours` followed by each run's array (`theirs`), or `None` when it or any of them is.
fn join<T: Copy + Send + Sync, const RUN: usize>(
    ours: &mut Option<Vec<T>>,
    runs: &[VertexColumns],
    theirs: impl Fn(&VertexColumns) -> Option<&[T]>,
) {
    let parts: Option<Vec<&[T]>> = runs.iter().map(theirs).collect();
    match (ours.as_mut(), parts) {
        (Some(ours), Some(parts)) => append_parts::<T, RUN>(ours, &parts),
        _ => *ours = None,
    }
}

/// Appends `parts` to `ours` in order, each but the last `RUN` long (a power of two), on every
/// core: item `i` of the appended values is item `i % RUN` of part `i / RUN`, an indexed
/// iterator that rayon writes straight into `ours`'s new room: the copy and the first touch of
/// its pages are shared out, where appending part by part kept one core busy while the others
/// waited for the next block.
fn append_parts<T: Copy + Send + Sync, const RUN: usize>(ours: &mut Vec<T>, parts: &[&[T]]) {
    let total: usize = parts.iter().map(|p| p.len()).sum();
    let shift = RUN.trailing_zeros();
    ours.par_extend(
        (0..total)
            .into_par_iter()
            .with_min_len(RUN.max(1 << 12))
            .map(|i| parts[i >> shift][i & (RUN - 1)]),
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: VertexAttributes = VertexAttributes {
        normals: true,
        colors: Some(Scalar::U8),
        uvs: true,
    };

    /// Vertex `i`'s values: distinct in every slot; a zero normal (not usable) at `bad_normal`.
    fn values(i: usize, bad_normal: Option<usize>) -> [f64; SLOTS] {
        let f = i as f64;
        let n = if bad_normal == Some(i) { 0.0 } else { 1.0 };
        [
            f,
            f + 0.5,
            -f,
            n,
            0.0,
            0.0,
            (i % 256) as f64,
            3.0,
            7.0,
            f * 0.25,
            1.0 - f,
        ]
    }

    /// Vertices `0..n` pushed into runs of `RUN` after `before` vertices pushed into the start,
    /// and appended, against all of them pushed into one.
    fn appended_and_pushed<const RUN: usize>(
        before: usize,
        n: usize,
        bad_normal: Option<usize>,
    ) -> (VertexColumns, VertexColumns) {
        let mut whole = VertexColumns::new(1, 0, ALL);
        for i in 0..before + n {
            whole.push(&values(i, bad_normal), ALL.colors).unwrap();
        }
        let mut start = VertexColumns::new(1, 0, ALL);
        for i in 0..before {
            start.push(&values(i, bad_normal), ALL.colors).unwrap();
        }
        let runs: Vec<VertexColumns> = (before..before + n)
            .step_by(RUN)
            .map(|from| {
                let mut run = VertexColumns::new(1 + from as u64, RUN, ALL);
                for i in from..(from + RUN).min(before + n) {
                    run.push(&values(i, bad_normal), ALL.colors).unwrap();
                }
                run
            })
            .collect();
        start.append_runs::<RUN>(&runs);
        (start, whole)
    }

    #[test]
    fn runs_appended_on_every_core_equal_the_vertices_pushed_in_one() {
        for (before, n) in [(0, 1), (0, 64), (5, 63), (3, 65), (1, 20_000), (0, 0)] {
            let (appended, pushed) = appended_and_pushed::<64>(before, n, None);
            assert_eq!(appended, pushed, "{before} + {n}");
            assert!(appended.normals.is_some() && appended.uvs.is_some());
        }
        // A normal that is not usable, in the start or in any run, loses the normals for all.
        for bad in [2, 10, 64 + 10, 130] {
            let (appended, pushed) = appended_and_pushed::<64>(5, 200, Some(bad));
            assert_eq!(appended, pushed, "bad normal at {bad}");
            assert_eq!(appended.normals, None);
            assert_eq!(appended.positions.len(), 205);
        }
    }
}
