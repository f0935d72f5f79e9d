//! The body of a binary STL: after the 84-byte header, 50 bytes a triangle (a normal, three
//! corners as little-endian `f32`, and two attribute bytes). The normal and the attribute
//! bytes are not read.
//!
//! Welding in two steps, for speed: a corner is named about six times, and a table of a
//! large mesh's vertices misses the cache on nearly every look-up. So pieces of the file are
//! welded alone first, in parallel, each with a table small enough to stay in a core's cache;
//! then only each piece's distinct corners, in the order the piece first names them, are
//! looked up in the whole mesh's table. That keeps the order of first sight in the file.

use std::io::Read;

use rayon::prelude::*;

use super::error::{StlProblem, coordinate_problem};
use crate::mesh::Place;
use crate::mesh::byte_source::ByteSource;
use crate::mesh::weld::{BATCH, Welder, coordinate_bits};

/// Bytes a binary STL gives each triangle.
pub const RECORD: usize = 50;

/// Triangles a piece welds alone: its table (about half a vertex a triangle) stays within a
/// core's 2 MiB cache.
const PIECE: usize = 1 << 15;

/// Pieces read ahead and welded in parallel together.
const ROUND: usize = 8;

/// One piece's corners welded alone.
struct Piece {
    /// Its distinct corners, in order of first sight.
    keys: Vec<[u32; 3]>,
    /// Each corner's index in `keys`, three a triangle.
    corners: Vec<u32>,
}

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
        let want = (count as u64 - done).min((ROUND * PIECE) as u64) as usize;
        let block = source.ahead(want * RECORD).map_err(io)?;
        let whole = (block.len() / RECORD).min(want);
        if whole == 0 {
            return Err((
                Place::Byte(start + block.len() as u64),
                StlProblem::Truncated {
                    triangle: done + 1,
                    count,
                },
            ));
        }
        let pieces: Vec<Result<Piece, (Place, StlProblem)>> = block[..whole * RECORD]
            .par_chunks(PIECE * RECORD)
            .enumerate()
            .map(|(k, bytes)| {
                let first = (k * PIECE) as u64;
                weld_piece(bytes, start + first * RECORD as u64, done + first)
            })
            .collect();
        let pieces = pieces.into_iter().collect::<Result<Vec<Piece>, _>>()?;
        // Each piece's distinct corners in the whole mesh, in file order.
        let ids: Vec<Vec<u32>> = pieces
            .iter()
            .map(|piece| {
                let mut ids = vec![0; piece.keys.len()];
                for (keys, out) in piece.keys.chunks(BATCH).zip(ids.chunks_mut(BATCH)) {
                    welder.index_all(keys, out);
                }
                ids
            })
            .collect();
        let base = triangles.len();
        triangles.resize(base + whole, [0; 3]);
        triangles[base..]
            .par_chunks_mut(PIECE)
            .zip(pieces.par_iter().zip(&ids))
            .for_each(|(out, (piece, ids))| {
                for (t, c) in out.iter_mut().zip(piece.corners.chunks_exact(3)) {
                    *t = [ids[c[0] as usize], ids[c[1] as usize], ids[c[2] as usize]];
                }
            });
        source.consume(whole * RECORD);
        done += whole as u64;
    }
    Ok(())
}

/// The triangles `bytes` holds (whole records, the first at file offset `offset` and numbered
/// `before + 1`), their corners welded among themselves.
fn weld_piece(bytes: &[u8], offset: u64, before: u64) -> Result<Piece, (Place, StlProblem)> {
    let triangles = bytes.len() / RECORD;
    // A closed mesh has about half as many vertices as triangles.
    let mut welder = Welder::<3>::with_capacity(triangles / 2);
    let mut corners = vec![0u32; 3 * triangles];
    // Triangles in batches whose corners are welded together (see `Welder::index_all`).
    const TRIANGLES: usize = BATCH / 3;
    let mut keys = [[0u32; 3]; TRIANGLES * 3];
    for (b, (batch, out)) in bytes
        .chunks(TRIANGLES * RECORD)
        .zip(corners.chunks_mut(TRIANGLES * 3))
        .enumerate()
    {
        for (t, record) in batch.chunks_exact(RECORD).enumerate() {
            // The corners' nine coordinates, after the 12 bytes of the normal.
            for (j, b4) in record[12..48].chunks_exact(4).enumerate() {
                let value = f32::from_le_bytes([b4[0], b4[1], b4[2], b4[3]]);
                if !crate::scene::limits::COORDINATE.accepts(value) {
                    let t_piece = b * TRIANGLES + t;
                    let problem = coordinate_problem(value, before + t_piece as u64 + 1)
                        .expect("a coordinate the limits refuse");
                    let at = offset + (t_piece * RECORD + 12 + 4 * j) as u64;
                    return Err((Place::Byte(at), problem));
                }
                keys[3 * t + j / 3][j % 3] = coordinate_bits(value);
            }
        }
        welder.index_all(&keys[..out.len()], out);
    }
    Ok(Piece {
        keys: welder.into_keys(),
        corners,
    })
}
