//! One glTF primitive read into welded triangles in the model's space.

use std::collections::HashMap;

use ::gltf::accessor::{DataType, Dimensions};
use ::gltf::mesh::Mode;
use ::gltf::{Accessor, Primitive, Semantic};
use glam::{Mat3, Mat4, Vec2, Vec3, Vec4};

use super::accessor::check_accessor;
use super::error::GltfError;
use super::warning::ImportWarning;
use crate::mesh::texture::UvTransform;
use crate::mesh::{ModelGeometry, unit_or_zero};

/// What became of a primitive.
#[derive(Debug)]
pub enum PrimitiveRead {
    /// Its triangles, moved by the node transform, and `COLOR_0`'s alpha at each triangle's
    /// corners when the colours have alpha and it is below 1 somewhere.
    Triangles(ModelGeometry, Option<Vec<[f32; 3]>>),
    /// Not drawn, and why.
    Skipped(ImportWarning),
}

/// Reads `primitive` (named `label` in messages) from `buffers` and moves it by `transform`,
/// the node's model-space matrix. Triangle strips and fans become triangle lists; a transform
/// that mirrors (negative determinant) has its triangles' winding reversed, so fronts stay fronts.
/// Vertex colours come from `COLOR_0` (RGB or RGBA, float or normalized 8- or 16-bit; linear,
/// as the specification says); their alpha, when below 1 somewhere, is kept per triangle
/// corner for a cut-out (`MASK`) material to multiply in. With `uv_set`, the texture coordinates of
/// `TEXCOORD_n` (float, or normalized 8- or 16-bit) become the corner UVs, moved by the
/// transform; a primitive without that set has none.
pub fn read_primitive(
    primitive: &Primitive,
    label: &str,
    buffers: &[Vec<u8>],
    transform: Mat4,
    uv_set: Option<(u32, UvTransform)>,
) -> Result<PrimitiveRead, GltfError> {
    let mode_name = match primitive.mode() {
        Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan => None,
        Mode::Points => Some("points"),
        Mode::Lines => Some("lines"),
        Mode::LineLoop => Some("a line loop"),
        Mode::LineStrip => Some("a line strip"),
    };
    if let Some(mode) = mode_name {
        return Ok(PrimitiveRead::Skipped(ImportWarning::NotTriangles {
            primitive: label.to_string(),
            mode,
        }));
    }
    let accessor_error =
        |accessor: &Accessor, role: &'static str, reason: String| GltfError::Accessor {
            primitive: label.to_string(),
            accessor: accessor.index(),
            role,
            reason,
        };
    let Some(position_accessor) = primitive.get(&Semantic::Positions) else {
        return Ok(unreadable(label, "it has no POSITION attribute"));
    };
    if position_accessor.view().is_none() && position_accessor.sparse().is_none() {
        return Ok(unreadable(
            label,
            "its positions are in no buffer view (compressed by an extension?)",
        ));
    }
    if position_accessor.data_type() != DataType::F32 || position_accessor.normalized() {
        return Ok(unreadable(
            label,
            "its positions are not 32-bit floats (quantized by an extension?)",
        ));
    }
    check_accessor(
        &position_accessor,
        &[DataType::F32],
        Dimensions::Vec3,
        buffers,
    )
    .map_err(|reason| accessor_error(&position_accessor, "POSITION", reason))?;
    let normal_accessor = primitive.get(&Semantic::Normals);
    if let Some(accessor) = &normal_accessor {
        check_accessor(accessor, &[DataType::F32], Dimensions::Vec3, buffers)
            .map_err(|reason| accessor_error(accessor, "NORMAL", reason))?;
        if accessor.count() != position_accessor.count() {
            return Err(accessor_error(
                accessor,
                "NORMAL",
                format!(
                    "{} normals for {} positions",
                    accessor.count(),
                    position_accessor.count()
                ),
            ));
        }
    }
    let color_accessor = primitive.get(&Semantic::Colors(0));
    if let Some(accessor) = &color_accessor {
        let dimensions = match accessor.dimensions() {
            Dimensions::Vec4 => Dimensions::Vec4,
            _ => Dimensions::Vec3,
        };
        let types = [DataType::F32, DataType::U8, DataType::U16];
        check_accessor(accessor, &types, dimensions, buffers)
            .map_err(|reason| accessor_error(accessor, "COLOR_0", reason))?;
        if accessor.count() != position_accessor.count() {
            return Err(accessor_error(
                accessor,
                "COLOR_0",
                format!(
                    "{} colours for {} positions",
                    accessor.count(),
                    position_accessor.count()
                ),
            ));
        }
    }
    let uv_accessor = uv_set.and_then(|(set, _)| primitive.get(&Semantic::TexCoords(set)));
    if let Some(accessor) = &uv_accessor {
        let types = [DataType::F32, DataType::U8, DataType::U16];
        check_accessor(accessor, &types, Dimensions::Vec2, buffers)
            .map_err(|reason| accessor_error(accessor, "TEXCOORD", reason))?;
        if accessor.count() != position_accessor.count() {
            return Err(accessor_error(
                accessor,
                "TEXCOORD",
                format!(
                    "{} texture coordinates for {} positions",
                    accessor.count(),
                    position_accessor.count()
                ),
            ));
        }
    }
    if let Some(accessor) = primitive.indices() {
        check_accessor(
            &accessor,
            &[DataType::U8, DataType::U16, DataType::U32],
            Dimensions::Scalar,
            buffers,
        )
        .map_err(|reason| accessor_error(&accessor, "indices", reason))?;
    }

    let reader = primitive.reader(|buffer| buffers.get(buffer.index()).map(Vec::as_slice));
    let unread = |accessor: &Accessor, role| {
        accessor_error(accessor, role, "its bytes could not be read".into())
    };
    let positions: Vec<Vec3> = reader
        .read_positions()
        .ok_or_else(|| unread(&position_accessor, "POSITION"))?
        .map(Vec3::from)
        .collect();
    let normals: Option<Vec<Vec3>> = match &normal_accessor {
        Some(accessor) => Some(
            reader
                .read_normals()
                .ok_or_else(|| unread(accessor, "NORMAL"))?
                .map(Vec3::from)
                .collect(),
        ),
        None => None,
    };
    let (colors, alphas): (Option<Vec<Vec3>>, Option<Vec<f32>>) = match &color_accessor {
        Some(accessor) => {
            let colors: Vec<Vec4> = reader
                .read_colors(0)
                .ok_or_else(|| unread(accessor, "COLOR_0"))?
                .into_rgba_f32()
                .map(Vec4::from)
                .collect();
            if colors.iter().any(|c| !c.is_finite()) {
                return Err(accessor_error(
                    accessor,
                    "COLOR_0",
                    "a colour is not a finite number".into(),
                ));
            }
            let colors: Vec<Vec4> = colors
                .iter()
                .map(|c| c.clamp(Vec4::ZERO, Vec4::ONE))
                .collect();
            let alphas = colors
                .iter()
                .any(|c| c.w < 1.0)
                .then(|| colors.iter().map(|c| c.w).collect());
            (Some(colors.iter().map(|c| c.truncate()).collect()), alphas)
        }
        None => (None, None),
    };
    let uvs: Option<Vec<Vec2>> = match (&uv_accessor, uv_set) {
        (Some(accessor), Some((set, uv_transform))) => {
            let uvs: Vec<Vec2> = reader
                .read_tex_coords(set)
                .ok_or_else(|| unread(accessor, "TEXCOORD"))?
                .into_f32()
                .map(|uv| uv_transform.apply(Vec2::from(uv)))
                .collect();
            if uvs.iter().any(|uv| !uv.is_finite()) {
                return Err(accessor_error(
                    accessor,
                    "TEXCOORD",
                    "a texture coordinate is not a finite number".into(),
                ));
            }
            Some(uvs)
        }
        _ => None,
    };
    let order: Vec<u32> = match primitive.indices() {
        Some(accessor) => reader
            .read_indices()
            .ok_or_else(|| unread(&accessor, "indices"))?
            .into_u32()
            .collect(),
        None => (0..positions.len() as u32).collect(),
    };
    if let Some(corner) = order.iter().position(|&i| i as usize >= positions.len()) {
        return Err(GltfError::IndexOutOfRange {
            primitive: label.to_string(),
            place: index_place(primitive.indices().as_ref(), corner),
            vertices: positions.len(),
        });
    }
    let mut triangles = assemble(primitive.mode(), &order);

    let positions: Vec<Vec3> = positions
        .iter()
        .map(|&p| transform.transform_point3(p))
        .collect();
    if positions.iter().any(|p| !p.is_finite()) {
        return Err(GltfError::NonFinite {
            primitive: label.to_string(),
        });
    }
    let linear = Mat3::from_mat4(transform);
    if mirrors(transform) {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    let normals = normals.and_then(|normals| transform_normals(&normals, linear));
    let mut geometry = weld(
        &positions,
        &triangles,
        normals.as_deref(),
        colors.as_deref(),
    );
    geometry.corner_uvs = uvs.map(|uvs| {
        triangles
            .iter()
            .map(|t| t.map(|i| uvs[i as usize]))
            .collect()
    });
    let corner_alphas = alphas.map(|alphas| {
        triangles
            .iter()
            .map(|t| t.map(|i| alphas[i as usize]))
            .collect()
    });
    Ok(PrimitiveRead::Triangles(geometry, corner_alphas))
}

/// `geometry` (a primitive read in its mesh's space) moved by `transform` as [`read_primitive`]
/// moves it: positions moved, winding reversed where the transform mirrors, normals by the
/// inverse transpose (none when one cannot be moved), UVs with their corners.
pub fn placed_geometry(geometry: &ModelGeometry, transform: Mat4) -> ModelGeometry {
    let linear = Mat3::from_mat4(transform);
    let mirrors = mirrors(transform);
    let turn = |t: [u32; 3]| if mirrors { [t[0], t[2], t[1]] } else { t };
    let corner_normals = geometry.corner_normals.as_ref().and_then(|corners| {
        let flat: Vec<Vec3> = corners.iter().flatten().copied().collect();
        let moved = transform_normals(&flat, linear)?;
        Some(
            moved
                .chunks_exact(3)
                .map(|c| turn_values([c[0], c[1], c[2]], mirrors))
                .collect(),
        )
    });
    ModelGeometry {
        positions: geometry
            .positions
            .iter()
            .map(|&p| transform.transform_point3(p))
            .collect(),
        triangles: geometry.triangles.iter().map(|&t| turn(t)).collect(),
        corner_normals,
        colors: geometry.colors.clone(),
        corner_uvs: geometry
            .corner_uvs
            .as_ref()
            .map(|uvs| uvs.iter().map(|&c| turn_values(c, mirrors)).collect()),
    }
}

/// Whether `transform` mirrors (its linear part's determinant is negative): a placed copy then
/// has its triangles' last two corners swapped.
pub fn mirrors(transform: Mat4) -> bool {
    Mat3::from_mat4(transform).determinant() < 0.0
}

/// A triangle's three corner values, the last two swapped when `mirrors`.
fn turn_values<T: Copy>(c: [T; 3], mirrors: bool) -> [T; 3] {
    if mirrors { [c[0], c[2], c[1]] } else { c }
}

/// Where the `corner`-th index of a primitive lies, for an error that must not echo the value
/// itself (it may be any bytes): "accessor 3 (buffer 1, offset 24)", or "the implicit order".
fn index_place(indices: Option<&Accessor>, corner: usize) -> String {
    let Some(accessor) = indices else {
        return "the implicit vertex order".to_string();
    };
    match accessor.view() {
        Some(view) if accessor.sparse().is_none() => {
            let stride = view.stride().unwrap_or(accessor.size());
            let offset = view.offset() + accessor.offset() + corner * stride;
            format!(
                "accessor {} (buffer {}, offset {offset})",
                accessor.index(),
                view.buffer().index()
            )
        }
        _ => format!("accessor {} (element {corner})", accessor.index()),
    }
}

fn unreadable(label: &str, reason: &str) -> PrimitiveRead {
    PrimitiveRead::Skipped(ImportWarning::UnreadablePositions {
        primitive: label.to_string(),
        reason: reason.to_string(),
    })
}

/// Triangles of `order` (vertex indices) drawn in `mode`, as the glTF specification defines
/// them: lists take three at a time (a remainder is ignored); strip triangle i is
/// (i, i+1+i%2, i+2−i%2); fan triangle i is (i+1, i+2, 0).
fn assemble(mode: Mode, order: &[u32]) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (0..order.len().saturating_sub(2))
            .map(|i| [order[i], order[i + 1 + i % 2], order[i + 2 - i % 2]])
            .collect(),
        Mode::TriangleFan => (0..order.len().saturating_sub(2))
            .map(|i| [order[i + 1], order[i + 2], order[0]])
            .collect(),
        _ => order.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect(),
    }
}

/// Normals moved by the inverse transpose of `linear`; `None` when the transform is singular or
/// a normal is zero, not finite or too short to normalize in f32 (normals are then computed from
/// the faces, as for OBJ).
fn transform_normals(normals: &[Vec3], linear: Mat3) -> Option<Vec<Vec3>> {
    if linear.determinant() == 0.0 {
        return None;
    }
    let normal_matrix = linear.inverse().transpose();
    normals
        .iter()
        .map(|&n| {
            if unit_or_zero(n) == Vec3::ZERO {
                return None;
            }
            let moved = unit_or_zero(normal_matrix * n);
            (moved != Vec3::ZERO).then_some(moved)
        })
        .collect()
}

/// Merges vertices at bit-identical positions, so that computed normals smooth across the seams
/// glTF exporters split vertices at; the file's normals, when given, stay with each corner.
/// With `colors`, vertices merge only where their colours are bit-identical too: a seam between
/// two colours stays split (and [`crate::mesh::with_colors_and_normals`] still smooths across it).
fn weld(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    normals: Option<&[Vec3]>,
    colors: Option<&[Vec3]>,
) -> ModelGeometry {
    let mut welded: Vec<Vec3> = Vec::with_capacity(positions.len());
    let mut welded_colors = colors.map(|_| Vec::with_capacity(positions.len()));
    let mut index_of: HashMap<[u32; 6], u32> = HashMap::with_capacity(positions.len());
    let remap: Vec<u32> = (0..positions.len())
        .map(|i| {
            let p = positions[i];
            let color = colors.map_or(Vec3::ZERO, |c| c[i]);
            let mut key = [0; 6];
            key[..3].copy_from_slice(&p.to_array().map(f32::to_bits));
            key[3..].copy_from_slice(&color.to_array().map(f32::to_bits));
            *index_of.entry(key).or_insert_with(|| {
                welded.push(p);
                if let Some(out) = &mut welded_colors {
                    out.push(color);
                }
                welded.len() as u32 - 1
            })
        })
        .collect();
    ModelGeometry {
        positions: welded,
        triangles: triangles
            .iter()
            .map(|t| t.map(|i| remap[i as usize]))
            .collect(),
        corner_normals: normals.map(|normals| {
            triangles
                .iter()
                .map(|t| t.map(|i| normals[i as usize]))
                .collect()
        }),
        colors: welded_colors,
        corner_uvs: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strips_alternate_winding_and_fans_turn_about_the_first_vertex() {
        let order = [0, 1, 2, 3, 4];
        assert_eq!(
            assemble(Mode::TriangleStrip, &order),
            vec![[0, 1, 2], [1, 3, 2], [2, 3, 4]]
        );
        assert_eq!(
            assemble(Mode::TriangleFan, &order),
            vec![[1, 2, 0], [2, 3, 0], [3, 4, 0]]
        );
        assert_eq!(assemble(Mode::Triangles, &order), vec![[0, 1, 2]]);
        assert!(assemble(Mode::TriangleStrip, &[0, 1]).is_empty());
    }

    #[test]
    fn welding_merges_equal_positions_and_keeps_corner_normals() {
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X, Vec3::Y, Vec3::ONE];
        let normals = [Vec3::Z, Vec3::Z, Vec3::Z, Vec3::X, Vec3::X, Vec3::X];
        let geometry = weld(&positions, &[[0, 1, 2], [3, 5, 4]], Some(&normals), None);
        assert_eq!(geometry.positions.len(), 4);
        assert_eq!(geometry.triangles, vec![[0, 1, 2], [1, 3, 2]]);
        let corners = geometry.corner_normals.expect("normals");
        assert_eq!(corners[1], [Vec3::X; 3]);
    }

    #[test]
    fn welding_keeps_a_seam_between_two_colours_split() {
        // Two triangles share the edge X–Y; the second colours it blue where the first has it
        // red: the shared positions must stay two vertices each, and the red ones merge.
        let positions = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X, Vec3::Y, Vec3::ONE];
        let (red, blue) = (Vec3::X, Vec3::Z);
        let colors = [red, red, red, blue, blue, blue];
        let geometry = weld(&positions, &[[0, 1, 2], [3, 5, 4]], None, Some(&colors));
        assert_eq!(geometry.positions.len(), 6);
        assert_eq!(geometry.colors.as_deref(), Some(&colors[..]));
        let same = [red, red, red, red, red, blue];
        let geometry = weld(&positions, &[[0, 1, 2], [3, 5, 4]], None, Some(&same));
        assert_eq!(geometry.positions.len(), 4);
        assert_eq!(geometry.triangles, vec![[0, 1, 2], [1, 3, 2]]);
        assert_eq!(geometry.colors, Some(vec![red, red, red, blue]));
    }

    #[test]
    fn normals_follow_a_non_uniform_scale_by_the_inverse_transpose() {
        // A 45° slope scaled 2× along X: its normal tilts toward the steeper side.
        let n = Vec3::new(1.0, 1.0, 0.0).normalize();
        let moved = transform_normals(&[n], Mat3::from_diagonal(Vec3::new(2.0, 1.0, 1.0)))
            .expect("invertible");
        assert!(moved[0].distance(Vec3::new(0.5, 1.0, 0.0).normalize()) < 1e-6);
        assert!(transform_normals(&[n], Mat3::from_diagonal(Vec3::new(0.0, 1.0, 1.0))).is_none());
        assert!(transform_normals(&[Vec3::ZERO], Mat3::IDENTITY).is_none());
        // Its squared length is subnormal: normalized, it would come out 1.13 long.
        let tiny = Vec3::new(2e-22, 0.0, 0.0);
        assert!(transform_normals(&[tiny], Mat3::IDENTITY).is_none());
        assert!(transform_normals(&[Vec3::new(1e-19, 0.0, 0.0)], Mat3::IDENTITY).is_none());
    }
}
