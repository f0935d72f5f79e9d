//! OBJ import: the statements rastray draws (`v`, `vn`, `f`) read line by line as the file
//! streams in, polygons fan-triangulated, every group merged into one face list. Nothing else
//! of the file is kept, so loading takes about the memory of the result: 12 bytes a vertex and
//! 12 a triangle (36 more a triangle when the file gives normals everywhere, 12 more a vertex
//! when it colours every vertex).
//!
//! Vertex colours follow the common extension `v x y z r g b`: three numbers in 0..1 after the
//! position, sRGB-encoded as image colours are (values outside 0..1 are clamped), decoded to
//! linear light. They are kept only when every vertex has one; a `v x y z w` (four numbers) has
//! none.

use std::io::{BufRead, BufReader};
use std::path::Path;

use glam::Vec3;

use super::geometry::ModelGeometry;
use super::normals::unit_or_zero;
use super::obj_error::{ObjError, ObjProblem};
use super::srgb::srgb_to_linear;
use crate::input_file::{MAX_MODEL_BYTES, open_bounded, read_bounded};
use crate::scene::limits::COORDINATE;

/// An OBJ file's geometry: every group of the file merged into one face list.
pub type ObjModel = ModelGeometry;

/// What a model file is called in refusals.
const MODEL_FILE: &str = "a model file";

/// Reads the OBJ file at `path`: a regular file of at most [`MAX_MODEL_BYTES`]. Vertices must
/// lie within the scene's coordinate limits. Errors name the file, and the line where there is
/// one. Vertices no face uses are dropped.
pub fn load_obj(path: &Path) -> Result<ObjModel, ObjError> {
    let fail = |line, problem| ObjError {
        path: path.to_path_buf(),
        line,
        problem,
    };
    let io = |e| fail(None, ObjProblem::Io(e));
    let file = open_bounded(path, MAX_MODEL_BYTES, MODEL_FILE).map_err(io)?;
    let mut reader = BufReader::with_capacity(1 << 16, file);
    let mut statements = Statements::default();
    let mut line = Vec::new();
    let mut number = 0;
    loop {
        line.clear();
        if reader.read_until(b'\n', &mut line).map_err(io)? == 0 {
            break;
        }
        number += 1;
        statements
            .read(&line)
            .map_err(|problem| fail(Some(number), problem))?;
    }
    if reader.get_ref().limit() == 0 {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "the file grew past the size limit while it was read",
        )));
    }
    let count = statements.positions.len();
    if statements.missing_vertex
        || statements
            .triangles
            .iter()
            .flatten()
            .any(|&i| i as usize >= count)
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
    statements.finish().map_err(|problem| fail(None, problem))
}

/// The geometry read so far.
#[derive(Default)]
struct Statements {
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
    /// Whether a face named a vertex before the first (index 0, or negative too far back).
    missing_vertex: bool,
    /// The corners of the face being read: vertex and normal indices, from 0.
    corners: Vec<(u32, Option<u32>)>,
}

/// An index that names nothing.
const NONE: u32 = u32::MAX;

impl Statements {
    /// Reads one line of the file.
    fn read(&mut self, line: &[u8]) -> Result<(), ObjProblem> {
        // A comment in another encoding is no obstacle; a number in one is no number.
        let line = String::from_utf8_lossy(line);
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => {
                let p = three_numbers(&mut words).ok_or(ObjProblem::Malformed(
                    "a vertex is `v x y z`, three numbers",
                ))?;
                let vertex = self.positions.len() + 1;
                if let Some(&value) = p.iter().find(|&&x| !COORDINATE.accepts(x)) {
                    return Err(if value.is_finite() {
                        ObjProblem::VertexOutOfRange { vertex, value }
                    } else {
                        ObjProblem::NonFiniteVertex { vertex }
                    });
                }
                self.positions.push(Vec3::from_array(p));
                match (vertex_color(&mut words), self.vertex_without_color) {
                    (_, true) => {}
                    (Some(color), false) => self.colors.push(color),
                    (None, false) => {
                        self.vertex_without_color = true;
                        self.colors = Vec::new();
                    }
                }
            }
            Some("vn") => {
                let n = three_numbers(&mut words).ok_or(ObjProblem::Malformed(
                    "a normal is `vn x y z`, three numbers",
                ))?;
                self.normals.push(unit_or_zero(Vec3::from_array(n)));
            }
            Some("f") => self.face(words)?,
            // Texture coordinates, groups, materials, smoothing groups, points and lines: not
            // drawn.
            _ => {}
        }
        Ok(())
    }

    /// Reads the corners of an `f` statement and fans them into triangles.
    fn face(&mut self, words: std::str::SplitWhitespace<'_>) -> Result<(), ObjProblem> {
        self.corners.clear();
        for word in words {
            let mut parts = word.split('/');
            let vertex =
                parts
                    .next()
                    .and_then(|v| v.parse::<i64>().ok())
                    .ok_or(ObjProblem::Malformed(
                        "a face corner is `v`, `v/vt`, `v//vn` or `v/vt/vn`",
                    ))?;
            let normal = match parts.nth(1) {
                Some("") | None => None,
                Some(n) => Some(n.parse::<i64>().map_err(|_| {
                    ObjProblem::Malformed("a face corner is `v`, `v/vt`, `v//vn` or `v/vt/vn`")
                })?),
            };
            let vertex = resolve(vertex, self.positions.len());
            self.missing_vertex |= vertex == NONE;
            let normal = normal.map(|n| resolve(n, self.normals.len()));
            if normal.is_some_and(|n| n as usize >= self.normals.len()) {
                return Err(ObjProblem::Malformed(
                    "a face names a normal the file lacks",
                ));
            }
            self.corners.push((vertex, normal));
        }
        // A point or a line: not drawn.
        if self.corners.len() < 3 {
            return Ok(());
        }
        // Refused as soon as it shows: a model file of nothing but tiny faces must not fill
        // memory before the world counts its triangles.
        let limit = crate::world::MAX_TRIANGLES;
        if (self.triangles.len() + self.corners.len() - 2) as u64 > limit {
            return Err(ObjProblem::TooManyTriangles { limit });
        }
        let (first, first_normal) = self.corners[0];
        for pair in self.corners[1..].windows(2) {
            let [(b, b_normal), (c, c_normal)] = [pair[0], pair[1]];
            self.triangles.push([first, b, c]);
            match (first_normal, b_normal, c_normal) {
                (Some(na), Some(nb), Some(nc)) if !self.corner_without_normal => {
                    self.normal_corners.push([na, nb, nc]);
                }
                _ => {
                    self.corner_without_normal = true;
                    self.normal_corners = Vec::new();
                }
            }
        }
        Ok(())
    }

    /// The geometry: unused vertices dropped, corner normals kept when every corner has a
    /// finite, non-zero one.
    fn finish(self) -> Result<ModelGeometry, ObjProblem> {
        let mut triangles = self.triangles;
        // Renumber the vertices faces use, in file order.
        let mut new_index = vec![NONE; self.positions.len()];
        for &i in triangles.iter().flatten() {
            new_index[i as usize] = 0;
        }
        let used = new_index.iter().filter(|&&i| i == 0).count();
        let mut positions = Vec::with_capacity(used);
        let given = !self.vertex_without_color && self.colors.len() == self.positions.len();
        let mut colors = given.then(|| Vec::with_capacity(used));
        for (k, (slot, &p)) in new_index.iter_mut().zip(&self.positions).enumerate() {
            if *slot == 0 {
                *slot = positions.len() as u32;
                positions.push(p);
                if let Some(colors) = &mut colors {
                    colors.push(self.colors[k]);
                }
            }
        }
        drop(self.colors);
        drop(self.positions);
        for i in triangles.iter_mut().flatten() {
            *i = new_index[*i as usize];
        }
        triangles.shrink_to_fit();
        let corner_normals = if self.corner_without_normal || self.normals.is_empty() {
            None
        } else {
            let normals = &self.normals;
            let corners: Vec<[Vec3; 3]> = self
                .normal_corners
                .iter()
                .map(|t| t.map(|n| normals[n as usize]))
                .collect();
            corners
                .iter()
                .flatten()
                .all(|n| n.is_finite() && *n != Vec3::ZERO)
                .then_some(corners)
        };
        Ok(ModelGeometry {
            positions,
            triangles,
            corner_normals,
            colors,
            corner_uvs: None,
        })
    }
}

/// Index `i` as written (from 1, or negative back from the `count` read so far) as an index
/// from 0; [`NONE`] when it names nothing before the end of what was read. A positive index may
/// name a vertex the file gives later; it is checked at the end.
fn resolve(i: i64, count: usize) -> u32 {
    let resolved = if i < 0 { count as i64 + i } else { i - 1 };
    u32::try_from(resolved)
        .ok()
        .filter(|&r| r != NONE)
        .unwrap_or(NONE)
}

/// The vertex colour that ends a `v` statement, `r g b` after the position: exactly three
/// finite numbers, read as sRGB in 0..1 (clamped) and decoded to linear. `None` otherwise.
fn vertex_color(words: &mut std::str::SplitWhitespace<'_>) -> Option<Vec3> {
    let rgb = three_numbers(words)?;
    if words.next().is_some() || !rgb.iter().all(|c| c.is_finite()) {
        return None;
    }
    Some(Vec3::from_array(rgb.map(srgb_to_linear)))
}

/// The next three words as numbers; `None` when they are fewer or not numbers.
fn three_numbers(words: &mut std::str::SplitWhitespace<'_>) -> Option<[f32; 3]> {
    let mut xyz = [0.0; 3];
    for x in &mut xyz {
        *x = words.next()?.parse().ok()?;
    }
    Some(xyz)
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
