//! PLY import (Stanford polygon files): ASCII and binary of either byte order, every scalar
//! type, properties in any order, elements rastray does not read (and their lists) passed
//! over. From the `vertex` element: `x y z`, and when present `nx ny nz`, `red green blue`
//! and texture coordinates (`s t`, `u v` or `texture_u texture_v`); from the `face` element:
//! `vertex_indices` (or `vertex_index`), polygons fanned into triangles, and `texcoord` (u v
//! of each corner, as MeshLab writes), which wins over the vertices' texture coordinates. Colours are sRGB,
//! whatever their type (bytes, or floats in 0..=1), and are decoded to linear. The image a
//! `comment TextureFile NAME` names is recorded, not read.
//!
//! Memory: declared counts are refused before anything is allocated unless they fit in the
//! file (count × the smallest record ≤ bytes left); the file streams through one buffer.

mod ascii;
mod binary;
mod collect;
mod columns;
mod error;
mod fixed;
mod header;
mod plan;
mod scalar;

use std::io::BufReader;
use std::path::{Path, PathBuf};

pub use error::{PlyError, PlyProblem};
pub use header::PlyEncoding;

use self::binary::Role;
use self::collect::Collector;
use self::fixed::{FaceLayout, VertexLayout};
use self::header::{Element, Header, read_header};
use self::plan::{Plan, face_plan, skip_plan, vertex_plan};
use super::byte_source::{ByteSource, ModelSource};
use super::geometry::ModelGeometry;
use super::gltf::ImportWarning;
use super::model_error::{Place, grew};
use super::texture::{Appearance, Sampler, TextureBinding, load_texture};
use crate::memory_budget::triangle_cap;
use crate::memory_budget::{Estimate, OverBudget};
use crate::model_folder::{ModelFolder, ReferenceKind};

/// Most vertices a PLY file may declare: three for each triangle the bound in force lets a
/// scene hold ([`triangle_cap`]).
pub fn max_vertices() -> u64 {
    3 * triangle_cap()
}

/// A PLY file's geometry, how it was written, and the texture it names.
#[derive(Debug, Clone, PartialEq)]
pub struct PlyModel {
    pub geometry: ModelGeometry,
    pub encoding: PlyEncoding,
    /// The image `comment TextureFile NAME` names, as written.
    pub texture: Option<String>,
    /// That image as the model's texture, read from the model's folder, when it could be read.
    pub appearance: Appearance,
    /// Why the named texture is not drawn (missing, outside the folder, not an image).
    pub warnings: Vec<ImportWarning>,
    /// The texture's file, resolved inside the model's folder (read or not, to be watched).
    pub texture_files: Vec<PathBuf>,
}

/// Reads the PLY file at `path`: a regular file of at most [`MAX_MODEL_BYTES`](crate::input_file::MAX_MODEL_BYTES), at most
/// [`max_vertices`] vertices within the scene's coordinate limits and at most
/// [`triangle_cap`] triangles. Errors name the file and the line (header, ASCII body) or byte
/// offset (binary body).
pub fn load_ply(path: &Path) -> Result<PlyModel, PlyError> {
    let fail = |(place, problem)| PlyError {
        path: path.to_path_buf(),
        place,
        problem,
    };
    let io = |e| fail((Place::File, PlyProblem::Io(e)));
    let (mut source, size) = ByteSource::open_model(path).map_err(io)?;
    let header = read_header(&mut source).map_err(fail)?;
    let (vertex, vertex_plan, attributes) =
        vertex_element(&header, size, source.offset()).map_err(fail)?;
    let faces = header
        .elements
        .iter()
        .position(|e| e.name == "face" && e.count > 0);
    let Some(face) = faces else {
        return Err(fail((
            Place::File,
            PlyProblem::PointCloud {
                vertices: header.elements[vertex].count,
            },
        )));
    };
    let (face_plan, face_uvs) = face_plan(&header.elements[face]).ok_or_else(|| {
        fail((
            Place::Line(header.elements[face].line),
            PlyProblem::NoIndexList,
        ))
    })?;
    let mut collector = Collector::new(
        header.elements[vertex].count,
        header.elements[face].count,
        attributes,
        face_uvs,
        triangle_cap(),
    );
    let plans: Vec<(Plan, Role)> = header
        .elements
        .iter()
        .enumerate()
        .map(|(i, element)| {
            if i == vertex {
                (vertex_plan.clone(), Role::Vertex)
            } else if i == face {
                (face_plan.clone(), Role::Face)
            } else {
                (skip_plan(element), Role::Skip)
            }
        })
        .collect();
    read_body(&mut source, size, &header, plans, &mut collector).map_err(fail)?;
    if source.get_ref().limit() == 0 {
        return Err(io(grew()));
    }
    let geometry = collector
        .finish()
        .map_err(|problem| fail((Place::File, problem)))?;
    let (appearance, warnings) = match &header.texture {
        Some(name) => texture_appearance(path, name, geometry.triangles.len() as u64)
            .map_err(|over| fail((Place::File, PlyProblem::OverBudget(over.figures()))))?,
        None => (Appearance::plain(), Vec::new()),
    };
    let texture_files = header
        .texture
        .iter()
        .filter_map(|name| {
            let folder = ModelFolder::of(path).ok()?;
            folder.resolve(name, ReferenceKind::Path).ok()
        })
        .collect();
    Ok(PlyModel {
        texture_files,
        geometry,
        encoding: header.encoding,
        texture: header.texture,
        appearance,
        warnings,
    })
}

/// The appearance of a model of `triangles` whose texture is the file `name` beside the model at
/// `path` (sampled with repeat and trilinear filtering), or a plain one and the warning why not;
/// the figures when the texture would take the model past the memory bound.
fn texture_appearance(
    path: &Path,
    name: &str,
    triangles: u64,
) -> Result<(Appearance, Vec<ImportWarning>), OverBudget> {
    let folder = ModelFolder::of(path);
    let texture = folder
        .as_ref()
        .map_err(|e| format!("texture {name}: {e}"))
        .and_then(|folder| {
            folder.textures().count_model(Estimate {
                triangles,
                objects: 1,
                ..Estimate::default()
            });
            load_texture(folder, name, ReferenceKind::Path).map_err(|e| e.to_string())
        });
    if let Some(over) = folder.ok().and_then(|f| f.textures().refusal()) {
        return Err(over);
    }
    Ok(match texture {
        Ok(texture) => (
            Appearance {
                base_color: Some(TextureBinding {
                    texture,
                    sampler: Sampler::default(),
                }),
                ..Appearance::plain()
            },
            Vec::new(),
        ),
        Err(reason) => (
            Appearance::plain(),
            vec![ImportWarning::ModelTextureUnreadable { reason }],
        ),
    })
}

/// The vertex element's index, plan and attributes, once every element's count is known to
/// fit in the `size − body` bytes of the body.
fn vertex_element(
    header: &Header,
    size: u64,
    body: u64,
) -> Result<(usize, Plan, plan::VertexAttributes), (Place, PlyProblem)> {
    let available = size.saturating_sub(body);
    for element in &header.elements {
        let record = element.min_record_bytes(header.encoding);
        if element.count.saturating_mul(record) > available {
            return Err((
                Place::Line(element.line),
                PlyProblem::CountTooLarge {
                    element: element.name.clone(),
                    count: element.count,
                    record,
                    available,
                },
            ));
        }
    }
    let no_positions = (Place::File, PlyProblem::NoPositions);
    let vertex = header
        .elements
        .iter()
        .position(|e| e.name == "vertex")
        .ok_or(no_positions)?;
    let element: &Element = &header.elements[vertex];
    let (plan, attributes) =
        vertex_plan(element).ok_or((Place::Line(element.line), PlyProblem::NoPositions))?;
    if element.count > max_vertices() {
        return Err((
            Place::Line(element.line),
            PlyProblem::TooManyVertices {
                count: element.count,
                limit: max_vertices(),
            },
        ));
    }
    Ok((vertex, plan, attributes))
}

/// Reads every element of the body in order.
fn read_body(
    source: &mut ModelSource,
    size: u64,
    header: &Header,
    plans: Vec<(Plan, Role)>,
    collector: &mut Collector,
) -> Result<(), (Place, PlyProblem)> {
    match header.encoding {
        PlyEncoding::Ascii => {
            let mut lines = ascii::Lines::new(BufReader::new(source), header.lines);
            for (element, (plan, role)) in header.elements.iter().zip(plans) {
                ascii::read_element(&mut lines, element, &plan, role, collector)?;
            }
        }
        PlyEncoding::BinaryLittleEndian => {
            let elements = header.elements.iter().zip(plans);
            read_binary_body::<false>(source, size, elements, collector)?
        }
        PlyEncoding::BinaryBigEndian => {
            let elements = header.elements.iter().zip(plans);
            read_binary_body::<true>(source, size, elements, collector)?
        }
    }
    Ok(())
}

/// Reads the `elements` of a binary body (each with its plan and role) in order (`BIG`:
/// big-endian), each through the fast paths while they fit, then the general reader.
fn read_binary_body<'h, const BIG: bool>(
    source: &mut ModelSource,
    size: u64,
    elements: impl Iterator<Item = (&'h Element, (Plan, Role))>,
    collector: &mut Collector,
) -> Result<(), (Place, PlyProblem)> {
    for (element, (plan, role)) in elements {
        let first = fast_prefix::<BIG>(source, element, &plan, &role, collector)?;
        binary::read_element::<_, BIG>(source, size, (element, first), &plan, role, collector)?;
    }
    Ok(())
}

/// Reads the records of a vertex or face element that the fast paths of [`fixed`] fit, while
/// they fit; how many are read (the general reader reads the rest).
fn fast_prefix<const BIG: bool>(
    source: &mut ModelSource,
    element: &Element,
    plan: &Plan,
    role: &Role,
    collector: &mut Collector,
) -> Result<u64, (Place, PlyProblem)> {
    match role {
        Role::Vertex => match VertexLayout::of(plan) {
            Some(layout) => fixed::read_vertices::<BIG>(source, element.count, &layout, collector),
            None => Ok(0),
        },
        Role::Face => match FaceLayout::of(plan) {
            Some(layout) => fixed::read_faces::<BIG>(source, element.count, &layout, collector),
            None => Ok(0),
        },
        Role::Skip => Ok(0),
    }
}
