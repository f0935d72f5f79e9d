//! The values of a run of PLY vertices, one array an attribute: positions, and the normals,
//! colours and texture coordinates the vertex element gives. Runs read apart (in parallel) and
//! appended in file order equal the run read at once.

use glam::{Vec2, Vec3};

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

    /// Appends `next`, the run that follows this one in the file. An attribute either run has
    /// lost (a normal that is not usable) is lost for all.
    pub fn append(&mut self, next: VertexColumns) {
        debug_assert_eq!(next.first, self.first + self.positions.len() as u64);
        self.positions.extend_from_slice(&next.positions);
        join(&mut self.normals, next.normals);
        join(&mut self.colors, next.colors);
        join(&mut self.uvs, next.uvs);
    }
}

/// `ours` followed by `theirs`, or `None` when either is.
fn join<T: Copy>(ours: &mut Option<Vec<T>>, theirs: Option<Vec<T>>) {
    match (ours.as_mut(), theirs) {
        (Some(ours), Some(theirs)) => ours.extend_from_slice(&theirs),
        _ => *ours = None,
    }
}
