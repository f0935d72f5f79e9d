//! Each object's material as the lighting function takes it: the coefficients in lanes, plus
//! the specular cutoff that lets the lighting skip highlights too faint to show.

use super::simd::{Lanes, Lanes8, V3, WIDTH};
use crate::scene::Material;
use crate::world::World;

/// Specular terms below this are dropped: 2^−14, a fifth of the smallest step an 8-bit sRGB
/// pixel can show (code 1 is 3·10^−4 in linear light).
pub const SPECULAR_FLOOR: f32 = 1.0 / 16_384.0;

/// The lighting coefficients of a [`Material`], one material per lane.
#[derive(Debug, Clone, Copy)]
pub struct MaterialLanes<L> {
    /// Linear RGB albedo.
    pub color: V3<L>,
    /// Kd.
    pub diffuse: L,
    /// Ks.
    pub specular: L,
    /// Phong exponent p.
    pub shininess: L,
    /// R·V at or below which Ks·(R·V)^p, times the brightest light, is under
    /// [`SPECULAR_FLOOR`]: the highlight is not computed there. In [0, 1], or +∞ when the
    /// material has no visible highlight at all.
    pub specular_cutoff: L,
}

impl MaterialLanes<f32> {
    /// The coefficients of `m` lit by lights no brighter than `brightest` (intensity times the
    /// largest colour channel).
    pub fn new(m: &Material, brightest: f32) -> MaterialLanes<f32> {
        // Ks·I·x^p < floor ⟺ x < (floor / (Ks·I))^(1/p); Ks·I = 0 gives +∞, p = 0 gives 0
        // (x^0 = 1 everywhere) or +∞ when even that is too faint.
        let ratio = SPECULAR_FLOOR / (m.specular * brightest);
        MaterialLanes {
            color: m.color.into(),
            diffuse: m.diffuse,
            specular: m.specular,
            shininess: m.shininess,
            specular_cutoff: ratio.powf(m.shininess.recip()),
        }
    }
}

impl<L: Lanes> MaterialLanes<L> {
    /// `m` in every lane.
    #[inline(always)]
    pub fn splat(m: &MaterialLanes<f32>) -> MaterialLanes<L> {
        MaterialLanes {
            color: V3::new(
                L::splat(m.color.x),
                L::splat(m.color.y),
                L::splat(m.color.z),
            ),
            diffuse: L::splat(m.diffuse),
            specular: L::splat(m.specular),
            shininess: L::splat(m.shininess),
            specular_cutoff: L::splat(m.specular_cutoff),
        }
    }
}

impl<L: Lanes8> MaterialLanes<L> {
    /// Lane k takes `materials[k]`.
    #[inline(always)]
    pub fn gather(materials: [&MaterialLanes<f32>; WIDTH]) -> MaterialLanes<L> {
        let lanes = |f: fn(&MaterialLanes<f32>) -> f32| L::from_array(materials.map(f));
        MaterialLanes {
            color: V3::new(
                lanes(|m| m.color.x),
                lanes(|m| m.color.y),
                lanes(|m| m.color.z),
            ),
            diffuse: lanes(|m| m.diffuse),
            specular: lanes(|m| m.specular),
            shininess: lanes(|m| m.shininess),
            specular_cutoff: lanes(|m| m.specular_cutoff),
        }
    }
}

/// Every object's material, ready for the lighting function, in world order.
#[derive(Debug, Clone)]
pub struct ObjectMaterials {
    /// One value per object.
    pub one: Vec<MaterialLanes<f32>>,
}

impl ObjectMaterials {
    /// The materials of `world`'s objects under its lights.
    pub fn new(world: &World) -> ObjectMaterials {
        let brightest = world
            .lights
            .iter()
            .map(|l| l.intensity * l.color.max_element())
            .fold(0.0, f32::max);
        let one: Vec<_> = world
            .objects
            .iter()
            .map(|o| MaterialLanes::new(&o.material, brightest))
            .collect();
        ObjectMaterials { one }
    }

    /// The material of `object` in every lane.
    #[inline(always)]
    pub fn splat<L: Lanes>(&self, object: usize) -> MaterialLanes<L> {
        MaterialLanes::splat(&self.one[object])
    }

    /// The materials of objects `objects`, lane by lane: one object's splat when all eight
    /// belong to it (the common case), else gathered.
    #[inline(always)]
    pub fn of_lanes<L: Lanes8>(&self, objects: &[u32; WIDTH]) -> MaterialLanes<L> {
        if objects.iter().all(|&o| o == objects[0]) {
            self.splat(objects[0] as usize)
        } else {
            MaterialLanes::gather(objects.map(|o| &self.one[o as usize]))
        }
    }

    /// The materials of two batches of lanes, `low`'s objects then `high`'s, in sixteen lanes.
    #[inline(always)]
    pub fn of_pair<L: Lanes8>(
        &self,
        low: &[u32; WIDTH],
        high: &[u32; WIDTH],
    ) -> MaterialLanes<L::Pair> {
        let object = low[0];
        if low.iter().chain(high).all(|&o| o == object) {
            return self.splat(object as usize);
        }
        let (low, high) = (self.of_lanes::<L>(low), self.of_lanes::<L>(high));
        MaterialLanes {
            color: V3::pair(low.color, high.color),
            diffuse: L::pair(low.diffuse, high.diffuse),
            specular: L::pair(low.specular, high.specular),
            shininess: L::pair(low.shininess, high.shininess),
            specular_cutoff: L::pair(low.specular_cutoff, high.specular_cutoff),
        }
    }
}
