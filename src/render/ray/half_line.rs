//! A ray: origin, unit direction and the reciprocal direction the box tests need.

use glam::{Vec3, Vec3A};

/// Components of a direction smaller than this are nudged to it (keeping their sign) before the
/// reciprocal is taken, so box tests never multiply 0 by ∞.
pub(crate) const TINY: f32 = 1.0e-20;

/// A half-line `origin + t·dir`, t ≥ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Start point, world units.
    pub origin: Vec3A,
    /// Direction; unit length for every ray the renderer casts, so t is a distance.
    pub dir: Vec3A,
    /// Per-component 1/dir, finite (see [`TINY`]).
    pub inv_dir: Vec3A,
}

impl Ray {
    /// The ray from `origin` along `dir` (not renormalised).
    #[inline]
    pub fn new(origin: Vec3, dir: Vec3) -> Ray {
        let dir = Vec3A::from(dir);
        let safe = Vec3A::select(
            dir.abs().cmplt(Vec3A::splat(TINY)),
            Vec3A::splat(TINY).copysign(dir),
            dir,
        );
        Ray {
            origin: Vec3A::from(origin),
            dir,
            inv_dir: safe.recip(),
        }
    }
}
