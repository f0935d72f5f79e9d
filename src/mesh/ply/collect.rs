//! The vertices and faces of a PLY body as they are read, and the geometry they make: faces
//! fanned into triangles, vertices no face uses dropped, vertices with bit-identical positions
//! (and colours) welded (kept in file order), per-vertex normals and texture coordinates moved
//! to the corners.

use glam::{Vec2, Vec3};

use super::error::PlyProblem;
use rayon::prelude::*;

use super::columns::{VertexColumns, VertexRoom};
use super::plan::{FaceLists, SLOTS, VertexAttributes};

use crate::huge_pages;
use crate::mesh::ModelGeometry;
use crate::mesh::used_vertices::used_bits;
use crate::mesh::weld::{Repeats, kept_of, weld_indices};

/// What has been read so far.
///
/// Invariant: every triangle's indices are below `vertices` (the declared count); the
/// optional attribute arrays are as long as `positions`.
#[derive(Debug)]
pub struct Collector {
    /// The vertex count the header declares.
    vertices: u64,
    attributes: VertexAttributes,
    columns: VertexColumns,
    triangles: Vec<[u32; 3]>,
    /// (u, v) of each triangle's corners from the faces' `texcoord` lists, while every face
    /// so far has one of the right length.
    face_uvs: Option<Vec<[Vec2; 3]>>,
    /// Faces read, for messages.
    faces: u64,
    limit: u64,
}

impl Collector {
    /// A collector for `vertices` vertices (the header's count, already bounded by the file's
    /// size) with `attributes`, keeping at most `limit` triangles; `faces` is the declared face
    /// count (room is made for that many triangles, up to the limit); `face_uvs`: whether the
    /// faces carry texture coordinates.
    pub fn new(
        vertices: u64,
        faces: u64,
        attributes: VertexAttributes,
        face_uvs: bool,
        limit: u64,
    ) -> Collector {
        let n = vertices as usize;
        Collector {
            vertices,
            attributes,
            columns: VertexColumns::new(1, n, attributes),
            triangles: huge_pages::with_capacity(faces.min(limit) as usize),
            face_uvs: face_uvs.then(Vec::new),
            faces: 0,
            limit,
        }
    }

    /// Takes one vertex record; errors name the vertex (from 1).
    #[inline]
    pub fn vertex(&mut self, values: &[f64; SLOTS]) -> Result<(), PlyProblem> {
        self.columns.push(values, self.attributes.colors)
    }

    /// What the vertex element gives.
    pub fn attributes(&self) -> VertexAttributes {
        self.attributes
    }

    /// Takes the next `n` vertices, written in place by `fill` (see
    /// [`VertexColumns::fill_in_place`]); an error leaves no vertex taken.
    pub fn fixed_vertices<E>(
        &mut self,
        n: usize,
        fill: impl FnOnce(VertexRoom<'_>) -> Result<bool, E>,
    ) -> Result<(), E> {
        self.columns.fill_in_place(n, fill)
    }

    /// Takes one face's vertex indices, fanned into triangles (a face of fewer than three
    /// corners is a point or a line: not drawn). `echo`: whether the message of an index out of
    /// range may quote it (text files) or not (binary data).
    #[inline]
    pub fn face(&mut self, lists: &FaceLists, echo: bool) -> Result<(), PlyProblem> {
        let corners = &lists.indices[..];
        self.faces += 1;
        let face = self.faces;
        let vertices = self.vertices;
        let index = |value: f64| -> Result<u32, PlyProblem> {
            if value >= 0.0 && value < vertices as f64 && value.fract() == 0.0 {
                Ok(value as u32)
            } else {
                Err(PlyProblem::IndexOutOfRange {
                    face,
                    written: echo.then_some(value as i64),
                    vertices,
                })
            }
        };
        if corners.len() < 3 {
            return corners.iter().try_for_each(|&c| index(c).map(drop));
        }
        if self.triangles.len() as u64 + corners.len() as u64 - 2 > self.limit {
            return Err(PlyProblem::TooManyTriangles { limit: self.limit });
        }
        let first = index(corners[0])?;
        let mut previous = index(corners[1])?;
        for &c in &corners[2..] {
            let next = index(c)?;
            self.triangles.push([first, previous, next]);
            previous = next;
        }
        if let Some(face_uvs) = &mut self.face_uvs {
            let uvs: Vec<Vec2> = lists
                .uvs
                .chunks_exact(2)
                .map(|uv| Vec2::new(uv[0] as f32, uv[1] as f32))
                .collect();
            if uvs.len() == corners.len() && uvs.iter().all(|uv| uv.is_finite()) {
                face_uvs.extend(uvs[1..].windows(2).map(|w| [uvs[0], w[0], w[1]]));
            } else {
                self.face_uvs = None;
            }
        }
        Ok(())
    }

    /// How many more faces of one triangle each may be taken before the triangle limit.
    pub fn triangle_room(&self) -> u64 {
        self.limit.saturating_sub(self.triangles.len() as u64)
    }

    /// Takes up to `n` faces of one triangle each (at most [`Collector::triangle_room`]):
    /// `fill` writes their triangles, already checked against [`FaceRun::vertices`], and says
    /// how many of them it wrote (a prefix); an error leaves no face taken.
    pub fn fixed_faces<E>(
        &mut self,
        n: usize,
        fill: impl FnOnce(&mut [[u32; 3]], FaceRun) -> Result<usize, E>,
    ) -> Result<usize, E> {
        debug_assert!(n as u64 <= self.triangle_room() && self.face_uvs.is_none());
        let start = self.triangles.len();
        let run = FaceRun {
            first: self.faces + 1,
            vertices: self.vertices,
        };
        let kept = fill(
            huge_pages::extend_filled(&mut self.triangles, n, [0; 3]),
            run,
        );
        self.triangles
            .truncate(start + *kept.as_ref().unwrap_or(&0));
        if let Ok(kept) = kept {
            self.faces += kept as u64;
        }
        kept
    }

    /// The geometry read. Called once every record is read.
    pub fn finish(self) -> Result<ModelGeometry, PlyProblem> {
        if self.triangles.is_empty() {
            return Err(PlyProblem::NoTriangles);
        }
        let corner = |values: &[Vec2], t: &[u32; 3]| t.map(|i| values[i as usize]);
        let flip = |uv: Vec2| Vec2::new(uv.x, 1.0 - uv.y);
        let corner_uvs = match (&self.face_uvs, &self.columns.uvs) {
            (Some(face_uvs), _) => Some(face_uvs.par_iter().map(|t| t.map(flip)).collect()),
            (None, Some(uvs)) => Some(
                self.triangles
                    .par_iter()
                    .map(|t| corner(uvs, t).map(flip))
                    .collect(),
            ),
            (None, None) => None,
        };
        let corner_normals = self.columns.normals.as_ref().map(|normals| {
            self.triangles
                .par_iter()
                .map(|t| t.map(|i| normals[i as usize]))
                .collect()
        });
        let mut positions = self.columns.positions;
        // −0 becomes 0, as `coordinate_bits` sees it.
        positions.par_iter_mut().for_each(|p| *p += Vec3::ZERO);
        let used = used_bits(&self.triangles, positions.len());
        let used = |i: usize| used[i / 64] >> (i % 64) & 1 == 1;
        let (colors, (kept, triangles)) = match self.columns.colors {
            Some(colors) => {
                let key = |i: usize| {
                    let [x, y, z] = positions[i].to_array().map(f32::to_bits);
                    let [r, g, b] = colors[i].to_array().map(f32::to_bits);
                    [x, y, z, r, g, b]
                };
                let welded =
                    weld_indices(positions.len(), key, self.triangles, Repeats::Rare, used);
                (Some(colors), welded)
            }
            None => {
                let key = |i: usize| positions[i].to_array().map(f32::to_bits);
                let welded =
                    weld_indices(positions.len(), key, self.triangles, Repeats::Rare, used);
                (None, welded)
            }
        };
        let (positions, colors) = match kept {
            None => (positions, colors),
            Some(kept) => (
                kept_of(&positions, &kept),
                colors.map(|colors| kept_of(&colors, &kept)),
            ),
        };
        Ok(ModelGeometry {
            positions,
            triangles,
            corner_normals,
            colors,
            corner_uvs,
        })
    }
}

/// Where a run of faces given to [`Collector::fixed_faces`] stands.
#[derive(Debug, Clone, Copy)]
pub struct FaceRun {
    /// Number (from 1) of the run's first face, for messages.
    pub first: u64,
    /// Vertices the file declares: every index must be below.
    pub vertices: u64,
}
