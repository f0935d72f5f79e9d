//! Möller–Trumbore on eight lanes, in both of the packet walk's shapes: eight rays against one
//! triangle (the triangle in every lane), and one ray against up to eight triangles of a leaf
//! (the ray in every lane). Both run [`meet`], so a ray and a triangle give the same bits in
//! either shape, and the same bits as [`Triangle::intersect`]'s `f32` arithmetic.

use glam::Vec3A;

use super::intersect::{EDGE_BAND, PARALLEL_COS, Triangle};
use super::packet::{Lane8, Lanes3, dot, splat3};

/// Triangles in lanes: one per lane, or one in every lane.
#[derive(Clone, Copy)]
pub(super) struct TriangleLanes<L> {
    /// First vertex, world units.
    v0: Lanes3<L>,
    /// Edges v1 − v0 and v2 − v0 in `f32`.
    e1: Lanes3<L>,
    e2: Lanes3<L>,
    /// Geometric normal e1 × e2, not normalised.
    n: Lanes3<L>,
    /// cos²(`PARALLEL_COS`)·|n|²: a ray is parallel to the plane when (d·n)² ≤ this·|d|².
    parallel: L,
}

/// The ray/triangle tests of a [`TriangleLanes`], lane by lane.
#[derive(Clone, Copy)]
pub(super) struct Meeting<L> {
    /// Hit within (t_min, t_max) as `f32` decides it: meaningful only outside `edge`.
    pub found: L,
    /// Ray parameter in `f32`.
    pub t: L,
    /// Barycentric weights of the second and third vertices, in `f32`.
    pub u: L,
    pub v: L,
    /// Not parallel, t within (t_min, t_max), and the point within [`EDGE_BAND`] of an edge:
    /// `f32` cannot decide, [`Triangle::intersect_exact`] does.
    pub edge: L,
}

/// The cosine limit of [`Triangle::intersect`], as it multiplies it: (ε·ε)·|n|².
#[inline(always)]
fn parallel_limit(n: Vec3A) -> f32 {
    PARALLEL_COS * PARALLEL_COS * n.length_squared()
}

impl<L: Lane8> TriangleLanes<L> {
    /// `tri` in every lane.
    #[inline(always)]
    pub fn splat(tri: &Triangle) -> TriangleLanes<L> {
        TriangleLanes {
            v0: splat3(tri.v0),
            e1: splat3(tri.e1()),
            e2: splat3(tri.e2()),
            n: splat3(tri.n),
            parallel: L::splat(parallel_limit(tri.n)),
        }
    }

    /// Up to eight triangles, `tris[k]` in lane k; lanes beyond them hold a degenerate
    /// triangle (all zero), which no ray meets.
    #[inline(always)]
    pub fn gather(tris: &[Triangle]) -> TriangleLanes<L> {
        debug_assert!(tris.len() <= 8);
        const NONE: Triangle = Triangle {
            v0: Vec3A::ZERO,
            v1: Vec3A::ZERO,
            v2: Vec3A::ZERO,
            n: Vec3A::ZERO,
        };
        let each: [&Triangle; 8] = std::array::from_fn(|k| tris.get(k).unwrap_or(&NONE));
        let v0 = L::transpose(each.map(|t| &t.v0));
        let v1 = L::transpose(each.map(|t| &t.v1));
        let v2 = L::transpose(each.map(|t| &t.v2));
        let n = L::transpose(each.map(|t| &t.n));
        let minus = |a: Lanes3<L>, b: Lanes3<L>| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
        TriangleLanes {
            v0,
            e1: minus(v1, v0),
            e2: minus(v2, v0),
            n,
            // As `parallel_limit`: glam's |n|² sums x², y², z² in that order, as `dot` does.
            parallel: L::splat(PARALLEL_COS * PARALLEL_COS) * dot(n, n),
        }
    }
}

/// Rays `origin + t·dir` in lanes (one per lane, or one in every lane) with `dir_len2` = d·d.
#[derive(Clone, Copy)]
pub(super) struct RayLanes<L> {
    pub origin: Lanes3<L>,
    pub dir: Lanes3<L>,
    pub dir_len2: L,
    pub t_min: L,
}

/// Where each lane's ray meets each lane's triangle within (t_min, `t_max`): Möller–Trumbore
/// as [`Triangle::intersect`] computes it, operation for operation.
#[inline(always)]
pub(super) fn meet<L: Lane8>(ray: &RayLanes<L>, tri: &TriangleLanes<L>, t_max: L) -> Meeting<L> {
    let d = ray.dir;
    let det = dot(d, tri.n).negate();
    let not_parallel = (det * det).gt(tri.parallel * ray.dir_len2);
    let inv_det = L::splat(1.0) / det;
    let o = [
        ray.origin[0] - tri.v0[0],
        ray.origin[1] - tri.v0[1],
        ray.origin[2] - tri.v0[2],
    ];
    let t = dot(o, tri.n) * inv_det;
    let q = [
        o[1] * d[2] - o[2] * d[1],
        o[2] * d[0] - o[0] * d[2],
        o[0] * d[1] - o[1] * d[0],
    ];
    let u = dot(tri.e2, q) * inv_det;
    let v = dot(tri.e1, q).negate() * inv_det;
    let zero = L::splat(0.0);
    let inside = u.ge(zero) & v.ge(zero) & (u + v).le(L::splat(1.0));
    let nearer = t.gt(ray.t_min) & t.lt(t_max);
    let least = u.min(v).min(L::splat(1.0) - u - v);
    let edge =
        not_parallel & nearer & least.gt(L::splat(-EDGE_BAND)) & least.lt(L::splat(EDGE_BAND));
    Meeting {
        found: not_parallel & nearer & inside,
        t,
        u,
        v,
        edge,
    }
}
