//! OBJ import: the statements rastray draws (`v`, `vt`, `vn`, `f`, and `usemtl` and `mtllib`
//! for materials), polygons fan-triangulated, every group merged into one face list that
//! remembers which material each triangle uses. The file is read a block of a few megabytes at
//! a time; each block's whole lines are cut into pieces read on all cores
//! ([`super::obj_piece`]) and joined in order, so indices, errors and materials are as one
//! reader going line by line would find them; the pieces write their positions and triangles
//! straight into the file's arrays ([`super::piece_room`]). The next block is read
//! ([`super::line_blocks`]) while one is parsed. Nothing else of the file is kept, so loading
//! takes about the memory of the result and a block: 12 bytes a vertex and 12 a triangle (36
//! more a triangle when the file gives normals everywhere, 24 more when it gives texture
//! coordinates everywhere, 12 more a vertex when it colours every vertex).
//! [`super::obj_model`] turns the materials into parts.
//!
//! Vertex colours follow the common extension `v x y z r g b`: three numbers in 0..1 after the
//! position, sRGB-encoded as image colours are (values outside 0..1 are clamped), decoded to
//! linear light. They are kept only when every vertex has one; a `v x y z w` (four numbers) has
//! none.

use std::path::Path;

use glam::{Vec2, Vec3};

use super::geometry::ModelGeometry;
use super::line_blocks::{Stop, for_each_line_block};
use rayon::prelude::*;

use super::obj_error::{ObjError, ObjProblem};
use super::obj_piece::{Counts, Piece, count_statements, read_piece};
use super::piece_room::{Filled, Room, join_rooms};
use super::used_vertices::drop_unused;
use crate::huge_pages::extend_filled;
use crate::input_file::{MAX_MODEL_BYTES, open_bounded, read_bounded};

/// What a model file is called in refusals.
const MODEL_FILE: &str = "a model file";

/// Reads the OBJ file at `path`: a regular file of at most [`MAX_MODEL_BYTES`]. Vertices must
/// lie within the scene's coordinate limits. Errors name the file, and the line where there is
/// one. Vertices no face uses are dropped. Every face is kept, whatever its material.
pub fn load_obj(path: &Path) -> Result<ModelGeometry, ObjError> {
    read_obj(path).map(|read| read.geometry)
}

/// An OBJ file as read: its geometry, which material each triangle uses, and the material
/// libraries it names.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjRead {
    /// Every face of the file, welded as the file indexes them.
    pub geometry: ModelGeometry,
    /// The names `usemtl` gave, in the order first met.
    pub material_names: Vec<String>,
    /// Where each run of triangles starts and the material it uses (an index into
    /// `material_names`, or `None` before any `usemtl`), ascending by start; empty when the file
    /// never says `usemtl`.
    pub material_runs: Vec<(u32, Option<u32>)>,
    /// Each `mtllib` statement: its line and the rest of the line as written.
    pub libraries: Vec<(usize, String)>,
}

/// Most bytes of the file read at a time, then shared out among the cores in pieces of whole
/// lines: the text in memory at once stays a few megabytes, whatever the file's size.
const BLOCK: usize = 1 << 23;

/// Pieces a block is cut into, a few a core (on 2 cores), so that the cores finish together.
const PIECES: usize = 8;

/// Fewest bytes worth a piece of its own.
const MIN_PIECE: usize = 1 << 16;

/// As [`load_obj`], keeping what the file says of materials.
pub fn read_obj(path: &Path) -> Result<ObjRead, ObjError> {
    read_obj_in_blocks(path, BLOCK)
}

/// [`read_obj`] reading `block` bytes at a time (tests make it small, so that statements fall
/// across blocks and pieces).
pub fn read_obj_in_blocks(path: &Path, block: usize) -> Result<ObjRead, ObjError> {
    let fail = |line, problem| ObjError {
        path: path.to_path_buf(),
        line,
        problem,
    };
    let io = |e| fail(None, ObjProblem::Io(e));
    let mut file = open_bounded(path, MAX_MODEL_BYTES, MODEL_FILE).map_err(io)?;
    let mut statements = Statements::default();
    for_each_line_block(&mut file, block, |lines| {
        statements.read_lines(lines, block)
    })
    .map_err(|stop| match stop {
        Stop::Io(e) => io(e),
        Stop::Refused((line, problem)) => fail(Some(line), problem),
    })?;
    if file.limit() == 0 {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "the file grew past the size limit while it was read",
        )));
    }
    let count = statements.positions.len();
    if statements.missing_vertex
        || statements
            .triangles
            .par_iter()
            .any(|t| t.iter().any(|&i| i as usize >= count))
    {
        // Faces may come before the vertices they name: only now is a missing one known. The
        // text is read again only to say where.
        let text = read_bounded(path, MAX_MODEL_BYTES, MODEL_FILE).map_err(io)?;
        return Err(match missing_vertex(&text) {
            Some((line, index, count)) => {
                fail(Some(line), ObjProblem::MissingVertex { index, count })
            }
            None => fail(
                None,
                ObjProblem::Malformed("a face names a vertex the file lacks"),
            ),
        });
    }
    if statements.triangles.is_empty() {
        return Err(fail(None, ObjProblem::NoFaces));
    }
    let material_names = std::mem::take(&mut statements.material_names);
    let material_runs = std::mem::take(&mut statements.material_runs);
    let libraries = std::mem::take(&mut statements.libraries);
    Ok(ObjRead {
        geometry: statements.finish().map_err(|problem| fail(None, problem))?,
        material_names,
        material_runs,
        libraries,
    })
}

/// The geometry read so far.
#[derive(Default)]
struct Statements {
    /// Lines and statements read so far.
    counts: Counts,
    positions: Vec<Vec3>,
    /// Unit normals (zero for a zero normal), as `vn` statements give them.
    normals: Vec<Vec3>,
    /// The linear colour of each vertex, while every vertex so far has one.
    colors: Vec<Vec3>,
    /// Whether some vertex has no colour.
    vertex_without_color: bool,
    triangles: Vec<[u32; 3]>,
    /// The normal index of each triangle corner, while every corner so far has one.
    normal_corners: Vec<[u32; 3]>,
    /// Whether some face corner has no normal.
    corner_without_normal: bool,
    /// Texture coordinates (u, v) as `vt` statements give them (OBJ's origin: bottom-left).
    uvs: Vec<Vec2>,
    /// The texture coordinate index of each triangle corner, while every corner so far has one.
    uv_corners: Vec<[u32; 3]>,
    /// Whether some face corner has no texture coordinate.
    corner_without_uv: bool,
    /// The names `usemtl` gave, in the order first met, and their indices.
    material_names: Vec<String>,
    material_index: std::collections::HashMap<String, u32>,
    /// Where each run of triangles of one material starts (see [`ObjRead::material_runs`]).
    material_runs: Vec<(u32, Option<u32>)>,
    /// The material of the faces read next: `None` before any `usemtl`.
    material: Option<u32>,
    /// The `mtllib` statements: line and the rest of the line.
    libraries: Vec<(usize, String)>,
    /// Whether a face named a vertex before the first (index 0, or negative too far back).
    missing_vertex: bool,
}

impl Statements {
    /// Reads `text` (whole lines, the next of the file, read `block` bytes at a time) in
    /// [`PIECES`] pieces, or fewer of [`MIN_PIECE`] bytes or more, on the current rayon pool,
    /// and adds them in order. An error names its line.
    fn read_lines(&mut self, text: &[u8], block: usize) -> Result<(), (usize, ObjProblem)> {
        let pieces = pieces(text, (text.len() / PIECES).max(MIN_PIECE.min(block)));
        // One task a piece: rayon would otherwise cut the pieces into one half a thread, and a
        // thread that woke late found its half already taken by the other.
        let counts: Vec<Counts> = pieces
            .par_iter()
            .with_max_len(1)
            .map(|p| count_statements(p))
            .collect();
        let mut before = Vec::with_capacity(pieces.len());
        let mut so_far = Counts {
            triangles: 0,
            ..self.counts
        };
        for c in &counts {
            before.push(so_far);
            so_far = so_far.then(*c);
        }
        let limit = crate::memory_budget::triangle_cap();
        let holds = counts.iter().fold(Counts::default(), |a, &b| a.then(b));
        self.reserve(holds);
        // Each piece's room in the file's arrays, as long as its counts say (its faces' first
        // triangles, as far as the triangle limit allows), written as the pieces are read.
        let mut positions = std::mem::take(&mut self.positions);
        let mut triangles = std::mem::take(&mut self.triangles);
        let (positions_start, triangles_start) = (positions.len(), triangles.len());
        let triangle_room = holds
            .faces
            .min((limit as usize).saturating_sub(triangles_start));
        let position_rooms = Room::cut(
            extend_filled(&mut positions, holds.positions, Vec3::ZERO),
            counts.iter().map(|c| c.positions),
        );
        let triangle_rooms = Room::cut(
            extend_filled(&mut triangles, triangle_room, [0; 3]),
            counts.iter().map(|c| c.faces),
        );
        let read: Vec<Result<Piece, (usize, ObjProblem)>> = pieces
            .par_iter()
            .with_max_len(1)
            .zip(&before)
            .zip(&counts)
            .zip(position_rooms.into_par_iter().zip(triangle_rooms))
            .map(|(((text, &before), &holds), (positions, triangles))| {
                read_piece(text, before, holds, positions, triangles)
            })
            .collect();
        let mut filled_positions = Vec::with_capacity(read.len());
        let mut filled_triangles = Vec::with_capacity(read.len());
        let mut triangles_read = triangles_start;
        for (((piece, text), before), holds) in
            read.into_iter().zip(&pieces).zip(before).zip(counts)
        {
            let piece = match piece {
                Ok(piece) if (triangles_read + piece.triangles.len()) as u64 <= limit => piece,
                // Read again knowing the triangles before: the file passes the triangle limit
                // there, before the piece's own error or without one. The piece was refused
                // or went past the limit, so this reading is refused too.
                _ => {
                    let before = Counts {
                        triangles: triangles_read,
                        ..before
                    };
                    read_piece(text, before, holds, Room::default(), Room::default())?;
                    return Err((
                        before.lines + holds.lines,
                        ObjProblem::TooManyTriangles { limit },
                    ));
                }
            };
            let start = triangles_read;
            triangles_read += piece.triangles.len();
            let (positions, triangles) = self.add(piece, start);
            filled_positions.push(positions);
            filled_triangles.push(triangles);
        }
        join_rooms(&mut positions, positions_start, &filled_positions);
        join_rooms(&mut triangles, triangles_start, &filled_triangles);
        self.positions = positions;
        self.triangles = triangles;
        self.counts = Counts {
            triangles: 0,
            ..so_far
        };
        Ok(())
    }

    /// Makes room for the normals, texture coordinates and colours that `holds` counts, about
    /// to be added (positions and triangles get theirs as rooms, see [`Statements::read_lines`]).
    fn reserve(&mut self, holds: Counts) {
        self.normals.reserve(holds.normals);
        self.uvs.reserve(holds.uvs);
        if !self.vertex_without_color && !self.colors.is_empty() {
            self.colors.reserve(holds.positions);
        }
    }

    /// Adds a piece read after everything so far, its first triangle the file's `start`-th,
    /// but for its positions and triangles, which are in its rooms: what [`join_rooms`] needs
    /// of them is returned.
    fn add(&mut self, piece: Piece, start: usize) -> (Filled<Vec3>, Filled<[u32; 3]>) {
        append(&mut self.normals, &piece.normals);
        append(&mut self.uvs, &piece.uvs);
        self.missing_vertex |= piece.missing_vertex;
        if piece.vertex_without_color {
            self.vertex_without_color = true;
            self.colors = Vec::new();
        } else if !self.vertex_without_color {
            append(&mut self.colors, &piece.colors);
        }
        // Each `usemtl` where it came among the triangles.
        for (at, name) in &piece.material_uses {
            self.use_material(name, start + at);
        }
        if piece.corner_without_normal {
            self.corner_without_normal = true;
            self.normal_corners = Vec::new();
        } else if !self.corner_without_normal {
            append(&mut self.normal_corners, &piece.normal_corners);
        }
        if piece.corner_without_uv {
            self.corner_without_uv = true;
            self.uv_corners = Vec::new();
        } else if !self.corner_without_uv {
            append(&mut self.uv_corners, &piece.uv_corners);
        }
        self.libraries.extend(piece.libraries);
        (piece.positions.into_filled(), piece.triangles.into_filled())
    }

    /// Makes `name` the material of the faces from triangle `start` on (`usemtl` with no
    /// name: none).
    fn use_material(&mut self, name: &str, start: usize) {
        let material = (!name.is_empty()).then(|| {
            let next = self.material_names.len() as u32;
            *self
                .material_index
                .entry(name.to_string())
                .or_insert_with(|| {
                    self.material_names.push(name.to_string());
                    next
                })
        });
        if material == self.material {
            return;
        }
        let start = start as u32;
        if self.material_runs.is_empty() && start > 0 {
            self.material_runs.push((0, None));
        }
        match self.material_runs.last_mut() {
            // A run with no triangles yet takes the new material.
            Some(last) if last.0 == start => last.1 = material,
            _ => self.material_runs.push((start, material)),
        }
        self.material = material;
    }

    /// The geometry: unused vertices dropped, corner normals kept when every corner has a
    /// finite, non-zero one, texture coordinates when every corner has one (stored as
    /// (u, 1 − v): the image's top-left is the origin of [`ModelGeometry::corner_uvs`]).
    fn finish(self) -> Result<ModelGeometry, ObjProblem> {
        let mut triangles = self.triangles;
        let given = !self.vertex_without_color && self.colors.len() == self.positions.len();
        let (positions, colors) = match drop_unused(&mut triangles, self.positions.len()) {
            // Every vertex is used (as in nearly every file): the numbering stays as it is.
            None => {
                let mut positions = self.positions;
                positions.shrink_to_fit();
                (positions, given.then_some(self.colors))
            }
            // The vertices faces use, kept in file order.
            Some(kept) => {
                let positions = kept.iter().map(|&k| self.positions[k as usize]).collect();
                let colors = given.then(|| kept.iter().map(|&k| self.colors[k as usize]).collect());
                (positions, colors)
            }
        };
        triangles.shrink_to_fit();
        let corner_normals = if self.corner_without_normal || self.normals.is_empty() {
            None
        } else {
            let normals = &self.normals;
            let corners: Vec<[Vec3; 3]> = self
                .normal_corners
                .par_iter()
                .map(|t| t.map(|n| normals[n as usize]))
                .collect();
            corners
                .par_iter()
                .all(|t| t.iter().all(|n| n.is_finite() && *n != Vec3::ZERO))
                .then_some(corners)
        };
        let corner_uvs = (!self.corner_without_uv && !self.uvs.is_empty()).then(|| {
            let uvs = &self.uvs;
            self.uv_corners
                .par_iter()
                .map(|t| t.map(|k| Vec2::new(uvs[k as usize].x, 1.0 - uvs[k as usize].y)))
                .collect()
        });
        Ok(ModelGeometry {
            positions,
            triangles,
            corner_normals,
            colors,
            corner_uvs,
        })
    }
}

/// Fewest items worth copying on every core.
const PARALLEL_COPY: usize = 1 << 14;

/// Appends `items` to `to`, copied on every core when they are many: on one core, the copy and
/// the fresh pages it touches were a twentieth of loading the 1.31M-triangle icosphere.
fn append<T: Copy + Send + Sync>(to: &mut Vec<T>, items: &[T]) {
    if items.len() < PARALLEL_COPY {
        to.extend_from_slice(items);
    } else {
        to.par_extend(items.par_iter().copied());
    }
}

/// The OBJ statements of `text` as (1-based line, keyword, arguments).
fn statements(text: &[u8]) -> impl Iterator<Item = (usize, &str, std::str::SplitWhitespace<'_>)> {
    text.split(|&b| b == b'\n')
        .enumerate()
        .filter_map(|(n, line)| {
            let mut words = std::str::from_utf8(line).ok()?.split_whitespace();
            Some((n + 1, words.next()?, words))
        })
}

/// The first face corner naming a vertex the file lacks: its line, the index as written, and
/// the file's vertex count. Negative indices count back from the vertices read so far.
fn missing_vertex(text: &[u8]) -> Option<(usize, i64, usize)> {
    let count = statements(text).filter(|(_, k, _)| *k == "v").count();
    let mut so_far = 0i64;
    for (line, keyword, corners) in statements(text) {
        match keyword {
            "v" => so_far += 1,
            "f" => {
                for corner in corners {
                    let Some(index) = corner.split('/').next().and_then(|i| i.parse::<i64>().ok())
                    else {
                        continue;
                    };
                    let resolved = if index < 0 { so_far + index } else { index - 1 };
                    if !(0..count as i64).contains(&resolved) {
                        return Some((line, index, count));
                    }
                }
            }
            _ => {}
        }
    }
    None
}

/// `text` cut into pieces of whole lines of about `size` bytes or more (the last may be
/// shorter), in order.
fn pieces(text: &[u8], size: usize) -> Vec<&[u8]> {
    let mut pieces = Vec::new();
    let mut rest = text;
    while rest.len() > size {
        let cut = rest[size..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(rest.len(), |at| size + at + 1);
        let (piece, after) = rest.split_at(cut);
        pieces.push(piece);
        rest = after;
    }
    if !rest.is_empty() {
        pieces.push(rest);
    }
    pieces
}
