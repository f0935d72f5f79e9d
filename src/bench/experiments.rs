//! The scenes of the study's two experiments, generated point by point.
//!
//! 1. **Area sweep**: six objects with few faces (two icosahedra, two boxes, two prisms, 140 faces),
//!    each scaled about its own centre so that the total face area grows from about 0.1 Mpx to
//!    8.5 Mpx, past the study's 4.08 Mpx. The camera stays outside every object.
//! 2. **Face sweep**: an icosahedron, a box and a prism whose faces are subdivided (icosahedron
//!    subdivisions k, box and prism `segments` s: 20·4^k + 12s² + 8s² faces, from 40 to about a
//!    million) and scaled so that the total face area stays at 2 Mpx.
//!
//! Areas are stated for a 1920×1080 image and scale with the image's pixel count, so that at any
//! size the scenes look the same and cover the same fraction of the image.

use std::fmt;
use std::path::Path;

use glam::Vec3;

use super::area::total_face_area;
use crate::render::{Size, View};
use crate::scene::{Camera, Light, Material, Object, Scene, Shape};
use crate::world::World;

/// Pixels of the image size the study's areas refer to (1920×1080).
pub const REFERENCE_PIXELS: f64 = 1920.0 * 1080.0;

/// Experiment 1 targets, Mpx of total face area at 1920×1080.
const AREA_TARGETS: [f64; 14] = [
    0.1, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0, 7.0, 8.5,
];
/// Experiment 1 targets in quick mode.
const AREA_TARGETS_QUICK: [f64; 4] = [0.1, 2.5, 5.0, 8.5];
/// Experiment 2's constant total face area, Mpx at 1920×1080.
const FACES_AREA: f64 = 2.0;
/// Experiment 2 steps: (icosahedron subdivisions k, box and prism segments s).
const FACE_STEPS: [(u32, u32); 9] = [
    (0, 1),
    (1, 2),
    (2, 4),
    (3, 8),
    (4, 16),
    (5, 32),
    (6, 64),
    (7, 128),
    (7, 192),
];
/// Experiment 2 steps in quick mode.
const FACE_STEPS_QUICK: [(u32, u32); 4] = [(0, 1), (3, 8), (5, 32), (7, 192)];
/// Relative tolerance of the scale search on the target area.
const AREA_TOLERANCE: f64 = 0.002;

/// The study's two experiments: a closed set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Experiment {
    /// Few faces, growing total face area.
    Area,
    /// Growing face count, constant total face area.
    Faces,
}

impl Experiment {
    /// Both, in the study's order.
    pub const ALL: [Experiment; 2] = [Experiment::Area, Experiment::Faces];

    /// The word used in the CSV file.
    pub fn name(self) -> &'static str {
        match self {
            Experiment::Area => "area",
            Experiment::Faces => "faces",
        }
    }

    /// Parses [`Experiment::name`].
    pub fn from_name(name: &str) -> Option<Experiment> {
        Experiment::ALL.into_iter().find(|e| e.name() == name)
    }

    /// A one-line description for reports.
    pub fn title(self) -> &'static str {
        match self {
            Experiment::Area => "Experiment 1: few faces, growing total face area",
            Experiment::Faces => "Experiment 2: growing face count, constant total face area",
        }
    }
}

impl fmt::Display for Experiment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One scene of a sweep.
#[derive(Debug, Clone)]
pub struct Point {
    pub experiment: Experiment,
    /// What was varied, for display ("scale 2.31", "k=3, segments 8").
    pub label: String,
    pub scene: Scene,
}

/// The scenes of `experiment` for an image of `size`; `quick` keeps fewer points.
pub fn points(experiment: Experiment, size: Size, quick: bool) -> Vec<Point> {
    let pixels = size.width as f64 * size.height as f64;
    let to_pixels = |mpx: f64| mpx * 1.0e6 * pixels / REFERENCE_PIXELS;
    match experiment {
        Experiment::Area => {
            let targets: &[f64] = if quick {
                &AREA_TARGETS_QUICK
            } else {
                &AREA_TARGETS
            };
            let limit = area_scene_max_scale();
            targets
                .iter()
                .map(|&mpx| {
                    let scale = calibrate(area_scene, limit, to_pixels(mpx), size);
                    Point {
                        experiment,
                        label: format!("scale {scale:.3}"),
                        scene: area_scene(scale),
                    }
                })
                .collect()
        }
        Experiment::Faces => {
            let steps: &[(u32, u32)] = if quick {
                &FACE_STEPS_QUICK
            } else {
                &FACE_STEPS
            };
            steps
                .iter()
                .map(|&(k, s)| faces_point(k, s, size))
                .collect()
        }
    }
}

/// The experiment 2 scene with subdivisions `k` and segments `s`, scaled to the experiment's
/// constant total face area on an image of `size`.
pub fn faces_point(k: u32, s: u32, size: Size) -> Point {
    let pixels = size.width as f64 * size.height as f64;
    let target = FACES_AREA * 1.0e6 * pixels / REFERENCE_PIXELS;
    // Search the scale on a coarse stand-in: box and prism areas do not depend on the segments,
    // and an icosahedron's barely changes past 3 subdivisions.
    let proxy = |scale| faces_scene(k.min(3), s.min(2), scale);
    let scale = calibrate(proxy, 4.0, target, size);
    Point {
        experiment: Experiment::Faces,
        label: format!("k={k}, segments {s}"),
        scene: faces_scene(k, s, scale),
    }
}

/// Faces of the experiment 2 scene with subdivisions `k` and segments `s`: 20·4^k + 12s² + 8s².
pub fn faces_scene_face_count(k: u32, s: u32) -> usize {
    20 * 4usize.pow(k) + 20 * (s as usize).pow(2)
}

/// The experiment 1 scene with every object scaled by `scale` (> 0) about its own centre.
pub fn area_scene(scale: f32) -> Scene {
    let objects = vec![
        solid(
            Shape::Icosahedron {
                center: Vec3::new(-3.0, 1.0, 0.0),
                radius: scale,
                subdivisions: 1,
            },
            Vec3::ZERO,
            Vec3::new(0.85, 0.25, 0.2),
            0.2,
        ),
        solid(
            Shape::Icosahedron {
                center: Vec3::new(3.0, -1.0, -3.0),
                radius: scale,
                subdivisions: 0,
            },
            Vec3::new(0.0, 20.0, 0.0),
            Vec3::new(0.9, 0.7, 0.2),
            0.0,
        ),
        solid(
            Shape::Box {
                center: Vec3::new(0.0, -1.0, 2.0),
                size: Vec3::splat(1.5 * scale),
                segments: 1,
            },
            Vec3::new(20.0, 30.0, 0.0),
            Vec3::new(0.25, 0.5, 0.85),
            0.3,
        ),
        solid(
            Shape::Box {
                center: Vec3::new(-1.5, -1.5, -4.0),
                size: Vec3::new(2.0, 1.0, 1.5) * scale,
                segments: 1,
            },
            Vec3::new(0.0, 45.0, 0.0),
            Vec3::new(0.6, 0.6, 0.6),
            0.0,
        ),
        solid(
            Shape::Prism {
                center: Vec3::new(1.5, 1.5, 1.0),
                size: Vec3::new(1.6, 1.4, 1.2) * scale,
                segments: 1,
            },
            Vec3::new(0.0, -30.0, 0.0),
            Vec3::new(0.3, 0.75, 0.35),
            0.2,
        ),
        solid(
            Shape::Prism {
                center: Vec3::new(0.0, 2.0, -5.0),
                size: Vec3::new(2.0, 1.5, 1.5) * scale,
                segments: 1,
            },
            Vec3::new(15.0, 60.0, 0.0),
            Vec3::new(0.7, 0.3, 0.8),
            0.0,
        ),
    ];
    scene(Vec3::new(0.0, 1.5, 16.0), objects)
}

/// The experiment 2 scene: icosahedron with `k` subdivisions, box and prism with `s` segments,
/// each scaled by `scale` (> 0) about its own centre.
pub fn faces_scene(k: u32, s: u32, scale: f32) -> Scene {
    let objects = vec![
        solid(
            Shape::Icosahedron {
                center: Vec3::new(-2.6, 0.0, 0.0),
                radius: 1.1 * scale,
                subdivisions: k,
            },
            Vec3::ZERO,
            Vec3::new(0.85, 0.25, 0.2),
            0.2,
        ),
        solid(
            Shape::Box {
                center: Vec3::ZERO,
                size: Vec3::splat(1.6 * scale),
                segments: s,
            },
            Vec3::new(25.0, 35.0, 0.0),
            Vec3::new(0.25, 0.5, 0.85),
            0.2,
        ),
        solid(
            Shape::Prism {
                center: Vec3::new(2.6, 0.0, 0.0),
                size: Vec3::new(1.8, 1.6, 1.4) * scale,
                segments: s,
            },
            Vec3::new(10.0, -30.0, 0.0),
            Vec3::new(0.3, 0.75, 0.35),
            0.2,
        ),
    ];
    scene(Vec3::new(0.0, 1.0, 10.0), objects)
}

/// An object with the default material but for `color` and mirror `reflection`, turned by
/// `rotation` (Euler degrees).
fn solid(shape: Shape, rotation: Vec3, color: Vec3, reflection: f32) -> Object {
    Object {
        rotation,
        material: Material {
            color,
            reflection,
            ..Material::default()
        },
        ..Object::new(shape)
    }
}

/// A scene of `objects` seen from `eye` toward the origin (45° field of view), under two lights.
fn scene(eye: Vec3, objects: Vec<Object>) -> Scene {
    Scene {
        camera: Camera {
            position: eye,
            target: Vec3::ZERO,
            up: Vec3::Y,
            fov: 45.0,
            ..Camera::default()
        },
        lights: lights(),
        objects,
        ..Scene::default()
    }
}

/// The two point lights both experiments use.
fn lights() -> Vec<Light> {
    vec![
        Light {
            name: Some("key".into()),
            position: Vec3::new(-6.0, 8.0, 10.0),
            intensity: 0.85,
            ..Light::default()
        },
        Light {
            name: Some("fill".into()),
            position: Vec3::new(7.0, 3.0, 6.0),
            intensity: 0.35,
            ..Light::default()
        },
    ]
}

/// The largest scale at which the experiment 1 camera stays clear of every object (10% margin).
fn area_scene_max_scale() -> f32 {
    let unit = area_scene(1.0);
    let world = World::build(&unit, Path::new(".")).expect("the built-in scene has no files");
    world
        .objects
        .iter()
        .map(|o| {
            let distance = o.bounds.center.distance(unit.camera.position);
            distance / (o.bounds.radius * 1.1)
        })
        .fold(f32::INFINITY, f32::min)
}

/// Total face area of `scene` on an image of `size`, square pixels.
pub fn scene_area(scene: &Scene, size: Size) -> f64 {
    let world = World::build(scene, Path::new(".")).expect("the built-in scene has no files");
    total_face_area(&world, &View::new(&scene.camera, size.width, size.height))
}

/// The scale in (0, `limit`] at which `scene_at(scale)` has total face area `target` pixels
/// (bisection: area grows with scale). Returns `limit` when even that falls short.
fn calibrate(scene_at: impl Fn(f32) -> Scene, limit: f32, target: f64, size: Size) -> f32 {
    let (mut lo, mut hi) = (0.0f32, limit);
    if scene_area(&scene_at(hi), size) <= target {
        return hi;
    }
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        let area = scene_area(&scene_at(mid), size);
        if (area - target).abs() <= AREA_TOLERANCE * target {
            return mid;
        }
        if area < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}
