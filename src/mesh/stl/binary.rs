//! The body of a binary STL: after the 84-byte header, 50 bytes a triangle (a normal, three
//! corners as little-endian `f32`, and two attribute bytes). The normal and the attribute
//! bytes are not read.

use std::io::Read;

use super::error::{StlProblem, coordinate_problem};
use crate::mesh::Place;
use crate::mesh::byte_source::ByteSource;
use crate::mesh::weld::{BATCH, Welder, coordinate_bits};

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
        // Triangles in batches whose corners are welded together (see `Welder::index_all`).
        const TRIANGLES: usize = BATCH / 3;
        let mut keys = [[0u32; 3]; TRIANGLES * 3];
        let mut corners = [0u32; TRIANGLES * 3];
        for (b, batch) in block[..whole * RECORD]
            .chunks(TRIANGLES * RECORD)
            .enumerate()
        {
            for (t, record) in batch.chunks_exact(RECORD).enumerate() {
                // The corners' nine coordinates, after the 12 bytes of the normal.
                for (j, b4) in record[12..48].chunks_exact(4).enumerate() {
                    let value = f32::from_le_bytes([b4[0], b4[1], b4[2], b4[3]]);
                    let t_block = b * TRIANGLES + t;
                    if let Some(problem) = coordinate_problem(value, done + t_block as u64 + 1) {
                        let offset = start + (t_block * RECORD + 12 + 4 * j) as u64;
                        return Err((Place::Byte(offset), problem));
                    }
                    keys[3 * t + j / 3][j % 3] = coordinate_bits(value);
                }
            }
            let n = batch.len() / RECORD * 3;
            welder.index_all(&keys[..n], &mut corners[..n]);
            triangles.extend(corners[..n].chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        }
        source.consume(whole * RECORD);
        done += whole as u64;
    }
    Ok(())
}
