//! The body of a binary STL: after the 84-byte header, 50 bytes a triangle (a normal, three
//! corners as little-endian `f32`, and two attribute bytes). The normal and the attribute
//! bytes are not read.

use std::io::Read;

use super::error::{StlProblem, coordinate_problem};
use crate::mesh::Place;
use crate::mesh::byte_source::ByteSource;
use crate::mesh::weld::{Welder, coordinate_bits};

/// Bytes a binary STL gives each triangle.
pub const RECORD: usize = 50;

/// Reads `count` triangles from `source` (just past the header), welding their corners into
/// `welder` and appending their corner indices to `triangles`.
pub fn read_triangles<R: Read>(
    source: &mut ByteSource<R>,
    count: u32,
    welder: &mut Welder<3>,
    triangles: &mut Vec<[u32; 3]>,
) -> Result<(), (Place, StlProblem)> {
    let io = |e| (Place::File, StlProblem::Io(e));
    let mut done = 0u64;
    while done < count as u64 {
        let start = source.offset();
        let block = source.ahead(RECORD).map_err(io)?;
        let whole = (block.len() / RECORD).min((count as u64 - done) as usize);
        if whole == 0 {
            return Err((
                Place::Byte(start + block.len() as u64),
                StlProblem::Truncated {
                    triangle: done + 1,
                    count,
                },
            ));
        }
        for (t, record) in block[..whole * RECORD].chunks_exact(RECORD).enumerate() {
            let mut corners = [0u32; 3];
            for (k, corner) in corners.iter_mut().enumerate() {
                let mut key = [0u32; 3];
                for (c, bits) in key.iter_mut().enumerate() {
                    let at = 12 + 12 * k + 4 * c;
                    let b = &record[at..at + 4];
                    let value = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                    if let Some(problem) = coordinate_problem(value, done + t as u64 + 1) {
                        let offset = start + (t * RECORD + at) as u64;
                        return Err((Place::Byte(offset), problem));
                    }
                    *bits = coordinate_bits(value);
                }
                *corner = welder.index(key);
            }
            triangles.push(corners);
        }
        source.consume(whole * RECORD);
        done += whole as u64;
    }
    Ok(())
}
