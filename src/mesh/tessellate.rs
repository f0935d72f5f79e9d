//! Turning a scene object into a world-space [`Mesh`].

use std::collections::HashMap;

use glam::{Affine3A, EulerRot, Quat, Vec3};
use rayon::prelude::*;

use super::cuboid::cuboid;
use super::face_list::{Mesh, PASS_CHUNK};
use super::geometry::ModelGeometry;
use super::icosahedron::icosahedron;
use super::normals::{with_colors_and_normals, with_normals};
use super::prism::prism;
use crate::scene::{Object, Shape};

/// The object's placement: for a mesh, the turn that takes its file's up axis to +Y; then the
/// rotation (Euler degrees, X then Y then Z) about its centre, then the move to its centre.
pub fn object_transform(object: &Object) -> Affine3A {
    let r = object.rotation * (std::f32::consts::PI / 180.0);
    let mut rotation = Quat::from_euler(EulerRot::ZYX, r.z, r.y, r.x);
    if let Shape::Mesh { up, .. } = &object.shape {
        rotation *= up.rotation();
    }
    Affine3A::from_rotation_translation(rotation, object.shape.center())
}

/// The object's world-space mesh. A mesh object needs its loaded `obj` model.
///
/// # Panics
/// If `object` is a mesh and `obj` is `None` (a caller bug: the world loads models first).
pub fn tessellate(object: &Object, obj: Option<&ModelGeometry>) -> Mesh {
    let transform = object_transform(object);
    let local = match &object.shape {
        Shape::Icosahedron {
            radius,
            subdivisions,
            ..
        } => {
            let f = icosahedron(*radius, *subdivisions);
            with_normals(&f.positions, &f.triangles, object.smooth)
        }
        Shape::Box { size, segments, .. } => {
            let f = cuboid(*size, *segments);
            with_normals(&f.positions, &f.triangles, object.smooth)
        }
        Shape::Prism { size, segments, .. } => {
            let f = prism(*size, *segments);
            with_normals(&f.positions, &f.triangles, object.smooth)
        }
        Shape::Mesh { .. } => {
            let model = obj.expect("mesh objects are tessellated with their OBJ model");
            let (lo, hi) = model.bounds();
            return tessellate_part(object, model, (lo + hi) * 0.5);
        }
    };
    local.transformed(transform)
}

/// The world-space mesh of one part of a mesh object's file: `geometry` moved so that the
/// file's `centre` (the centre of the whole file's bounds, in its own space) sits at the object's
/// position, scaled by its `scale` and turned by its rotation. Normals come from the file when
/// it gives them and the object is smooth, otherwise from the faces within the crease angle.
/// The file's vertex colours, when it has them, stay with their vertices.
///
/// # Panics
/// If `object` is not a mesh object (a caller bug).
pub fn tessellate_part(object: &Object, geometry: &ModelGeometry, centre: Vec3) -> Mesh {
    let Shape::Mesh { scale, .. } = &object.shape else {
        panic!("only mesh objects have model parts");
    };
    let positions: Vec<Vec3> = geometry
        .positions
        .par_iter()
        .with_min_len(PASS_CHUNK)
        .map(|&p| (p - centre) * *scale)
        .collect();
    part_mesh(object, geometry, &positions).transformed(object_transform(object))
}

/// The mesh of a part that several instances share, in its own space: `geometry`'s positions
/// as they are, with normals as [`tessellate_part`] makes them (the file's, or computed from
/// these positions). [`instance_transform`] places it.
pub fn tessellate_shared(object: &Object, geometry: &ModelGeometry) -> Mesh {
    part_mesh(object, geometry, &geometry.positions)
}

/// Where [`tessellate_shared`]'s mesh is drawn for an instance placed in the model by
/// `placement`: as [`tessellate_part`] places the model (centred on `centre`, scaled, then
/// turned and moved by the object).
pub fn instance_transform(object: &Object, centre: Vec3, placement: glam::Mat4) -> Affine3A {
    let Shape::Mesh { scale, .. } = &object.shape else {
        panic!("only mesh objects have model parts");
    };
    object_transform(object)
        * Affine3A::from_scale(Vec3::splat(*scale))
        * Affine3A::from_translation(-centre)
        * Affine3A::from_mat4(placement)
}

/// The mesh of `geometry`'s triangles on `positions` (one per geometry position), smooth or flat
/// as `object` says, with the file's normals when it has them and is smooth.
fn part_mesh(object: &Object, geometry: &ModelGeometry, positions: &[Vec3]) -> Mesh {
    let colors = geometry.colors.as_deref();
    match (&geometry.corner_normals, object.smooth) {
        (Some(normals), true) => with_file_normals(positions, &geometry.triangles, normals, colors),
        _ => with_colors_and_normals(positions, &geometry.triangles, colors, object.smooth),
    }
}

/// The world positions of `geometry`'s (welded) vertices as [`tessellate_part`] places them,
/// bit for bit: a model's shape can be measured from these and the file's triangles without the
/// world mesh, whose flat-shaded corners each have a vertex of their own.
pub fn placed_positions(object: &Object, geometry: &ModelGeometry, centre: Vec3) -> Vec<Vec3> {
    let Shape::Mesh { scale, .. } = &object.shape else {
        panic!("only mesh objects have model parts");
    };
    let transform = object_transform(object);
    crate::huge_pages::collected(
        geometry
            .positions
            .par_iter()
            .with_min_len(PASS_CHUNK)
            .map(|&p| transform.transform_point3((p - centre) * *scale)),
    )
}

/// A mesh using the file's own corner normals, and `colors` (one per position) when given;
/// corners with equal position index and normal share a vertex (a position index holds one
/// colour, so corners of different colours never do).
fn with_file_normals(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    normals: &[[Vec3; 3]],
    colors: Option<&[Vec3]>,
) -> Mesh {
    let mut mesh = Mesh {
        colors: colors.map(|_| Vec::new()),
        ..Mesh::default()
    };
    let mut index: HashMap<(u32, [u32; 3]), u32> = HashMap::with_capacity(positions.len());
    for (tri, corner_normals) in triangles.iter().zip(normals) {
        let mut out = [0u32; 3];
        for k in 0..3 {
            let n = corner_normals[k];
            let key = (tri[k], n.to_array().map(f32::to_bits));
            out[k] = *index.entry(key).or_insert_with(|| {
                mesh.positions.push(positions[tri[k] as usize]);
                mesh.normals.push(n);
                if let (Some(out), Some(colors)) = (&mut mesh.colors, colors) {
                    out.push(colors[tri[k] as usize]);
                }
                mesh.positions.len() as u32 - 1
            });
        }
        mesh.triangles.push(out);
    }
    mesh
}
