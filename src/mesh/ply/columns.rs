//! The values of a run of PLY vertices, one array an attribute: positions, and the normals,
//! colours and texture coordinates the vertex element gives. A block of vertices is written in
//! place, on every core, through rooms split from the arrays' new room, and equals the same
//! vertices pushed one by one.

use glam::{Vec2, Vec3};

use super::error::PlyProblem;
use super::plan::{NX, RED, SLOTS, U, VertexAttributes, X};
use super::scalar::Scalar;
use crate::huge_pages::{extend_filled, with_capacity};
use crate::mesh::srgb::{srgb_byte_table, srgb_to_linear};
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
            positions: with_capacity(n),
            normals: attributes.normals.then(|| with_capacity(n)),
            colors: attributes.colors.map(|_| with_capacity(n)),
            uvs: attributes.uvs.then(|| with_capacity(n)),
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
        self.positions.push(position(values, vertex)?);
        if let Some(normals) = &mut self.normals {
            match normal(values) {
                Some(n) => normals.push(n),
                None => self.normals = None,
            }
        }
        if let (Some(out), Some(ty)) = (&mut self.colors, colors) {
            out.push(color(values, ty));
        }
        if let Some(uvs) = &mut self.uvs {
            uvs.push(uv(values, vertex)?);
        }
        Ok(())
    }

    /// Takes the next `n` vertices, written in place by `fill` (on every core, through
    /// [`VertexRoom::split`]), which says whether every one of them has a usable normal. The
    /// room is made on every core too, backed by huge pages where the arrays are large (made
    /// by [`VertexColumns::new`] with room for them). An error leaves no vertex taken.
    pub fn fill_in_place<E>(
        &mut self,
        n: usize,
        fill: impl FnOnce(VertexRoom<'_>) -> Result<bool, E>,
    ) -> Result<(), E> {
        let start = self.positions.len();
        let room = VertexRoom {
            first: self.first + start as u64,
            positions: extend_filled(&mut self.positions, n, Vec3::ZERO),
            normals: self
                .normals
                .as_mut()
                .map(|v| extend_filled(v, n, Vec3::ZERO)),
            colors: self
                .colors
                .as_mut()
                .map(|v| extend_filled(v, n, Vec3::ZERO)),
            uvs: self.uvs.as_mut().map(|v| extend_filled(v, n, Vec2::ZERO)),
        };
        match fill(room) {
            Ok(normals_kept) => {
                if !normals_kept {
                    self.normals = None;
                }
                Ok(())
            }
            Err(e) => {
                self.truncate(start);
                Err(e)
            }
        }
    }

    /// Keeps the first `n` vertices.
    fn truncate(&mut self, n: usize) {
        self.positions.truncate(n);
        for values in [&mut self.normals, &mut self.colors].into_iter().flatten() {
            values.truncate(n);
        }
        if let Some(uvs) = &mut self.uvs {
            uvs.truncate(n);
        }
    }
}

/// Room for a run of vertices in the collected arrays, written in place.
///
/// Invariant: the optional slices are as long as `positions` (or `None`).
pub struct VertexRoom<'a> {
    /// Number (from 1) of the room's first vertex, for messages.
    first: u64,
    positions: &'a mut [Vec3],
    normals: Option<&'a mut [Vec3]>,
    colors: Option<&'a mut [Vec3]>,
    uvs: Option<&'a mut [Vec2]>,
}

impl<'a> VertexRoom<'a> {
    /// The room cut into rooms of `len` vertices (the last may be shorter), in order.
    pub fn split(self, len: usize) -> Vec<VertexRoom<'a>> {
        let mut rooms = Vec::new();
        let mut rest = self;
        while rest.positions.len() > len {
            let (head, tail) = rest.split_at(len);
            rooms.push(head);
            rest = tail;
        }
        rooms.push(rest);
        rooms
    }

    fn split_at(self, mid: usize) -> (VertexRoom<'a>, VertexRoom<'a>) {
        fn cut<T>(values: Option<&mut [T]>, mid: usize) -> (Option<&mut [T]>, Option<&mut [T]>) {
            values.map(|v| v.split_at_mut(mid)).unzip()
        }
        let (positions, later_positions) = self.positions.split_at_mut(mid);
        let (normals, later_normals) = cut(self.normals, mid);
        let (colors, later_colors) = cut(self.colors, mid);
        let (uvs, later_uvs) = cut(self.uvs, mid);
        (
            VertexRoom {
                first: self.first,
                positions,
                normals,
                colors,
                uvs,
            },
            VertexRoom {
                first: self.first + mid as u64,
                positions: later_positions,
                normals: later_normals,
                colors: later_colors,
                uvs: later_uvs,
            },
        )
    }

    /// Writes vertex `i` of the room from a position and 8-bit sRGB colours read straight from
    /// a record, as [`VertexRoom::set`] would from the same values; the room keeps no normals
    /// or texture coordinates (the element gives none).
    #[inline]
    pub fn set_plain(
        &mut self,
        i: usize,
        position: [f32; 3],
        rgb: Option<[u8; 3]>,
    ) -> Result<(), PlyProblem> {
        debug_assert!(self.normals.is_none() && self.uvs.is_none());
        let vertex = self.first + i as u64;
        for value in position {
            coordinate(value.into(), vertex)?;
        }
        self.positions[i] = Vec3::from_array(position);
        if let (Some(out), Some(rgb)) = (&mut self.colors, rgb) {
            out[i] = byte_color(rgb);
        }
        Ok(())
    }

    /// Writes vertex `i` of the room from its record's values, as [`VertexColumns::push`]
    /// takes them; whether its normal is usable (always, when the element gives none).
    #[inline]
    pub fn set(
        &mut self,
        i: usize,
        values: &[f64; SLOTS],
        colors: Option<Scalar>,
    ) -> Result<bool, PlyProblem> {
        let vertex = self.first + i as u64;
        self.positions[i] = position(values, vertex)?;
        let mut usable = true;
        if let Some(normals) = &mut self.normals {
            match normal(values) {
                Some(n) => normals[i] = n,
                None => usable = false,
            }
        }
        if let (Some(out), Some(ty)) = (&mut self.colors, colors) {
            out[i] = color(values, ty);
        }
        if let Some(uvs) = &mut self.uvs {
            uvs[i] = uv(values, vertex)?;
        }
        Ok(usable)
    }
}

/// Vertex `vertex`'s position (its number from 1, for the message), checked against the
/// scene's coordinate limits.
#[inline]
fn position(values: &[f64; SLOTS], vertex: u64) -> Result<Vec3, PlyProblem> {
    let mut p = [0f32; 3];
    for (c, out) in p.iter_mut().enumerate() {
        *out = coordinate(values[X + c], vertex)?;
    }
    Ok(Vec3::from_array(p))
}

/// A coordinate of vertex `vertex` as a single, checked against the scene's limits.
#[inline]
fn coordinate(value: f64, vertex: u64) -> Result<f32, PlyProblem> {
    let single = value as f32;
    if COORDINATE.accepts(single) {
        Ok(single)
    } else if value.is_finite() {
        Err(PlyProblem::OutOfRange {
            vertex,
            value: single,
        })
    } else {
        Err(PlyProblem::NonFinite { vertex })
    }
}

/// The unit normal, when the values give a finite, non-zero one.
#[inline]
fn normal(values: &[f64; SLOTS]) -> Option<Vec3> {
    let n = Vec3::new(
        values[NX] as f32,
        values[NX + 1] as f32,
        values[NX + 2] as f32,
    )
    .normalize_or_zero();
    (n.is_finite() && n != Vec3::ZERO).then_some(n)
}

/// The linear colour of values written as `ty`.
#[inline]
fn color(values: &[f64; SLOTS], ty: Scalar) -> Vec3 {
    let [r, g, b] = [values[RED], values[RED + 1], values[RED + 2]];
    match ty {
        Scalar::U8 => byte_color([r as u8, g as u8, b as u8]),
        _ => Vec3::from_array([r, g, b].map(|v| srgb_to_linear((v / ty.full_scale()) as f32))),
    }
}

/// The linear colour of 8-bit sRGB codes.
#[inline]
fn byte_color(rgb: [u8; 3]) -> Vec3 {
    let table = srgb_byte_table();
    Vec3::from_array(rgb.map(|code| table[code as usize]))
}

/// The texture coordinates, which must be finite.
#[inline]
fn uv(values: &[f64; SLOTS], vertex: u64) -> Result<Vec2, PlyProblem> {
    let uv = Vec2::new(values[U] as f32, values[U + 1] as f32);
    if uv.is_finite() {
        Ok(uv)
    } else {
        Err(PlyProblem::NonFiniteUv { vertex })
    }
}

#[cfg(test)]
mod tests {
    use rayon::prelude::*;

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

    /// Vertices `0..n` written in place in rooms of `len` (on every core) after `before`
    /// vertices pushed into the start, against all of them pushed one by one.
    fn filled_and_pushed(
        before: usize,
        n: usize,
        len: usize,
        bad_normal: Option<usize>,
    ) -> (VertexColumns, VertexColumns) {
        let mut whole = VertexColumns::new(1, 0, ALL);
        for i in 0..before + n {
            whole.push(&values(i, bad_normal), ALL.colors).unwrap();
        }
        let mut filled = VertexColumns::new(1, before + n, ALL);
        for i in 0..before {
            filled.push(&values(i, bad_normal), ALL.colors).unwrap();
        }
        filled
            .fill_in_place(n, |room| {
                let kept: Result<Vec<bool>, PlyProblem> = room
                    .split(len)
                    .into_par_iter()
                    .enumerate()
                    .map(|(k, mut room)| {
                        let mut kept = true;
                        for i in 0..len.min(n - k * len) {
                            let v = values(before + k * len + i, bad_normal);
                            kept &= room.set(i, &v, ALL.colors)?;
                        }
                        Ok(kept)
                    })
                    .collect();
                kept.map(|k| k.iter().all(|&kept| kept))
            })
            .unwrap();
        (filled, whole)
    }

    #[test]
    fn rooms_filled_on_every_core_equal_the_vertices_pushed_one_by_one() {
        for (before, n) in [(0, 1), (0, 64), (5, 63), (3, 65), (1, 20_000), (0, 0)] {
            let (filled, pushed) = filled_and_pushed(before, n, 64, None);
            assert_eq!(filled, pushed, "{before} + {n}");
            assert!(filled.normals.is_some() && filled.uvs.is_some());
        }
        // A normal that is not usable, in the start or in any room, loses the normals for all.
        for bad in [2, 10, 64 + 10, 130] {
            let (filled, pushed) = filled_and_pushed(5, 200, 64, Some(bad));
            assert_eq!(filled, pushed, "bad normal at {bad}");
            assert_eq!(filled.normals, None);
            assert_eq!(filled.positions.len(), 205);
        }
    }

    #[test]
    fn a_vertex_refused_in_a_room_names_itself_and_leaves_no_vertex_taken() {
        let mut columns = VertexColumns::new(1, 0, ALL);
        columns.push(&values(0, None), ALL.colors).unwrap();
        let before = columns.clone();
        let refused = columns.fill_in_place(100, |room| {
            let mut rooms = room.split(30);
            assert_eq!(rooms.len(), 4);
            let mut bad = values(70, None);
            bad[X + 1] = f64::NAN;
            rooms[2].set(10, &bad, ALL.colors)
        });
        // Vertex 72 from 1: one pushed, then room 2 begins at the room's vertex 60.
        assert!(
            matches!(refused, Err(PlyProblem::NonFinite { vertex: 72 })),
            "{refused:?}"
        );
        assert_eq!(columns, before);
    }
}
