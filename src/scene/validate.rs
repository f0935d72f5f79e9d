//! Range checks on a parsed scene, against the ranges of [`super::limits`]. Every check is
//! written so that NaN fails it.

use std::fmt;

use glam::Vec3;

use super::field_path::FieldPath;
use super::limits::{self, CountLimits, Limits};
use super::material::Material;
use super::model::Scene;
use super::object::Shape;
use super::projection::Projection;

/// A value out of its range: where it is and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("`{path}` {problem}")]
pub struct Invalid {
    pub path: FieldPath,
    pub problem: Problem,
}

/// What is wrong with a value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Problem {
    /// A number outside its limits.
    #[error("must be {limits}, got {value}")]
    Number { value: f32, limits: Limits },
    /// A vector with a component outside the limits every component shares.
    #[error("{components} must each be {limits}, got {value}")]
    Vector {
        value: Vec3,
        components: Components,
        limits: Limits,
    },
    /// A whole number outside its limits.
    #[error("must be {limits}, got {value}")]
    Count { value: u32, limits: CountLimits },
    /// The camera looks at its own position.
    #[error("must differ from the camera position")]
    TargetAtPosition,
    /// The camera's up direction has no part across the view direction.
    #[error("must not be parallel to the view direction")]
    UpAlongView,
    /// An orthographic camera without its view height.
    #[error("must be given for an orthographic camera (the view's height in world units)")]
    NoViewHeight,
    /// A mesh object without a file.
    #[error("must name a model file")]
    NoPath,
}

/// What the three components of a vector are, for messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Components {
    Coordinates,
    Angles,
    Channels,
    Dimensions,
}

impl fmt::Display for Components {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Components::Coordinates => "coordinates",
            Components::Angles => "angles",
            Components::Channels => "channels",
            Components::Dimensions => "width, height and depth",
        })
    }
}

type Check = Result<(), Invalid>;

fn fail(path: &FieldPath, problem: Problem) -> Check {
    Err(Invalid {
        path: path.clone(),
        problem,
    })
}

fn number(path: &FieldPath, value: f32, limits: Limits) -> Check {
    if limits.accepts(value) {
        Ok(())
    } else {
        fail(path, Problem::Number { value, limits })
    }
}

fn vector(path: &FieldPath, value: Vec3, components: Components, limits: Limits) -> Check {
    if value.to_array().iter().all(|&x| limits.accepts(x)) {
        Ok(())
    } else {
        fail(
            path,
            Problem::Vector {
                value,
                components,
                limits,
            },
        )
    }
}

fn count(path: &FieldPath, value: u32, limits: CountLimits) -> Check {
    if limits.accepts(value) {
        Ok(())
    } else {
        fail(path, Problem::Count { value, limits })
    }
}

fn coordinates(path: &FieldPath, value: Vec3) -> Check {
    vector(path, value, Components::Coordinates, limits::COORDINATE)
}

fn color(path: &FieldPath, value: Vec3) -> Check {
    vector(path, value, Components::Channels, limits::COLOR)
}

/// Checks a material's coefficients.
fn validate_material(path: &FieldPath, m: &Material) -> Check {
    color(&path.clone().key("color"), m.color)?;
    number(&path.clone().key("diffuse"), m.diffuse, limits::COEFFICIENT)?;
    number(
        &path.clone().key("specular"),
        m.specular,
        limits::COEFFICIENT,
    )?;
    number(
        &path.clone().key("shininess"),
        m.shininess,
        limits::SHININESS,
    )?;
    number(
        &path.clone().key("reflection"),
        m.reflection,
        limits::COEFFICIENT,
    )
}

/// Checks every number of `scene`; the first problem found is returned.
pub fn validate(scene: &Scene) -> Check {
    let root = FieldPath::default();
    let cam = root.clone().key("camera");
    let c = &scene.camera;
    coordinates(&cam.clone().key("position"), c.position)?;
    coordinates(&cam.clone().key("target"), c.target)?;
    coordinates(&cam.clone().key("up"), c.up)?;
    number(&cam.clone().key("fov"), c.fov, limits::FOV)?;
    match (c.projection, c.height) {
        (_, Some(height)) => number(&cam.clone().key("height"), height, limits::VIEW_HEIGHT)?,
        (Projection::Orthographic, None) => {
            fail(&cam.clone().key("height"), Problem::NoViewHeight)?
        }
        (Projection::Perspective, None) => {}
    }
    let dir = c.target - c.position;
    if dir.length_squared() < 1e-12 {
        fail(&cam.clone().key("target"), Problem::TargetAtPosition)?;
    }
    if dir
        .normalize()
        .cross(c.up.normalize_or_zero())
        .length_squared()
        < 1e-8
    {
        fail(&cam.clone().key("up"), Problem::UpAlongView)?;
    }
    number(&root.clone().key("ambient"), scene.ambient, limits::AMBIENT)?;
    color(&root.clone().key("background"), scene.background)?;
    count(
        &root.clone().key("max_depth"),
        scene.max_depth,
        limits::REFLECTION_DEPTH,
    )?;
    if let Some(f) = &scene.falloff {
        let fp = root.clone().key("falloff");
        number(&fp.clone().key("linear"), f.linear, limits::FALLOFF)?;
        number(&fp.clone().key("quadratic"), f.quadratic, limits::FALLOFF)?;
    }
    for (i, light) in scene.lights.iter().enumerate() {
        let lp = root.clone().key("light").index(i);
        coordinates(&lp.clone().key("position"), light.position)?;
        number(
            &lp.clone().key("intensity"),
            light.intensity,
            limits::INTENSITY,
        )?;
        color(&lp.clone().key("color"), light.color)?;
    }
    for (i, object) in scene.objects.iter().enumerate() {
        let op = root.clone().key("object").index(i);
        vector(
            &op.clone().key("rotation"),
            object.rotation,
            Components::Angles,
            limits::ROTATION,
        )?;
        validate_material(&op.clone().key("material"), &object.material)?;
        match &object.shape {
            Shape::Icosahedron {
                center,
                radius,
                subdivisions,
            } => {
                coordinates(&op.clone().key("center"), *center)?;
                number(&op.clone().key("radius"), *radius, limits::EXTENT)?;
                count(
                    &op.clone().key("subdivisions"),
                    *subdivisions,
                    limits::SUBDIVISIONS,
                )?;
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
                coordinates(&op.clone().key("center"), *center)?;
                vector(
                    &op.clone().key("size"),
                    *size,
                    Components::Dimensions,
                    limits::EXTENT,
                )?;
                count(&op.clone().key("segments"), *segments, limits::SEGMENTS)?;
            }
            Shape::Mesh {
                path,
                position,
                scale,
                ..
            } => {
                if path.as_os_str().is_empty() {
                    fail(&op.clone().key("path"), Problem::NoPath)?;
                }
                coordinates(&op.clone().key("position"), *position)?;
                number(&op.clone().key("scale"), *scale, limits::EXTENT)?;
            }
        }
    }
    Ok(())
}
