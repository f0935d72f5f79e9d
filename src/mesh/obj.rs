//! OBJ import: the statements rastray draws (`v`, `vt`, `vn`, `f`, and `usemtl` and `mtllib`
//! for materials) read line by line as the file streams in, polygons fan-triangulated, every
//! group merged into one face list that remembers which material each triangle uses. Nothing
//! else of the file is kept, so loading takes about the memory of the result: 12 bytes a vertex
//! and 12 a triangle (36 more a triangle when the file gives normals everywhere, 24 more when it
//! gives texture coordinates everywhere, 12 more a vertex when it colours every vertex).
//! [`super::obj_model`] turns the materials into parts.
//!
//! Vertex colours follow the common extension `v x y z r g b`: three numbers in 0..1 after the
//! position, sRGB-encoded as image colours are (values outside 0..1 are clamped), decoded to
//! linear light. They are kept only when every vertex has one; a `v x y z w` (four numbers) has
//! none.

use std::io::{BufRead, BufReader};
use std::path::Path;

use glam::{Vec2, Vec3};

use super::geometry::ModelGeometry;
use super::normals::unit_or_zero;
use super::obj_error::{ObjError, ObjProblem};
use super::srgb::srgb_to_linear;
use crate::input_file::{MAX_MODEL_BYTES, open_bounded, read_bounded};
use crate::scene::limits::COORDINATE;

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

/// As [`load_obj`], keeping what the file says of materials.
pub fn read_obj(path: &Path) -> Result<ObjRead, ObjError> {
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
    loop {
        line.clear();
        if reader.read_until(b'\n', &mut line).map_err(io)? == 0 {
            break;
        }
        statements
            .read(&line)
            .map_err(|problem| fail(Some(statements.line), problem))?;
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
    /// The number of the line read last, from 1.
    line: usize,
    /// Whether a face named a vertex before the first (index 0, or negative too far back).
    missing_vertex: bool,
    /// The corners of the face being read: vertex, texture coordinate and normal indices, from 0.
    corners: Vec<Corner>,
}

/// An index that names nothing.
const NONE: u32 = u32::MAX;

/// One corner of a face: vertex, texture coordinate and normal indices, from 0.
#[derive(Debug, Clone, Copy)]
struct Corner {
    vertex: u32,
    uv: Option<u32>,
    normal: Option<u32>,
}

/// What a malformed face corner should have been.
const CORNER_FORMS: &str = "a face corner is `v`, `v/vt`, `v//vn` or `v/vt/vn`";

impl Statements {
    /// Reads one line of the file.
    fn read(&mut self, line: &[u8]) -> Result<(), ObjProblem> {
        self.line += 1;
        // A comment in another encoding is no obstacle; a number in one is no number.
        let line = String::from_utf8_lossy(line);
        let mut words = line.split_whitespace();
        let keyword = words.next();
        match keyword {
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
            Some("vt") => {
                let u = words.next().and_then(|w| w.parse::<f32>().ok());
                // `vt u [v [w]]`: v defaults to 0.
                let v = match words.next() {
                    None => Some(0.0),
                    Some(w) => w.parse::<f32>().ok(),
                };
                match (u, v) {
                    (Some(u), Some(v)) if u.is_finite() && v.is_finite() => {
                        self.uvs.push(Vec2::new(u, v));
                    }
                    _ => {
                        return Err(ObjProblem::Malformed(
                            "a texture coordinate is `vt u [v [w]]`, finite numbers",
                        ));
                    }
                }
            }
            Some("f") => self.face(words)?,
            Some(keyword @ ("usemtl" | "mtllib")) => {
                // The name is the rest of the line: it may hold spaces.
                let rest = line.trim_start()[keyword.len()..].trim();
                if keyword == "mtllib" {
                    if !rest.is_empty() {
                        self.libraries.push((self.line, rest.to_string()));
                    }
                } else {
                    self.use_material(rest);
                }
            }
            // Groups, smoothing groups, points and lines: not drawn.
            _ => {}
        }
        Ok(())
    }

    /// Makes `name` the material of the faces that follow (`usemtl` with no name: none).
    fn use_material(&mut self, name: &str) {
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
        let start = self.triangles.len() as u32;
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

    /// Reads the corners of an `f` statement and fans them into triangles.
    fn face(&mut self, words: std::str::SplitWhitespace<'_>) -> Result<(), ObjProblem> {
        self.corners.clear();
        for word in words {
            let mut parts = word.split('/');
            let vertex = parts
                .next()
                .and_then(|v| v.parse::<i64>().ok())
                .ok_or(ObjProblem::Malformed(CORNER_FORMS))?;
            // An index as written, resolved; `None` when absent, `Some(NONE)` when it names
            // nothing read so far.
            let mut index = |count: usize| match parts.next() {
                Some("") | None => Ok(None),
                Some(n) => n
                    .parse::<i64>()
                    .map(|n| {
                        Some(resolve(n, count)).map(|i| if i as usize >= count { NONE } else { i })
                    })
                    .map_err(|_| ObjProblem::Malformed(CORNER_FORMS)),
            };
            // A texture coordinate the file lacks leaves the model without coordinates, as
            // before rastray read them: such files loaded then and still do.
            let uv = index(self.uvs.len())?.filter(|&t| t != NONE);
            let normal = index(self.normals.len())?;
            if normal == Some(NONE) {
                return Err(ObjProblem::Malformed(
                    "a face names a normal the file lacks",
                ));
            }
            let vertex = resolve(vertex, self.positions.len());
            self.missing_vertex |= vertex == NONE;
            self.corners.push(Corner { vertex, uv, normal });
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
        let first = self.corners[0];
        for pair in self.corners[1..].windows(2) {
            let [b, c] = [pair[0], pair[1]];
            self.triangles.push([first.vertex, b.vertex, c.vertex]);
            match (first.normal, b.normal, c.normal) {
                (Some(na), Some(nb), Some(nc)) if !self.corner_without_normal => {
                    self.normal_corners.push([na, nb, nc]);
                }
                _ => {
                    self.corner_without_normal = true;
                    self.normal_corners = Vec::new();
                }
            }
            match (first.uv, b.uv, c.uv) {
                (Some(ta), Some(tb), Some(tc)) if !self.corner_without_uv => {
                    self.uv_corners.push([ta, tb, tc]);
                }
                _ => {
                    self.corner_without_uv = true;
                    self.uv_corners = Vec::new();
                }
            }
        }
        Ok(())
    }

    /// The geometry: unused vertices dropped, corner normals kept when every corner has a
    /// finite, non-zero one, texture coordinates when every corner has one (stored as
    /// (u, 1 − v): the image's top-left is the origin of [`ModelGeometry::corner_uvs`]).
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
        let corner_uvs = (!self.corner_without_uv && !self.uvs.is_empty()).then(|| {
            let uvs = &self.uvs;
            self.uv_corners
                .iter()
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
