//! What each property of an element is read for: a slot of the vertex record (position,
//! normal, colour, texture coordinate), a face's vertex indices, or nothing (skipped).

use super::header::{Element, PropertyType};
use super::scalar::Scalar;

/// The vertex values rastray reads, by slot.
pub const X: usize = 0;
pub const NX: usize = 3;
pub const RED: usize = 6;
pub const U: usize = 9;
/// Slots in a vertex record: x y z, nx ny nz, red green blue, u v.
pub const SLOTS: usize = 11;

/// What a property's values become.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Read past.
    Skip,
    /// The vertex value of this slot.
    Slot(usize),
    /// The face's vertex indices.
    Indices,
    /// The face's texture coordinates, u and v for each corner in turn (`texcoord`).
    TexCoords,
}

/// The lists of one face record.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FaceLists {
    /// Vertex indices, as read.
    pub indices: Vec<f64>,
    /// u, v of each corner, as read (empty when the element has none).
    pub uvs: Vec<f64>,
}

impl FaceLists {
    /// The list `target` names, if it names one.
    pub fn of(&mut self, target: Target) -> Option<&mut Vec<f64>> {
        match target {
            Target::Indices => Some(&mut self.indices),
            Target::TexCoords => Some(&mut self.uvs),
            Target::Skip | Target::Slot(_) => None,
        }
    }
}

/// How to read one element: each property's type and what it is read for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Plan {
    pub properties: Vec<(PropertyType, Target)>,
}

/// What the vertex element gives beyond positions, and the type colours are written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct VertexAttributes {
    pub normals: bool,
    /// The type of `red` when red, green and blue are all there.
    pub colors: Option<Scalar>,
    pub uvs: bool,
}

/// Names of the texture coordinate pairs, in order of preference.
const UV_NAMES: [(&str, &str); 4] = [
    ("s", "t"),
    ("u", "v"),
    ("texture_u", "texture_v"),
    ("texture_s", "texture_t"),
];

/// The plan of the vertex element and what it gives; `None` when it lacks x, y or z.
pub fn vertex_plan(element: &Element) -> Option<(Plan, VertexAttributes)> {
    let mut targets = vec![Target::Skip; element.properties.len()];
    // Marks the properties `names` (all scalars) as the slots from `first_slot` on; the type
    // of the first, or `None` when one is missing.
    let mut set = |names: &[&str], first_slot: usize| -> Option<Scalar> {
        let found: Vec<(usize, Scalar)> = names
            .iter()
            .map(|n| {
                let i = element.find(n)?;
                match element.properties[i].ty {
                    PropertyType::Scalar(s) => Some((i, s)),
                    PropertyType::List { .. } => None,
                }
            })
            .collect::<Option<_>>()?;
        for (k, &(i, _)) in found.iter().enumerate() {
            targets[i] = Target::Slot(first_slot + k);
        }
        found.first().map(|&(_, s)| s)
    };
    set(&["x", "y", "z"], X)?;
    let normals = set(&["nx", "ny", "nz"], NX).is_some();
    let colors = set(&["red", "green", "blue"], RED)
        .or_else(|| set(&["diffuse_red", "diffuse_green", "diffuse_blue"], RED));
    let uvs = UV_NAMES.iter().any(|(u, v)| set(&[u, v], U).is_some());
    Some((
        plan(element, targets),
        VertexAttributes {
            normals,
            colors,
            uvs,
        },
    ))
}

/// The plan of the face element, and whether it gives texture coordinates per corner (a
/// `texcoord` list, as MeshLab writes); `None` when it has no list of vertex indices.
pub fn face_plan(element: &Element) -> Option<(Plan, bool)> {
    let list = ["vertex_indices", "vertex_index"].iter().find_map(|name| {
        element
            .find(name)
            .filter(|&i| matches!(element.properties[i].ty, PropertyType::List { .. }))
    })?;
    let mut targets = vec![Target::Skip; element.properties.len()];
    targets[list] = Target::Indices;
    let uvs = element
        .find("texcoord")
        .filter(|&i| matches!(element.properties[i].ty, PropertyType::List { .. }));
    if let Some(i) = uvs {
        targets[i] = Target::TexCoords;
    }
    Some((plan(element, targets), uvs.is_some()))
}

/// The plan that reads past every property of `element`.
pub fn skip_plan(element: &Element) -> Plan {
    plan(element, vec![Target::Skip; element.properties.len()])
}

fn plan(element: &Element, targets: Vec<Target>) -> Plan {
    Plan {
        properties: element
            .properties
            .iter()
            .map(|p| p.ty)
            .zip(targets)
            .collect(),
    }
}
