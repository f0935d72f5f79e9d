//! Fast paths for the binary layouts nearly every PLY uses: a vertex element of scalars only
//! (records of one size), and a face element whose records are scalars and one index list of
//! 32-bit integers that holds three. Blocks of whole records are read at once and decoded in
//! parallel. Each path reads a prefix of its element and says how long: the general reader
//! ([`super::binary::read_element`]) reads the rest, so that a file the fast path does not fit
//! (a quad, a record cut short, the triangle limit reached) gets the same result and the same
//! messages as before.

use rayon::prelude::*;

use super::collect::{Collector, FaceRun};
use super::columns::VertexRoom;
use super::error::PlyProblem;
use super::header::PropertyType;
use super::plan::{Plan, RED, SLOTS, Target, X};
use super::scalar::Scalar;
use crate::mesh::Place;
use crate::mesh::byte_source::ModelSource;

/// Bytes of records read ahead and decoded together (about 16 ms of a core's work).
const BLOCK_BYTES: usize = 4 << 20;

/// Records one parallel task decodes.
const TASK_RECORDS: usize = 1 << 14;

/// A vertex record of scalars only: its size and where the values rastray reads lie.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct VertexLayout {
    /// Bytes a record takes.
    stride: usize,
    /// Offset in the record, type and slot of each value read.
    fields: Vec<(usize, Scalar, usize)>,
}

impl VertexLayout {
    /// The layout of records read by `plan`, when every property is a scalar.
    pub fn of(plan: &Plan) -> Option<VertexLayout> {
        let mut stride = 0;
        let mut fields = Vec::new();
        for &(ty, target) in &plan.properties {
            let PropertyType::Scalar(s) = ty else {
                return None;
            };
            if let Target::Slot(k) = target {
                fields.push((stride, s, k));
            }
            stride += s.size();
        }
        Some(VertexLayout { stride, fields })
    }
}

/// The layout nearly every scanner writes: `float` x, y, z and, when there are colours, `uchar`
/// red, green, blue (at any offsets, beside properties rastray skips), and nothing else read.
/// Decoded straight from the bytes, where the general layout goes through one `f64` a value: a
/// third of the time of a big PLY's vertices (`examples/model_load`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct PlainLayout {
    /// Offsets of x, y and z in the record.
    xyz: [usize; 3],
    /// Offsets of red, green and blue, when the element has colours.
    rgb: Option<[usize; 3]>,
}

impl PlainLayout {
    /// The plain layout of `layout`, when it is one; `colors`: the type colours are written in.
    fn of(layout: &VertexLayout, colors: Option<Scalar>) -> Option<PlainLayout> {
        let at = |slot: usize, ty: Scalar| {
            let mut found = layout.fields.iter().filter(|f| f.2 == slot);
            match (found.next(), found.next()) {
                (Some(&(offset, t, _)), None) if t == ty => Some(offset),
                _ => None,
            }
        };
        let xyz = [
            at(X, Scalar::F32)?,
            at(X + 1, Scalar::F32)?,
            at(X + 2, Scalar::F32)?,
        ];
        let rgb = match colors {
            None => None,
            Some(Scalar::U8) => Some([
                at(RED, Scalar::U8)?,
                at(RED + 1, Scalar::U8)?,
                at(RED + 2, Scalar::U8)?,
            ]),
            Some(_) => return None,
        };
        let read = 3 + rgb.map_or(0, |_| 3);
        (layout.fields.len() == read).then_some(PlainLayout { xyz, rgb })
    }

    /// Writes the record's vertex to place `r` of `room`.
    #[inline]
    fn set<const BIG: bool>(
        &self,
        room: &mut VertexRoom<'_>,
        r: usize,
        record: &[u8],
    ) -> Result<(), PlyProblem> {
        let float = |at: usize| {
            let bytes = [record[at], record[at + 1], record[at + 2], record[at + 3]];
            if BIG {
                f32::from_be_bytes(bytes)
            } else {
                f32::from_le_bytes(bytes)
            }
        };
        let position = self.xyz.map(float);
        let rgb = self.rgb.map(|rgb| rgb.map(|at| record[at]));
        room.set_plain(r, position, rgb)
    }
}

/// A face record of scalars and one list of three 32-bit vertex indices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaceLayout {
    /// Bytes before the list's length.
    before: usize,
    /// The list's length type.
    count: Scalar,
    /// `I32` or `U32`.
    item: Scalar,
    /// Bytes a record of three indices takes.
    stride: usize,
}

impl FaceLayout {
    /// The layout of records read by `plan`, when it is one: a single list, of vertex indices
    /// of 32-bit integers, beside scalars only.
    pub fn of(plan: &Plan) -> Option<FaceLayout> {
        let mut before = None;
        let mut stride = 0;
        let mut list = None;
        for &(ty, target) in &plan.properties {
            match (ty, target) {
                (PropertyType::Scalar(s), _) => stride += s.size(),
                (PropertyType::List { count, item }, Target::Indices)
                    if list.is_none() && matches!(item, Scalar::I32 | Scalar::U32) =>
                {
                    before = Some(stride);
                    list = Some((count, item));
                    stride += count.size() + 3 * item.size();
                }
                (PropertyType::List { .. }, _) => return None,
            }
        }
        let (count, item) = list?;
        Some(FaceLayout {
            before: before?,
            count,
            item,
            stride,
        })
    }
}

/// Reads vertex records `0..count` of the element that begins at the source's position while
/// they are whole; how many are read. Errors as the general reader's: the vertex's number and its record's offset.
pub fn read_vertices<const BIG: bool>(
    source: &mut ModelSource,
    count: u64,
    layout: &VertexLayout,
    collector: &mut Collector,
) -> Result<u64, (Place, PlyProblem)> {
    let stride = layout.stride;
    let attributes = collector.attributes();
    let plain = PlainLayout::of(layout, attributes.colors);
    let mut done = 0;
    while done < count && stride > 0 {
        let want = (count - done).min((BLOCK_BYTES / stride).max(1) as u64) as usize;
        let (start, block) = whole_records(source, want, stride)?;
        let n = block.len() / stride;
        if n == 0 {
            break;
        }
        collector
            .fixed_vertices(n, |room| {
                let tasks: Vec<Result<bool, (usize, PlyProblem)>> = block
                    .par_chunks(TASK_RECORDS * stride)
                    .zip(room.split(TASK_RECORDS))
                    .enumerate()
                    .map(|(task, (bytes, mut room))| {
                        let base = task * TASK_RECORDS;
                        let mut values = [0f64; SLOTS];
                        let mut normals_kept = true;
                        if let Some(plain) = plain {
                            for (r, record) in bytes.chunks_exact(stride).enumerate() {
                                plain
                                    .set::<BIG>(&mut room, r, record)
                                    .map_err(|problem| (base + r, problem))?;
                            }
                            return Ok(true);
                        }
                        for (r, record) in bytes.chunks_exact(stride).enumerate() {
                            for &(offset, ty, slot) in &layout.fields {
                                values[slot] = ty.read::<BIG>(&record[offset..]);
                            }
                            normals_kept &= room
                                .set(r, &values, attributes.colors)
                                .map_err(|problem| (base + r, problem))?;
                        }
                        Ok(normals_kept)
                    })
                    .collect();
                tasks
                    .into_iter()
                    .try_fold(true, |all, kept| Ok(all & kept?))
            })
            .map_err(|(r, problem)| (record_place(start, r, stride), problem))?;
        source.consume(n * stride);
        done += n as u64;
    }
    Ok(done)
}

/// Reads face records `0..count` of the element that begins at the source's position while
/// they are whole triangles and the triangle limit has room; how many are read. Errors as the
/// general reader's: an index out of range names the face and its record's offset.
pub fn read_faces<const BIG: bool>(
    source: &mut ModelSource,
    count: u64,
    layout: &FaceLayout,
    collector: &mut Collector,
) -> Result<u64, (Place, PlyProblem)> {
    let stride = layout.stride;
    let three = three_as::<BIG>(layout.count);
    let length = layout.before..layout.before + layout.count.size();
    let items = length.end;
    let mut done = 0;
    while done < count {
        let want = (count - done)
            .min((BLOCK_BYTES / stride) as u64)
            .min(collector.triangle_room()) as usize;
        if want == 0 {
            break;
        }
        let (start, block) = whole_records(source, want, stride)?;
        let n = block.len() / stride;
        if n == 0 {
            break;
        }
        let read = collector.fixed_faces(n, |triangles, run| {
            let tasks: Vec<Result<usize, (usize, PlyProblem)>> = block
                .par_chunks(TASK_RECORDS * stride)
                .zip(triangles.par_chunks_mut(TASK_RECORDS))
                .enumerate()
                .map(|(task, (bytes, out))| {
                    let base = task * TASK_RECORDS;
                    let records = bytes.chunks_exact(stride);
                    for (r, (record, triangle)) in records.zip(out.iter_mut()).enumerate() {
                        if !record[length.clone()]
                            .iter()
                            .zip(&three)
                            .all(|(a, b)| a == b)
                        {
                            return Ok(r);
                        }
                        let corners = &record[items..items + 12];
                        *triangle = indices::<BIG>(corners, layout.item, run.vertices)
                            .ok_or_else(|| (base + r, out_of_range(run, base + r)))?;
                    }
                    Ok(out.len())
                })
                .collect();
            let mut read = 0;
            for (task, result) in tasks.into_iter().enumerate() {
                let whole = TASK_RECORDS.min(n - task * TASK_RECORDS);
                match result {
                    Ok(r) if r == whole => read += r,
                    Ok(r) => return Ok(read + r),
                    Err((r, problem)) => return Err((record_place(start, r, stride), problem)),
                }
            }
            Ok(read)
        })?;
        source.consume(read * stride);
        done += read as u64;
        if read < n {
            break;
        }
    }
    Ok(done)
}

/// The whole records of `stride` bytes among the next `want` in `source` (fewer where the file
/// ends), and the offset of the first: a block the fast paths decode. Nothing is consumed.
fn whole_records(
    source: &mut ModelSource,
    want: usize,
    stride: usize,
) -> Result<(u64, &[u8]), (Place, PlyProblem)> {
    let start = source.offset();
    let block = source
        .ahead_in_parallel(want * stride)
        .map_err(|e| (Place::File, PlyProblem::Io(e)))?;
    let whole = block.len() / stride * stride;
    Ok((start, &block[..whole.min(want * stride)]))
}

/// Where record `r` of a block that begins at byte `start` begins.
fn record_place(start: u64, r: usize, stride: usize) -> Place {
    Place::Byte(start + (r * stride) as u64)
}

/// The bytes of the number 3 as a list length of type `ty` (the first `ty.size()` of them).
fn three_as<const BIG: bool>(ty: Scalar) -> [u8; 4] {
    let mut bytes = [0u8; 4];
    let size = ty.size().min(4);
    bytes[if BIG { size - 1 } else { 0 }] = 3;
    bytes
}

/// The three indices at the start of `bytes` (`item` is `I32` or `U32`), when each is below
/// `vertices`.
#[inline(always)]
fn indices<const BIG: bool>(bytes: &[u8], item: Scalar, vertices: u64) -> Option<[u32; 3]> {
    let mut out = [0u32; 3];
    for (k, out) in out.iter_mut().enumerate() {
        let b: [u8; 4] = bytes[4 * k..4 * k + 4].try_into().expect("12 bytes");
        let word = if BIG {
            u32::from_be_bytes(b)
        } else {
            u32::from_le_bytes(b)
        };
        // A negative `I32` is out of range, as is any `U32` from 2^31 when vertices are fewer.
        let signed_negative = item == Scalar::I32 && word >= 1 << 31;
        if signed_negative || word as u64 >= vertices {
            return None;
        }
        *out = word;
    }
    Some(out)
}

/// The general reader's message for the face `r` records into `run`.
fn out_of_range(run: FaceRun, r: usize) -> PlyProblem {
    PlyProblem::IndexOutOfRange {
        face: run.first + r as u64,
        written: None,
        vertices: run.vertices,
    }
}
