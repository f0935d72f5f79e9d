//! Scenes that load and render, but probably not as their author meant: no lights, an object
//! behind the camera, triangles without area. The command line prints these on stderr and the
//! editor shows new ones on its status line.

use std::fmt;

use glam::Vec3;

use crate::mesh::{Mesh, Sphere};
use crate::scene::{Camera, Scene};
use crate::world::World;

/// Something legal in a scene that is probably a mistake.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Warning {
    /// No point light: only the ambient term lights the scene.
    NoLights,
    /// Every vertex of the object lies behind the plane through the camera, facing its view.
    BehindCamera(ObjectName),
    /// `count` of the object's `total` triangles have zero area: they cover nothing.
    ZeroAreaTriangles {
        object: ObjectName,
        count: usize,
        total: usize,
    },
    /// Every triangle of the object has zero area, so it shows nothing.
    NoArea(ObjectName),
}

/// An object as a warning names it: its place in the file and its label.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjectName {
    /// Index into the scene's objects, as in `object[2]`.
    pub index: usize,
    /// The object's name, or its shape's kind.
    pub label: String,
}

impl fmt::Display for ObjectName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "object[{}] \"{}\"", self.index, self.label)
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Warning::NoLights => {
                f.write_str("the scene has no lights; only ambient light will show")
            }
            Warning::BehindCamera(object) => {
                write!(
                    f,
                    "{object} is entirely behind the camera and will not show"
                )
            }
            Warning::ZeroAreaTriangles {
                object,
                count,
                total,
            } => write!(
                f,
                "{object}: {count} of its {total} triangles have zero area and will not show"
            ),
            Warning::NoArea(object) => write!(
                f,
                "{object}: every triangle has zero area; the object will not show"
            ),
        }
    }
}

/// Most warnings of one kind printed in full; the rest are counted in one line.
pub const WARNINGS_SHOWN_PER_KIND: usize = 5;

impl Warning {
    /// Which kind of warning this is, as a small number (warnings of one kind are summarised
    /// together).
    fn kind(&self) -> usize {
        match self {
            Warning::NoLights => 0,
            Warning::BehindCamera(_) => 1,
            Warning::ZeroAreaTriangles { .. } => 2,
            Warning::NoArea(_) => 3,
        }
    }

    /// The line that stands for `more` further warnings of this one's kind.
    fn more(&self, more: usize) -> String {
        let objects = if more == 1 { "object" } else { "objects" };
        match self {
            Warning::NoLights => format!("and {more} more such warnings"),
            Warning::BehindCamera(_) => {
                format!("and {more} more {objects} entirely behind the camera")
            }
            Warning::ZeroAreaTriangles { .. } => {
                format!("and {more} more {objects} with zero-area triangles")
            }
            Warning::NoArea(_) => format!("and {more} more {objects} with no area at all"),
        }
    }
}

/// `warnings` as lines to print: of each kind, the first `shown` in full and then one line that
/// counts the rest ("and 52790 more objects entirely behind the camera"), so that a scene of
/// many objects gives a few lines, not one per object. Order is kept within a kind.
pub fn summarised(warnings: &[Warning], shown: usize) -> Vec<String> {
    let mut counts = [0usize; 4];
    let mut lines = Vec::new();
    for warning in warnings {
        let count = &mut counts[warning.kind()];
        *count += 1;
        if *count <= shown {
            lines.push(warning.to_string());
        }
    }
    for (kind, &count) in counts.iter().enumerate() {
        if count > shown
            && let Some(first) = warnings.iter().find(|w| w.kind() == kind)
        {
            lines.push(first.more(count - shown));
        }
    }
    lines
}

/// The warnings for `world`, built from `scene`, seen through `camera`, in scene order: first
/// the scene-wide ones, then each object's.
pub fn warnings(scene: &Scene, camera: &Camera, world: &World) -> Vec<Warning> {
    let mut found = Vec::new();
    if world.lights.is_empty() {
        found.push(Warning::NoLights);
    }
    let forward = (camera.target - camera.position).normalize();
    for (index, (object, built)) in scene.objects.iter().zip(&world.objects).enumerate() {
        let name = || ObjectName {
            index,
            label: object.label().to_string(),
        };
        // An instance's triangles are its shared mesh's: an invertible map keeps zero areas zero
        // and the others not.
        let total = built.local_mesh().triangle_count();
        let count = built.local_mesh().zero_area_triangles();
        if count == total {
            found.push(Warning::NoArea(name()));
            continue;
        }
        if count > 0 {
            found.push(Warning::ZeroAreaTriangles {
                object: name(),
                count,
                total,
            });
        }
        if built.instance.is_none() && behind(&built.mesh, built.bounds, camera.position, forward) {
            found.push(Warning::BehindCamera(name()));
        }
    }
    found
}

/// Whether every vertex of `mesh`, inside `sphere`, lies on or behind the plane through `eye`
/// facing unit `forward`.
fn behind(mesh: &Mesh, sphere: Sphere, eye: Vec3, forward: Vec3) -> bool {
    let depth = (sphere.center - eye).dot(forward);
    if depth + sphere.radius <= 0.0 {
        return true;
    }
    if depth - sphere.radius > 0.0 {
        return false;
    }
    mesh.positions
        .iter()
        .all(|&p| (p - eye).dot(forward) <= 0.0)
}
