//! Scene objects: a shape, where it sits, how it is turned and what it is made of.
//!
//! In a file an object is one flat `[[object]]` table with a `type` key; [`ObjectRecord`] is that
//! table and converting it to [`Object`] checks that each key belongs to the type.

use std::path::PathBuf;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::material::Material;
use super::material_source::MaterialSource;
use super::up_axis::UpAxis;
use super::vector::optional_vec3;

/// The geometry of an object. Sizes are in world units.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Regular icosahedron inscribed in a sphere of `radius` > 0; `subdivisions` ≤ 8 splits each
    /// face in four per level, pushing new vertices onto the sphere (20·4^k faces).
    Icosahedron {
        center: Vec3,
        radius: f32,
        subdivisions: u32,
    },
    /// Axis-aligned (before rotation) box, `size` = [width, height, depth] > 0; each face is a
    /// `segments`×`segments` grid of quads (segments ≥ 1).
    Box {
        center: Vec3,
        size: Vec3,
        segments: u32,
    },
    /// Right triangular prism: an isosceles triangle of base `size.x` and height `size.y` in the XY
    /// plane, extruded `size.z` along Z, centred on its bounding box; faces split into
    /// `segments`×`segments` grids.
    Prism {
        center: Vec3,
        size: Vec3,
        segments: u32,
    },
    /// A triangle mesh from a model file (OBJ, STL, PLY, glTF; path relative to the scene
    /// file). The file is turned so that its `up` axis becomes +Y, and the model's bounding-box
    /// centre is placed at `position`, after scaling by `scale` > 0. `materials` says whether
    /// the file's materials and textures or the object's own material draw it.
    Mesh {
        path: PathBuf,
        position: Vec3,
        scale: f32,
        up: UpAxis,
        materials: MaterialSource,
    },
}

/// The closed set of shape types, as written in the `type` key.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeKind {
    Icosahedron,
    Box,
    Prism,
    Mesh,
}

impl ShapeKind {
    /// Every kind, in menu order.
    pub const ALL: [ShapeKind; 4] = [
        ShapeKind::Icosahedron,
        ShapeKind::Box,
        ShapeKind::Prism,
        ShapeKind::Mesh,
    ];

    /// The word used in files and in the editor.
    pub fn name(self) -> &'static str {
        match self {
            ShapeKind::Icosahedron => "icosahedron",
            ShapeKind::Box => "box",
            ShapeKind::Prism => "prism",
            ShapeKind::Mesh => "mesh",
        }
    }
}

impl Shape {
    /// The kind of this shape.
    pub fn kind(&self) -> ShapeKind {
        match self {
            Shape::Icosahedron { .. } => ShapeKind::Icosahedron,
            Shape::Box { .. } => ShapeKind::Box,
            Shape::Prism { .. } => ShapeKind::Prism,
            Shape::Mesh { .. } => ShapeKind::Mesh,
        }
    }

    /// The point the object is placed at (centre or mesh position), world units.
    pub fn center(&self) -> Vec3 {
        match self {
            Shape::Icosahedron { center, .. }
            | Shape::Box { center, .. }
            | Shape::Prism { center, .. } => *center,
            Shape::Mesh { position, .. } => *position,
        }
    }

    /// Moves the object so that [`Shape::center`] becomes `to`.
    pub fn set_center(&mut self, to: Vec3) {
        match self {
            Shape::Icosahedron { center, .. }
            | Shape::Box { center, .. }
            | Shape::Prism { center, .. } => *center = to,
            Shape::Mesh { position, .. } => *position = to,
        }
    }

    /// Whether an object of this shape is smooth when the scene does not say: meshes are, but
    /// for STL files (named `.stl`, any case), whose faces are usually a CAD model's flat
    /// facets; the other shapes are flat.
    pub fn smooth_by_default(&self) -> bool {
        match self {
            Shape::Mesh { path, .. } => !path
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("stl")),
            _ => false,
        }
    }

    /// A sensible unit-sized shape of `kind` at `center` (meshes need a path).
    pub fn new(kind: ShapeKind, center: Vec3, path: PathBuf) -> Shape {
        match kind {
            ShapeKind::Icosahedron => Shape::Icosahedron {
                center,
                radius: 1.0,
                subdivisions: 0,
            },
            ShapeKind::Box => Shape::Box {
                center,
                size: Vec3::ONE,
                segments: 1,
            },
            ShapeKind::Prism => Shape::Prism {
                center,
                size: Vec3::ONE,
                segments: 1,
            },
            ShapeKind::Mesh => Shape::Mesh {
                path,
                position: center,
                scale: 1.0,
                up: UpAxis::Y,
                materials: MaterialSource::File,
            },
        }
    }
}

/// One object of the scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ObjectRecord", into = "ObjectRecord")]
pub struct Object {
    /// Optional label shown in the editor.
    pub name: Option<String>,
    /// The geometry.
    pub shape: Shape,
    /// Euler angles in degrees about the object's own centre, applied X, then Y, then Z.
    pub rotation: Vec3,
    /// Surface material.
    pub material: Material,
    /// Smooth shading: average normals of adjacent faces meeting at less than the crease angle.
    /// By default meshes are smooth, but for an STL file (named `.stl`), and other shapes flat.
    pub smooth: bool,
}

impl Object {
    /// A new object with the default material and no rotation.
    pub fn new(shape: Shape) -> Object {
        let smooth = shape.smooth_by_default();
        Object {
            name: None,
            shape,
            rotation: Vec3::ZERO,
            material: Material::default(),
            smooth,
        }
    }

    /// The name to show: the given name, or the shape's kind.
    pub fn label(&self) -> &str {
        self.name.as_deref().unwrap_or(self.shape.kind().name())
    }
}

/// The flat `[[object]]` table as written in a file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectRecord {
    #[serde(rename = "type")]
    kind: ShapeKind,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    #[serde(
        default,
        deserialize_with = "optional_vec3",
        skip_serializing_if = "Option::is_none"
    )]
    center: Option<Vec3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    radius: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    subdivisions: Option<u32>,
    #[serde(
        default,
        deserialize_with = "optional_vec3",
        skip_serializing_if = "Option::is_none"
    )]
    size: Option<Vec3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    segments: Option<u32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    path: Option<PathBuf>,
    #[serde(
        default,
        deserialize_with = "optional_vec3",
        skip_serializing_if = "Option::is_none"
    )]
    position: Option<Vec3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    scale: Option<f32>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    up: Option<UpAxis>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    materials: Option<MaterialSource>,
    #[serde(
        default,
        deserialize_with = "optional_vec3",
        skip_serializing_if = "Option::is_none"
    )]
    rotation: Option<Vec3>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    smooth: Option<bool>,
    #[serde(default)]
    material: Material,
}

/// An `[[object]]` table whose keys do not fit its `type`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ObjectError {
    /// A key of another shape type.
    #[error("key `{key}` does not apply to an object of type \"{}\"", kind.name())]
    Stray { key: &'static str, kind: ShapeKind },
    /// A key the type cannot do without.
    #[error("an object of type \"{}\" needs `{key}`", kind.name())]
    Missing { key: &'static str, kind: ShapeKind },
}

impl TryFrom<ObjectRecord> for Object {
    type Error = ObjectError;

    fn try_from(r: ObjectRecord) -> Result<Object, ObjectError> {
        let kind = r.kind;
        let stray = |key: &'static str, present: bool| -> Result<(), ObjectError> {
            if present {
                Err(ObjectError::Stray { key, kind })
            } else {
                Ok(())
            }
        };
        let required = |key: &'static str| ObjectError::Missing { key, kind };
        let shape = match kind {
            ShapeKind::Icosahedron => {
                stray("size", r.size.is_some())?;
                stray("segments", r.segments.is_some())?;
                stray("path", r.path.is_some())?;
                stray("position", r.position.is_some())?;
                stray("scale", r.scale.is_some())?;
                stray("up", r.up.is_some())?;
                stray("materials", r.materials.is_some())?;
                Shape::Icosahedron {
                    center: r.center.unwrap_or(Vec3::ZERO),
                    radius: r.radius.ok_or_else(|| required("radius"))?,
                    subdivisions: r.subdivisions.unwrap_or(0),
                }
            }
            ShapeKind::Box | ShapeKind::Prism => {
                stray("radius", r.radius.is_some())?;
                stray("subdivisions", r.subdivisions.is_some())?;
                stray("path", r.path.is_some())?;
                stray("position", r.position.is_some())?;
                stray("scale", r.scale.is_some())?;
                stray("up", r.up.is_some())?;
                stray("materials", r.materials.is_some())?;
                let center = r.center.unwrap_or(Vec3::ZERO);
                let size = r.size.ok_or_else(|| required("size"))?;
                let segments = r.segments.unwrap_or(1);
                if kind == ShapeKind::Box {
                    Shape::Box {
                        center,
                        size,
                        segments,
                    }
                } else {
                    Shape::Prism {
                        center,
                        size,
                        segments,
                    }
                }
            }
            ShapeKind::Mesh => {
                stray("center", r.center.is_some())?;
                stray("radius", r.radius.is_some())?;
                stray("subdivisions", r.subdivisions.is_some())?;
                stray("size", r.size.is_some())?;
                stray("segments", r.segments.is_some())?;
                Shape::Mesh {
                    path: r.path.ok_or_else(|| required("path"))?,
                    position: r.position.unwrap_or(Vec3::ZERO),
                    scale: r.scale.unwrap_or(1.0),
                    up: r.up.unwrap_or_default(),
                    materials: r
                        .materials
                        .unwrap_or_else(|| MaterialSource::implied_by(&r.material)),
                }
            }
        };
        let smooth = r.smooth.unwrap_or_else(|| shape.smooth_by_default());
        Ok(Object {
            name: r.name,
            shape,
            rotation: r.rotation.unwrap_or(Vec3::ZERO),
            material: r.material,
            smooth,
        })
    }
}

impl From<Object> for ObjectRecord {
    fn from(o: Object) -> ObjectRecord {
        let mut r = ObjectRecord {
            kind: o.shape.kind(),
            name: o.name,
            center: None,
            radius: None,
            subdivisions: None,
            size: None,
            segments: None,
            path: None,
            position: None,
            scale: None,
            up: None,
            materials: None,
            rotation: (o.rotation != Vec3::ZERO).then_some(o.rotation),
            smooth: Some(o.smooth),
            material: o.material,
        };
        match o.shape {
            Shape::Icosahedron {
                center,
                radius,
                subdivisions,
            } => {
                r.center = Some(center);
                r.radius = Some(radius);
                r.subdivisions = Some(subdivisions);
            }
            Shape::Box {
                center,
                size,
                segments,
            }
            | Shape::Prism {
                center,
                size,
                segments,
            } => {
                r.center = Some(center);
                r.size = Some(size);
                r.segments = Some(segments);
            }
            Shape::Mesh {
                path,
                position,
                scale,
                up,
                materials,
            } => {
                r.path = Some(path);
                r.position = Some(position);
                r.scale = Some(scale);
                r.up = (up != UpAxis::default()).then_some(up);
                r.materials = Some(materials);
            }
        }
        r
    }
}
