//! The mesh representation every renderer reads.

use glam::{Affine3A, Vec2, Vec3};
use rayon::prelude::*;

/// Vertices or triangles per parallel task in a pass over a whole mesh: a 10M-triangle scan's
/// passes (bounds, bounding sphere, placement, zero areas) take tens of milliseconds each on
/// one core, and the editor's first frame waits for all of them. Each pass gives the same bits
/// on any number of threads (minima, maxima, counts and per-item maps).
pub(crate) const PASS_CHUNK: usize = 1 << 14;

/// Indexed triangles with one unit normal per vertex, and optionally one colour and one texture
/// coordinate per vertex.
///
/// Invariants: `normals.len() == positions.len()`, and so do `colors`' and `uvs`' when present; every
/// index is `< positions.len()`; triangles of closed shapes wind counter-clockwise seen from
/// outside.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, world units.
    pub positions: Vec<Vec3>,
    /// Unit vertex normals, one per position.
    pub normals: Vec<Vec3>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
    /// Linear RGB colour of each vertex (channels finite, ≥ 0), when the model colours its
    /// vertices: the albedo at a point is the material colour times the colour interpolated
    /// there. `None` means white everywhere, and keeps the renderers on their paths without it.
    pub colors: Option<Vec<Vec3>>,
    /// Texture coordinates of each vertex ((0, 0) the image's top-left corner, v downward), when
    /// the mesh is textured. `None` keeps the renderers on their untextured paths.
    pub uvs: Option<Vec<Vec2>>,
    /// Whether the mesh is flat-shaded: each triangle's three corners carry its face normal, so
    /// the normal at any point of a triangle is the triangle's own (the ray tracer then takes
    /// it from the triangle it hit rather than from `normals`).
    pub flat: bool,
}

/// A bounding sphere: centre and radius in world units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    pub center: Vec3,
    pub radius: f32,
}

impl Mesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The three corner positions of triangle `t`.
    #[inline]
    pub fn corners(&self, t: usize) -> [Vec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Sum of the triangles' areas, square world units.
    pub fn surface_area(&self) -> f32 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.corners(t);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// Triangles with zero area: corners that coincide or lie on one line (or coordinates too
    /// large to multiply), so their edges' cross product has no direction. They cover nothing;
    /// [`super::with_normals`] gives them a neighbour's normal.
    pub fn zero_area_triangles(&self) -> usize {
        (0..self.triangles.len())
            .into_par_iter()
            .with_min_len(PASS_CHUNK)
            .filter(|&t| {
                let [a, b, c] = self.corners(t);
                has_zero_area(a, b, c)
            })
            .count()
    }

    /// Axis-aligned bounds (min, max); `None` for an empty mesh.
    pub fn bounds(&self) -> Option<(Vec3, Vec3)> {
        let first = *self.positions.first()?;
        Some(bounds_of(&self.positions, (first, first)))
    }

    /// A sphere enclosing every vertex, centred on the centre of `bounds`, which are this
    /// mesh's [`Mesh::bounds`].
    pub fn bounding_sphere(&self, bounds: Option<(Vec3, Vec3)>) -> Sphere {
        let Some((lo, hi)) = bounds else {
            return Sphere {
                center: Vec3::ZERO,
                radius: 0.0,
            };
        };
        let center = (lo + hi) * 0.5;
        let radius = self
            .positions
            .par_iter()
            .with_min_len(PASS_CHUNK)
            .map(|p| p.distance(center))
            .reduce(|| 0.0, f32::max);
        Sphere { center, radius }
    }

    /// The mesh moved by `transform` (a rotation, uniform scale and translation).
    pub fn transformed(mut self, transform: Affine3A) -> Mesh {
        self.positions
            .par_iter_mut()
            .with_min_len(PASS_CHUNK)
            .for_each(|p| *p = transform.transform_point3(*p));
        self.normals
            .par_iter_mut()
            .with_min_len(PASS_CHUNK)
            .for_each(|n| *n = transform.transform_vector3(*n).normalize_or_zero());
        self
    }

    /// Appends `other`'s vertices and triangles. When only one of the two has colours, the
    /// other's vertices become white; when only one has texture coordinates, the other's are 0.
    pub fn append(&mut self, other: &Mesh) {
        self.flat = other.flat && (self.flat || self.triangles.is_empty());
        let base = self.positions.len() as u32;
        let (count, more) = (self.positions.len(), other.positions.len());
        append_per_vertex(&mut self.colors, count, &other.colors, more, Vec3::ONE);
        append_per_vertex(&mut self.uvs, count, &other.uvs, more, Vec2::ZERO);
        self.positions.extend_from_slice(&other.positions);
        self.normals.extend_from_slice(&other.normals);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
    }
}

/// Whether the triangle `a b c` has zero area as [`Mesh::zero_area_triangles`] counts it: its
/// edges' cross product has no direction (`normalize_or_zero` gives zero). That is exactly
/// where the cross product's squared length is zero, not finite or NaN (its reciprocal square
/// root then is not finite and positive), tested without the square root and division.
#[inline]
pub(crate) fn has_zero_area(a: Vec3, b: Vec3, c: Vec3) -> bool {
    let squared = (b - a).cross(c - a).length_squared();
    !(squared > 0.0 && squared < f32::INFINITY)
}

/// The smallest and largest coordinates of `points` and of `start` (min, max), per axis: the
/// same on any number of threads (a minimum does not depend on the order it is taken in).
pub(crate) fn bounds_of(points: &[Vec3], start: (Vec3, Vec3)) -> (Vec3, Vec3) {
    points
        .par_chunks(PASS_CHUNK)
        .map(|chunk| {
            chunk
                .iter()
                .fold(start, |(lo, hi), &p| (lo.min(p), hi.max(p)))
        })
        .reduce(|| start, |(a, b), (c, d)| (a.min(c), b.max(d)))
}

/// Appends `more` (per-vertex values of `more_count` vertices, or none) to `values` (of `count`
/// vertices, or none): a side without values counts as `fill` at each of its vertices.
fn append_per_vertex<T: Copy>(
    values: &mut Option<Vec<T>>,
    count: usize,
    more: &Option<Vec<T>>,
    more_count: usize,
    fill: T,
) {
    match (values.as_mut(), more) {
        (Some(values), Some(more)) => values.extend_from_slice(more),
        (Some(values), None) => values.resize(count + more_count, fill),
        (None, Some(more)) => {
            let mut filled = vec![fill; count];
            filled.extend_from_slice(more);
            *values = Some(filled);
        }
        (None, None) => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One triangle a cross product: corners 0, `e1`, `e2` (edges `e1` and `e2`).
    fn triangle(e1: Vec3, e2: Vec3) -> Mesh {
        Mesh {
            positions: vec![Vec3::ZERO, e1, e2],
            normals: vec![Vec3::Y; 3],
            triangles: vec![[0, 1, 2]],
            ..Mesh::default()
        }
    }

    #[test]
    fn zero_area_is_where_the_normal_has_no_direction() {
        let tiny = 3e-23; // squared cross product subnormal, its square root normal
        let cases = [
            (Vec3::X, Vec3::Y),
            (Vec3::X, Vec3::X * 2.0),
            (Vec3::X * 1e-30, Vec3::Y * 1e-30), // the cross product's square underflows
            (Vec3::X * tiny, Vec3::Y),
            (Vec3::X * 1e5, Vec3::Y * 1e5), // length 1e10, its square 1e20: finite
            (Vec3::X * 1e20, Vec3::Y * 1e20), // the square overflows
            (Vec3::X * f32::MAX, Vec3::Y * f32::MAX),
            (Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Y),
            (Vec3::new(f32::INFINITY, 0.0, 0.0), Vec3::Y),
        ];
        for (e1, e2) in cases {
            let by_normal = usize::from(e1.cross(e2).normalize_or_zero() == Vec3::ZERO);
            assert_eq!(
                triangle(e1, e2).zero_area_triangles(),
                by_normal,
                "{e1} {e2}"
            );
        }
    }

    #[test]
    fn bounds_and_sphere_are_those_of_one_pass_in_order() {
        // More points than one parallel task takes, so that several tasks join.
        let positions: Vec<Vec3> = (0..5 * PASS_CHUNK)
            .map(|i| {
                let t = i as f32 * 0.618;
                Vec3::new(t.sin() * 3.0, (t * 1.7).cos() - 1.0, (t * 0.3).sin() * t)
            })
            .collect();
        let mesh = Mesh {
            normals: vec![Vec3::Y; positions.len()],
            positions: positions.clone(),
            ..Mesh::default()
        };
        let first = positions[0];
        let serial = positions
            .iter()
            .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        assert_eq!(mesh.bounds(), Some(serial));
        let center = (serial.0 + serial.1) * 0.5;
        let radius = positions
            .iter()
            .map(|p| p.distance(center))
            .fold(0.0, f32::max);
        assert_eq!(mesh.bounding_sphere(Some(serial)).radius, radius);
    }
}
