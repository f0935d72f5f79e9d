//! Ray/primitive intersection: triangle (Möller–Trumbore with a precomputed normal), sphere and
//! axis-aligned box. Every test accepts a hit only for t strictly inside (t_min, t_max).

use glam::{Vec3, Vec3A};

use super::half_line::Ray;

/// A ray is treated as parallel to a triangle's plane when |cos| of its angle with the plane's
/// normal is at most this: the hit point would be numerically meaningless.
pub(crate) const PARALLEL_COS: f32 = 1.0e-6;

/// A triangle prepared for intersection: one 64-byte cache line.
///
/// It keeps its three vertices rather than two edges: an edge rounded to `f32` moves the vertex
/// it leads to, so the two triangles on either side of a mesh edge would each see the edge a
/// little elsewhere, and a ray aimed at the edge could pass between them (the `f64` decision of
/// [`Triangle::intersect_exact`] needs the vertices themselves).
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct Triangle {
    /// The vertices.
    pub v0: Vec3A,
    pub v1: Vec3A,
    pub v2: Vec3A,
    /// Geometric normal e1 × e2 in `f32`, not normalised (its length is twice the area).
    pub n: Vec3A,
}

/// Where a ray meets a triangle: distance and the barycentric weights of v1 (`u`) and v2 (`v`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter of the hit (a distance for a unit direction).
    pub t: f32,
    /// Weight of the second vertex, in [0, 1].
    pub u: f32,
    /// Weight of the third vertex, in [0, 1]; u + v ≤ 1.
    pub v: f32,
}

impl Triangle {
    /// The triangle with corners `a`, `b`, `c` (either winding: both sides are hit).
    #[inline]
    pub fn new(a: Vec3, b: Vec3, c: Vec3) -> Triangle {
        let (a, b, c) = (Vec3A::from(a), Vec3A::from(b), Vec3A::from(c));
        let (e1, e2) = (b - a, c - a);
        Triangle {
            v0: a,
            v1: b,
            v2: c,
            n: e1.cross(e2),
        }
    }

    /// Edge v1 − v0 in `f32`.
    #[inline(always)]
    pub fn e1(&self) -> Vec3A {
        self.v1 - self.v0
    }

    /// Edge v2 − v0 in `f32`.
    #[inline(always)]
    pub fn e2(&self) -> Vec3A {
        self.v2 - self.v0
    }

    /// The nearest hit of `ray` with t in (t_min, t_max). Points on edges and vertices count as
    /// inside; degenerate triangles and rays parallel to the plane never hit.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<TriangleHit> {
        // Cramer's rule on o + t·d = v0 + u·e1 + v·e2, with det = −d·(e1 × e2).
        let det = -ray.dir.dot(self.n);
        // Parallel (or degenerate, n = 0): |d·n| ≤ ε·|d|·|n|, squared to avoid the roots.
        if det * det
            <= PARALLEL_COS * PARALLEL_COS * self.n.length_squared() * ray.dir.length_squared()
        {
            return None;
        }
        let inv_det = 1.0 / det;
        let to_origin = ray.origin - self.v0;
        let t = to_origin.dot(self.n) * inv_det;
        if !(t > t_min && t < t_max) {
            return None;
        }
        let q = to_origin.cross(ray.dir);
        let u = self.e2().dot(q) * inv_det;
        let v = -self.e1().dot(q) * inv_det;
        if near_edge(u, v) {
            return self.intersect_exact(ray.origin, ray.dir, t_min, t_max);
        }
        // Negative barycentric ⇒ the point lies outside.
        if u < 0.0 || v < 0.0 || u + v > 1.0 {
            return None;
        }
        Some(TriangleHit { t, u, v })
    }

    /// [`Triangle::intersect`] worked out in `f64`, for a ray that `f32` puts near an edge or a
    /// vertex (see [`near_edge`]): the rounding of `f32` there can leave a point of a shared edge
    /// outside both of its triangles, and a ray would pass through a closed surface (a
    /// 1.31M-triangle sphere seen from 3.7 radii: barycentrics off by 4·10⁻⁶). In `f64` the error
    /// is about 10⁻¹³ of that, and the edges come from the vertices themselves (the difference
    /// of two `f32` within 2^28 of each other's magnitude is exact in `f64`), so both triangles
    /// of a mesh edge see the same edge.
    #[cold]
    pub(super) fn intersect_exact(
        &self,
        origin: Vec3A,
        dir: Vec3A,
        t_min: f32,
        t_max: f32,
    ) -> Option<TriangleHit> {
        let v0 = self.v0.as_dvec3();
        let (e1, e2) = (self.v1.as_dvec3() - v0, self.v2.as_dvec3() - v0);
        let (dir, to_origin) = (dir.as_dvec3(), (origin.as_dvec3() - v0));
        let n = e1.cross(e2);
        let det = -dir.dot(n);
        if det == 0.0 {
            return None;
        }
        // The range is checked on the f32 t that is returned: a t just below `t_max` in f64 that
        // rounds to it is no nearer than the hit that set `t_max`, which keeps a tie with it.
        let t = to_origin.dot(n) / det;
        let t32 = t as f32;
        if !(t32 > t_min && t32 < t_max) {
            return None;
        }
        let q = to_origin.cross(dir);
        let u = e2.dot(q) / det;
        let v = -e1.dot(q) / det;
        if u < 0.0 || v < 0.0 || u + v > 1.0 {
            return None;
        }
        Some(TriangleHit {
            t: t32,
            u: u as f32,
            v: v as f32,
        })
    }
}

/// How close to 0 a barycentric weight computed in `f32` must be for the hit to be decided in
/// `f64` instead ([`Triangle::intersect_exact`]): well above the `f32` error of a triangle a
/// thousandth the size of its distance to the ray's origin, and met by a fraction of a percent of
/// the rays that reach a triangle's plane near it.
pub(crate) const EDGE_BAND: f32 = 1.0e-3;

/// Whether barycentrics (`u`, `v`) computed in `f32` leave the hit undecided: the smallest of
/// the three weights within [`EDGE_BAND`] of 0. Beyond the band, the point is inside or
/// outside by more than `f32` can be wrong by.
#[inline(always)]
pub(crate) fn near_edge(u: f32, v: f32) -> bool {
    let least = u.min(v).min(1.0 - u - v);
    least > -EDGE_BAND && least < EDGE_BAND
}

/// Where a ray enters and leaves a sphere (`t_near` ≤ `t_far`, either may be negative), or `None`
/// when the line misses it. A tangent line enters and leaves at the same t. The renderer culls
/// with [`segment_meets_sphere`], which needs no root; the tests keep this as the exact answer.
#[cfg(test)]
pub fn ray_sphere(ray: &Ray, center: Vec3, radius: f32) -> Option<(f32, f32)> {
    let oc = ray.origin - Vec3A::from(center);
    let a = ray.dir.length_squared();
    let half_b = oc.dot(ray.dir);
    // c computed as (|oc| − r)(|oc| + r) loses less precision far from the sphere.
    let len = oc.length();
    let c = (len - radius) * (len + radius);
    let disc = half_b * half_b - a * c;
    if disc < 0.0 || a == 0.0 {
        return None;
    }
    let root = disc.sqrt();
    // The numerically stable pair of roots: q = −(b/2 + sign(b/2)·√disc).
    let q = -(half_b + root.copysign(half_b));
    let (t0, t1) = if q == 0.0 { (0.0, 0.0) } else { (q / a, c / q) };
    Some((t0.min(t1), t0.max(t1)))
}

/// Whether the segment [t_min, t_max] of `ray` (unit direction) touches the ball: the point of
/// the segment nearest the centre lies within `radius`. No root or division, so it is a cheap
/// first cull.
#[inline]
pub fn segment_meets_sphere(ray: &Ray, center: Vec3, radius: f32, t_min: f32, t_max: f32) -> bool {
    let to_center = Vec3A::from(center) - ray.origin;
    let along = to_center.dot(ray.dir);
    let t = if along < t_min {
        t_min
    } else if along > t_max {
        t_max
    } else {
        along
    };
    // t is finite whenever t_min is: an infinite t_max is never below `along`.
    let nearest = ray.origin + ray.dir * t;
    (Vec3A::from(center) - nearest).length_squared() <= radius * radius
}

/// The entry distance of `ray` into the box [lo, hi] clipped to [t_min, t_max], or `None`
/// when the box is missed within that range (slab test).
#[inline]
pub fn ray_box(ray: &Ray, lo: Vec3A, hi: Vec3A, t_min: f32, t_max: f32) -> Option<f32> {
    let t1 = (lo - ray.origin) * ray.inv_dir;
    let t2 = (hi - ray.origin) * ray.inv_dir;
    // Plain comparisons rather than f32::max/min: no NaN can arise (inv_dir is finite), and
    // they compile to single instructions in this, the hottest, loop.
    let near = t1.min(t2).max_element();
    let far = t1.max(t2).min_element();
    let near = if near > t_min { near } else { t_min };
    let far = if far < t_max { far } else { t_max };
    (near <= far).then_some(near)
}
