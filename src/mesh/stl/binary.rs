//! The body of a binary STL: after the 84-byte header, 50 bytes a triangle (a normal, three
//! corners as little-endian `f32`, and two attribute bytes). The normal and the attribute
//! bytes are not read.
//!
//! The body is read into memory at once (50 bytes a triangle, never zero-filled first), its
//! coordinates checked in parallel, and its corners (about six a position) welded straight
//! from those bytes by [`weld`], which keeps the order of first sight in the file.

use std::fs::File;
use std::io::Take;

use glam::Vec3;
use rayon::prelude::*;

use super::error::{StlProblem, coordinate_problem};
use crate::mesh::Place;
use crate::mesh::byte_source::ByteSource;
use crate::mesh::weld::{Indexed, Repeats, coordinate_bits, weld};

/// Bytes a binary STL gives each triangle.
pub const RECORD: usize = 50;

/// Triangles one task checks.
const TASK: usize = 1 << 15;

/// Reads `count` triangles from `source` (just past the header): the distinct corner
/// positions, in order of first sight, and each triangle's corners as indices into them.
pub fn read_triangles(
    source: &mut ByteSource<Take<File>>,
    count: u32,
) -> Result<Indexed<Vec3>, (Place, StlProblem)> {
    let start = source.offset();
    let body = source
        .take_vec(count as usize * RECORD)
        .map_err(|e| (Place::File, StlProblem::Io(e)))?;
    let whole = body.len() / RECORD;
    let records = &body[..whole * RECORD];
    check_coordinates(records, start)?;
    if whole < count as usize {
        return Err((
            Place::Byte(start + body.len() as u64),
            StlProblem::Truncated {
                triangle: whole as u64 + 1,
                count,
            },
        ));
    }
    let corner = |i: usize| {
        let at = i / 3 * RECORD + 12 + 12 * (i % 3);
        let c = &records[at..at + 12];
        let bits =
            |k: usize| coordinate_bits(f32::from_le_bytes([c[k], c[k + 1], c[k + 2], c[k + 3]]));
        [bits(0), bits(4), bits(8)]
    };
    let mut triangles = crate::huge_pages::filled(whole, [0u32; 3]);
    let positions = weld(
        triangles.as_flattened_mut(),
        Repeats::Near,
        corner,
        |_| true,
        |i| {
            let [x, y, z] = corner(i).map(f32::from_bits);
            Vec3::new(x, y, z)
        },
    );
    Ok((positions, triangles))
}

/// Checks every corner coordinate of `records` (whole records, the first at file offset
/// `start`) against the scene's limits; the first refused names its triangle and byte.
fn check_coordinates(records: &[u8], start: u64) -> Result<(), (Place, StlProblem)> {
    let refused = records
        .par_chunks(TASK * RECORD)
        .enumerate()
        .find_map_first(|(task, bytes)| {
            bytes
                .chunks_exact(RECORD)
                .enumerate()
                .find_map(|(t, record)| {
                    record[12..48]
                        .chunks_exact(4)
                        .enumerate()
                        .find_map(|(j, b)| {
                            let value = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                            let triangle = task * TASK + t;
                            coordinate_problem(value, triangle as u64 + 1).map(|problem| {
                                let at = start + (triangle * RECORD + 12 + 4 * j) as u64;
                                (Place::Byte(at), problem)
                            })
                        })
                })
        });
    refused.map_or(Ok(()), Err)
}
