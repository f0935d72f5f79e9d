//! OBJ import through tobj: polygons triangulated, every group merged into one face list.

use std::io::{BufRead, Read};
use std::path::Path;

use glam::Vec3;
use tobj::LoadError;

use super::obj_error::{ObjError, ObjProblem};

use super::geometry::ModelGeometry;

/// An OBJ file's geometry: every group of the file merged into one face list.
pub type ObjModel = ModelGeometry;

/// Reads the OBJ file at `path`. Errors name the file, and the line where there is one.
pub fn load_obj(path: &Path) -> Result<ObjModel, ObjError> {
    let fail = |line, problem| ObjError {
        path: path.to_path_buf(),
        line,
        problem,
    };
    let bytes = std::fs::read(path).map_err(|e| fail(None, ObjProblem::Io(e)))?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: false,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = LineCounter {
        text: &bytes,
        consumed: 0,
    };
    let loaded = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(LoadError::MaterialParseError)
    });
    let (models, _materials) = loaded.map_err(|error| match error {
        // Indices are checked when a group ends, lines after the face that names them.
        LoadError::FaceVertexOutOfBounds => match missing_vertex(&bytes) {
            Some((line, index, count)) => {
                fail(Some(line), ObjProblem::MissingVertex { index, count })
            }
            None => fail(None, ObjProblem::Malformed(error)),
        },
        LoadError::FaceTexCoordOutOfBounds
        | LoadError::FaceNormalOutOfBounds
        | LoadError::FaceColorOutOfBounds => fail(None, ObjProblem::Malformed(error)),
        _ => fail(Some(reader.line()), ObjProblem::Malformed(error)),
    })?;
    if let Some((line, vertex)) = non_finite_vertex(&bytes) {
        return Err(fail(Some(line), ObjProblem::NonFiniteVertex { vertex }));
    }

    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    let mut corner_normals = Some(Vec::new());
    for model in &models {
        let m = &model.mesh;
        let base = positions.len() as u32;
        let count = m.positions.len() / 3;
        for p in m.positions.chunks_exact(3) {
            let v = Vec3::new(p[0], p[1], p[2]);
            if !v.is_finite() {
                // Found above with its line; this guards the statements the scan cannot read.
                return Err(fail(
                    None,
                    ObjProblem::Malformed(LoadError::PositionParseError),
                ));
            }
            positions.push(v);
        }
        if m.indices.iter().any(|&i| i as usize >= count) {
            return Err(fail(
                None,
                ObjProblem::Malformed(LoadError::FaceVertexOutOfBounds),
            ));
        }
        triangles.extend(
            m.indices
                .chunks_exact(3)
                .map(|t| [t[0] + base, t[1] + base, t[2] + base]),
        );
        let has_normals = m.normal_indices.len() == m.indices.len() && !m.normals.is_empty();
        match (&mut corner_normals, has_normals) {
            (Some(list), true) => {
                let normal = |i: u32| -> Vec3 {
                    let i = i as usize * 3;
                    m.normals
                        .get(i..i + 3)
                        .map(|n| Vec3::new(n[0], n[1], n[2]).normalize_or_zero())
                        .unwrap_or(Vec3::ZERO)
                };
                list.extend(
                    m.normal_indices
                        .chunks_exact(3)
                        .map(|t| [normal(t[0]), normal(t[1]), normal(t[2])]),
                );
            }
            _ => corner_normals = None,
        }
    }
    if triangles.is_empty() {
        return Err(fail(None, ObjProblem::NoFaces));
    }
    let corner_normals = corner_normals.filter(|list| {
        list.iter()
            .flatten()
            .all(|n| n.is_finite() && *n != Vec3::ZERO)
    });
    Ok(ObjModel {
        positions,
        triangles,
        corner_normals,
    })
}

/// The OBJ text handed to tobj, counting how far tobj has read: when it refuses a statement,
/// the statement is on the last line it consumed.
struct LineCounter<'a> {
    text: &'a [u8],
    consumed: usize,
}

impl LineCounter<'_> {
    /// 1-based number of the last line read.
    fn line(&self) -> usize {
        let read = &self.text[..self.consumed.saturating_sub(1)];
        read.iter().filter(|&&b| b == b'\n').count() + 1
    }
}

impl Read for LineCounter<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = (&self.text[self.consumed..]).read(buf)?;
        self.consumed += n;
        Ok(n)
    }
}

impl BufRead for LineCounter<'_> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        Ok(&self.text[self.consumed..])
    }

    fn consume(&mut self, amount: usize) {
        self.consumed = (self.consumed + amount).min(self.text.len());
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

/// The line and number (from 1) of the first vertex with a NaN or infinite coordinate.
fn non_finite_vertex(text: &[u8]) -> Option<(usize, usize)> {
    statements(text)
        .filter(|(_, keyword, _)| *keyword == "v")
        .enumerate()
        .find(|(_, (_, _, coordinates))| {
            coordinates
                .clone()
                .take(3)
                .any(|c| c.parse::<f32>().is_ok_and(|x| !x.is_finite()))
        })
        .map(|(k, (line, _, _))| (line, k + 1))
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
