//! The vertices and faces of a PLY body as they are read, and the geometry they make: faces
//! fanned into triangles, vertices no face uses dropped, vertices with bit-identical positions
//! (and colours) welded, per-vertex normals and texture coordinates moved to the corners.

use glam::{Vec2, Vec3};

use super::error::PlyProblem;
use super::plan::{FaceLists, NX, RED, SLOTS, U, VertexAttributes, X};
use super::scalar::Scalar;
use crate::mesh::ModelGeometry;
use crate::mesh::srgb::{srgb_byte_to_linear, srgb_to_linear};
use crate::mesh::weld::{BATCH, Welder, coordinate_bits, positions_of};
use crate::scene::limits::COORDINATE;

/// What has been read so far.
///
/// Invariant: every triangle's indices are below `vertices` (the declared count); the
/// optional attribute arrays are as long as `positions`.
#[derive(Debug)]
pub struct Collector {
    /// The vertex count the header declares.
    vertices: u64,
    attributes: VertexAttributes,
    positions: Vec<Vec3>,
    /// Unit normals, while every vertex so far has a finite, non-zero one.
    normals: Option<Vec<Vec3>>,
    /// Linear RGB.
    colors: Option<Vec<Vec3>>,
    /// (u, v) as written: (0, 0) is the image's bottom-left.
    uvs: Option<Vec<Vec2>>,
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
            positions: Vec::with_capacity(n),
            normals: attributes.normals.then(|| Vec::with_capacity(n)),
            colors: attributes.colors.map(|_| Vec::with_capacity(n)),
            uvs: attributes.uvs.then(|| Vec::with_capacity(n)),
            triangles: Vec::with_capacity(faces.min(limit) as usize),
            face_uvs: face_uvs.then(Vec::new),
            faces: 0,
            limit,
        }
    }

    /// Takes one vertex record; errors name the vertex (from 1).
    #[inline]
    pub fn vertex(&mut self, values: &[f64; SLOTS]) -> Result<(), PlyProblem> {
        let vertex = self.positions.len() as u64 + 1;
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
        if let (Some(colors), Some(ty)) = (&mut self.colors, self.attributes.colors) {
            let channel = |v: f64| match ty {
                Scalar::U8 => srgb_byte_to_linear(v as u8),
                _ => srgb_to_linear((v / ty.full_scale()) as f32),
            };
            colors.push(Vec3::new(
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

    /// The geometry read. Called once every record is read.
    pub fn finish(self) -> Result<ModelGeometry, PlyProblem> {
        if self.triangles.is_empty() {
            return Err(PlyProblem::NoTriangles);
        }
        let corner = |values: &[Vec2], t: &[u32; 3]| t.map(|i| values[i as usize]);
        let flip = |uv: Vec2| Vec2::new(uv.x, 1.0 - uv.y);
        let corner_uvs = match (&self.face_uvs, &self.uvs) {
            (Some(face_uvs), _) => Some(face_uvs.iter().map(|t| t.map(flip)).collect()),
            (None, Some(uvs)) => Some(
                self.triangles
                    .iter()
                    .map(|t| corner(uvs, t).map(flip))
                    .collect(),
            ),
            (None, None) => None,
        };
        let corner_normals = self.normals.as_ref().map(|normals| {
            self.triangles
                .iter()
                .map(|t| t.map(|i| normals[i as usize]))
                .collect()
        });
        let (positions, colors, triangles) = match &self.colors {
            Some(colors) => {
                let key = |i: usize| {
                    let [x, y, z] = self.positions[i].to_array().map(coordinate_bits);
                    let [r, g, b] = colors[i].to_array().map(f32::to_bits);
                    [x, y, z, r, g, b]
                };
                let (keys, triangles) = weld(self.positions.len(), self.triangles, key);
                let positions = keys.iter().map(|k| from_bits(&k[..3])).collect();
                let colors = keys.iter().map(|k| from_bits(&k[3..])).collect();
                (positions, Some(colors), triangles)
            }
            None => {
                let key = |i: usize| self.positions[i].to_array().map(coordinate_bits);
                let (keys, triangles) = weld(self.positions.len(), self.triangles, key);
                let positions = positions_of(keys);
                (positions, None, triangles)
            }
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

/// The vector whose three coordinates have the bits `bits[..3]`.
fn from_bits(bits: &[u32]) -> Vec3 {
    Vec3::new(
        f32::from_bits(bits[0]),
        f32::from_bits(bits[1]),
        f32::from_bits(bits[2]),
    )
}

/// The distinct keys of the vertices `triangles` use (`key` of each vertex index, out of
/// `vertices`), in order of first use, and the triangles re-indexed onto them.
fn weld<const N: usize>(
    vertices: usize,
    mut triangles: Vec<[u32; 3]>,
    key: impl Fn(usize) -> [u32; N],
) -> (Vec<[u32; N]>, Vec<[u32; 3]>) {
    const UNSEEN: u32 = u32::MAX;
    let mut welder = Welder::with_capacity(vertices);
    let mut remap = vec![UNSEEN; vertices];
    // The vertices in order of first use, welded in batches (see `Welder::index_all`).
    let mut used = Vec::with_capacity(vertices);
    for &i in triangles.iter().flatten() {
        let slot = &mut remap[i as usize];
        if *slot == UNSEEN {
            *slot = 0;
            used.push(i);
        }
    }
    let mut keys = [[0u32; N]; BATCH];
    let mut indices = [0u32; BATCH];
    for batch in used.chunks(BATCH) {
        for (k, &i) in keys.iter_mut().zip(batch) {
            *k = key(i as usize);
        }
        welder.index_all(&keys[..batch.len()], &mut indices);
        for (&i, &index) in batch.iter().zip(&indices) {
            remap[i as usize] = index;
        }
    }
    for i in triangles.iter_mut().flatten() {
        *i = remap[*i as usize];
    }
    (welder.into_keys(), triangles)
}
