//! A 3-vector whose components are lanes: one vector per lane, stored component-wise.

use std::ops::{Add, AddAssign, Mul, Neg, Sub};

use glam::Vec3;

use super::lanes::{Lanes, Lanes8, WIDTH};

/// `x`, `y` and `z` each hold one component of every lane's vector.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct V3<L> {
    pub x: L,
    pub y: L,
    pub z: L,
}

impl<L: Lanes> V3<L> {
    /// The vector with the given component lanes.
    #[inline(always)]
    pub fn new(x: L, y: L, z: L) -> V3<L> {
        V3 { x, y, z }
    }

    /// `v` in every lane.
    #[inline(always)]
    pub fn splat(v: Vec3) -> V3<L> {
        V3::new(L::splat(v.x), L::splat(v.y), L::splat(v.z))
    }

    /// Dot product, lane by lane.
    #[inline(always)]
    pub fn dot(self, o: V3<L>) -> L {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product, lane by lane.
    #[inline(always)]
    pub fn cross(self, o: V3<L>) -> V3<L> {
        V3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Squared length.
    #[inline(always)]
    pub fn length_squared(self) -> L {
        self.dot(self)
    }

    /// Unit length; a zero vector stays zero (lengths below 10^−15 are taken as 10^−15).
    #[inline(always)]
    pub fn normalize_or_zero(self) -> V3<L> {
        let len2 = self.length_squared().max(L::splat(1.0e-30));
        self * (L::splat(1.0) / len2.sqrt())
    }

    /// −self where `mask` holds.
    #[inline(always)]
    pub fn negate_where(mask: L::Mask, v: V3<L>) -> V3<L> {
        V3::new(
            L::negate_where(mask, v.x),
            L::negate_where(mask, v.y),
            L::negate_where(mask, v.z),
        )
    }

    /// Component-wise product.
    #[inline(always)]
    pub fn mul_elements(self, o: V3<L>) -> V3<L> {
        V3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }
}

impl V3<f32> {
    /// As a glam vector.
    #[inline(always)]
    pub fn to_vec3(self) -> Vec3 {
        Vec3::new(self.x, self.y, self.z)
    }
}

impl<L: Lanes8> V3<L> {
    /// `low`'s lanes, then `high`'s.
    #[inline(always)]
    pub fn pair(low: V3<L>, high: V3<L>) -> V3<L::Pair> {
        V3::new(
            L::pair(low.x, high.x),
            L::pair(low.y, high.y),
            L::pair(low.z, high.z),
        )
    }

    /// The low eight lanes and the high eight.
    #[inline(always)]
    pub fn halves(pair: V3<L::Pair>) -> (V3<L>, V3<L>) {
        let ((x0, x1), (y0, y1), (z0, z1)) =
            (L::halves(pair.x), L::halves(pair.y), L::halves(pair.z));
        (V3::new(x0, y0, z0), V3::new(x1, y1, z1))
    }

    /// Lane k holds `vectors[k]`; lanes past the end repeat the last vector (`vectors` holds 1
    /// to [`WIDTH`] of them).
    ///
    /// Plain loops over the lanes rather than `array::from_fn`: the compiler unrolls them
    /// wherever this is inlined, while a closure-built array was at times left as a call per
    /// lane, which cost the Gouraud vertex stage a tenth of its time.
    #[inline]
    pub fn gather(vectors: &[Vec3]) -> V3<L> {
        debug_assert!((1..=WIDTH).contains(&vectors.len()));
        let last = vectors.len() - 1;
        let (mut x, mut y, mut z) = ([0.0; WIDTH], [0.0; WIDTH], [0.0; WIDTH]);
        for k in 0..WIDTH {
            let v = vectors[k.min(last)];
            (x[k], y[k], z[k]) = (v.x, v.y, v.z);
        }
        V3::new(L::from_array(x), L::from_array(y), L::from_array(z))
    }

    /// The vectors of the lanes.
    #[inline(always)]
    pub fn to_vec3s(self) -> [Vec3; WIDTH] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|k| Vec3::new(x[k], y[k], z[k]))
    }
}

impl From<Vec3> for V3<f32> {
    #[inline(always)]
    fn from(v: Vec3) -> V3<f32> {
        V3::new(v.x, v.y, v.z)
    }
}

impl<L: Lanes> Add for V3<L> {
    type Output = V3<L>;

    #[inline(always)]
    fn add(self, o: V3<L>) -> V3<L> {
        V3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<L: Lanes> AddAssign for V3<L> {
    #[inline(always)]
    fn add_assign(&mut self, o: V3<L>) {
        *self = *self + o;
    }
}

impl<L: Lanes> Sub for V3<L> {
    type Output = V3<L>;

    #[inline(always)]
    fn sub(self, o: V3<L>) -> V3<L> {
        V3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<L: Lanes> Mul<L> for V3<L> {
    type Output = V3<L>;

    #[inline(always)]
    fn mul(self, s: L) -> V3<L> {
        V3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl<L: Lanes> Neg for V3<L> {
    type Output = V3<L>;

    #[inline(always)]
    fn neg(self) -> V3<L> {
        V3::new(-self.x, -self.y, -self.z)
    }
}
