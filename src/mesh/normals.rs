//! Vertex normals: flat (one normal per face, vertices split) or smooth within a crease angle.

use std::collections::HashMap;

use glam::Vec3;

use super::face_list::Mesh;

/// Adjacent faces meeting at less than this angle share a smoothed normal, degrees.
pub const CREASE_ANGLE_DEGREES: f32 = 60.0;

/// `v` scaled to unit length, or zero when it has no direction that f32 can state: zero, not
/// finite, or so short that its squared length is subnormal (normalizing that gives a vector
/// whose length is not 1: a normal of length 2e-22 came out 1.13 long). Normals from files and
/// from faces both pass through it, and a zero normal counts as missing.
pub fn unit_or_zero(v: Vec3) -> Vec3 {
    let squared = v.length_squared();
    if squared.is_normal() {
        // As glam's `normalize_or_zero` computes it, so normals keep their bits.
        v * (1.0 / squared.sqrt())
    } else {
        Vec3::ZERO
    }
}

/// Builds a [`Mesh`] from welded `positions` and `triangles`, without colours: see
/// [`with_colors_and_normals`].
pub fn with_normals(positions: &[Vec3], triangles: &[[u32; 3]], smooth: bool) -> Mesh {
    with_colors_and_normals(positions, triangles, None, smooth)
}

/// Builds a [`Mesh`] from welded `positions` and `triangles`, with `colors` (one per position)
/// when given.
///
/// Flat: every triangle gets its own three vertices carrying the face normal.
/// Smooth: each corner's normal is the area-weighted sum of the normals of the faces around that
/// vertex that meet its own face at less than [`CREASE_ANGLE_DEGREES`]; corners of one position
/// that end with the same normal share one vertex. Degenerate faces (zero area) take the normal
/// of a neighbour or +Y.
///
/// Each output vertex keeps its position's colour. With colours, a model may hold one point
/// several times, once per colour (a seam between two colours): those entries are never merged,
/// but the faces around all of them count for each one's normal, so a colour seam is no crease.
pub fn with_colors_and_normals(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    colors: Option<&[Vec3]>,
    smooth: bool,
) -> Mesh {
    debug_assert!(colors.is_none_or(|c| c.len() == positions.len()));
    if !smooth {
        return flat_normals(positions, triangles, colors);
    }
    let weighted: Vec<Vec3> = triangles
        .iter()
        .map(|&t| area_weighted_normal(positions, t))
        .collect();
    let unit: Vec<Vec3> = weighted.iter().map(|&n| unit_or_zero(n)).collect();
    smooth_normals(positions, triangles, colors, &weighted, &unit)
}

/// The face normal of triangle `[a, b, c]` weighted by its area: the edges' cross product,
/// whose length is twice the area.
fn area_weighted_normal(positions: &[Vec3], [a, b, c]: [u32; 3]) -> Vec3 {
    let (a, b, c) = (
        positions[a as usize],
        positions[b as usize],
        positions[c as usize],
    );
    (b - a).cross(c - a)
}

/// Three vertices a triangle, each with the face's unit normal (computed as it goes: no
/// per-triangle array beside the mesh being built) and its position's colour.
fn flat_normals(positions: &[Vec3], triangles: &[[u32; 3]], colors: Option<&[Vec3]>) -> Mesh {
    let mut mesh = Mesh {
        positions: Vec::with_capacity(triangles.len() * 3),
        normals: Vec::with_capacity(triangles.len() * 3),
        triangles: Vec::with_capacity(triangles.len()),
        colors: colors.map(|_| Vec::with_capacity(triangles.len() * 3)),
        uvs: None,
        flat: true,
    };
    for tri in triangles {
        let unit = unit_or_zero(area_weighted_normal(positions, *tri));
        let n = if unit == Vec3::ZERO { Vec3::Y } else { unit };
        let base = mesh.positions.len() as u32;
        for &i in tri {
            mesh.positions.push(positions[i as usize]);
            mesh.normals.push(n);
        }
        if let (Some(out), Some(colors)) = (&mut mesh.colors, colors) {
            out.extend(tri.map(|i| colors[i as usize]));
        }
        mesh.triangles.push([base, base + 1, base + 2]);
    }
    mesh
}

/// The first index of each position's bit-identical point: what the faces around a vertex are
/// gathered by when colours split one point into several entries.
fn points(positions: &[Vec3]) -> Vec<u32> {
    let mut first: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    (0..positions.len() as u32)
        .map(|v| {
            *first
                .entry(positions[v as usize].to_array().map(f32::to_bits))
                .or_insert(v)
        })
        .collect()
}

fn smooth_normals(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    colors: Option<&[Vec3]>,
    weighted: &[Vec3],
    unit: &[Vec3],
) -> Mesh {
    let cos_crease = CREASE_ANGLE_DEGREES.to_radians().cos();
    // Without colours, positions are welded already: each is its own point.
    let point_of = colors.map(|_| points(positions));
    let point = |v: u32| point_of.as_ref().map_or(v, |p| p[v as usize]) as usize;
    // Faces around each point, as compressed rows: faces_of[start[p]..start[p + 1]].
    let mut start = vec![0u32; positions.len() + 1];
    for tri in triangles {
        for &v in tri {
            start[point(v) + 1] += 1;
        }
    }
    for v in 0..positions.len() {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut faces_of = vec![0u32; triangles.len() * 3];
    for (t, tri) in triangles.iter().enumerate() {
        for &v in tri {
            faces_of[fill[point(v)] as usize] = t as u32;
            fill[point(v)] += 1;
        }
    }

    let mut mesh = Mesh {
        positions: Vec::with_capacity(positions.len()),
        normals: Vec::with_capacity(positions.len()),
        triangles: Vec::with_capacity(triangles.len()),
        colors: colors.map(|_| Vec::with_capacity(positions.len())),
        uvs: None,
        flat: false,
    };
    // The output vertices made for each welded vertex, as chains: `first_made[v]` is the first
    // (or NONE), `next_made[o]` the one made after output vertex `o` for the same welded
    // vertex. Two u32 a vertex, where a list per vertex cost some 90 bytes.
    const NONE: u32 = u32::MAX;
    let mut first_made = vec![NONE; positions.len()];
    let mut next_made: Vec<u32> = Vec::with_capacity(positions.len());
    for (t, tri) in triangles.iter().enumerate() {
        let mut out = [0u32; 3];
        for (corner, &v) in tri.iter().enumerate() {
            let p = point(v);
            let around = &faces_of[start[p] as usize..start[p + 1] as usize];
            let mut sum = Vec3::ZERO;
            for &g in around {
                if unit[t] == Vec3::ZERO || unit[g as usize].dot(unit[t]) >= cos_crease {
                    sum += weighted[g as usize];
                }
            }
            let mut n = unit_or_zero(sum);
            if n == Vec3::ZERO {
                n = around
                    .iter()
                    .map(|&g| unit[g as usize])
                    .find(|u| *u != Vec3::ZERO)
                    .unwrap_or(Vec3::Y);
            }
            let mut made = first_made[v as usize];
            let mut last = NONE;
            while made != NONE && mesh.normals[made as usize] != n {
                last = made;
                made = next_made[made as usize];
            }
            if made == NONE {
                made = mesh.positions.len() as u32;
                mesh.positions.push(positions[v as usize]);
                mesh.normals.push(n);
                if let (Some(out), Some(colors)) = (&mut mesh.colors, colors) {
                    out.push(colors[v as usize]);
                }
                next_made.push(NONE);
                match last {
                    NONE => first_made[v as usize] = made,
                    _ => next_made[last as usize] = made,
                }
            }
            out[corner] = made;
        }
        mesh.triangles.push(out);
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_normal_too_short_for_f32_counts_as_missing() {
        for v in [
            Vec3::new(2e-22, 0.0, 0.0),
            Vec3::new(1e-20, 1e-20, 1e-20),
            Vec3::ZERO,
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(f32::INFINITY, 0.0, 0.0),
        ] {
            assert_eq!(unit_or_zero(v), Vec3::ZERO, "{v}");
        }
        // The shortest that still normalizes comes out unit length.
        let short = Vec3::new(2e-19, 0.0, 0.0);
        assert!((unit_or_zero(short).length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn ordinary_normals_keep_glam_bits() {
        let mut x = 0.1f32;
        for _ in 0..1000 {
            x = (x * 3.7 + 0.13).fract();
            let v = Vec3::new(x - 0.5, (x * 7.0).fract() - 0.2, (x * 13.0).fract() * 3.0);
            assert_eq!(unit_or_zero(v), v.normalize_or_zero(), "{v}");
        }
    }

    #[test]
    fn a_tiny_triangle_takes_its_neighbours_normal() {
        // A unit right triangle in XY, and beside it one whose cross product is subnormal.
        let positions = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::new(1e-20, 0.0, 0.0),
            Vec3::new(0.0, 1e-20, 0.0),
        ];
        let mesh = with_normals(&positions, &[[0, 1, 2], [0, 3, 4]], true);
        for n in &mesh.normals {
            assert!((n.length() - 1.0).abs() < 1e-6, "{n}");
        }
    }
}
