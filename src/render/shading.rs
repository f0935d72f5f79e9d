//! The one lighting function every renderer calls: the Phong model summed over point lights.
//!
//! It is written once over [`Lanes`]: the ray tracer lights one hit at a time (`f32`), the
//! Z-buffer eight pixels or vertices at a time ([`F32x8`](super::simd::F32x8)). Both run the same
//! operations in the same order, so a point gets the same colour bits whichever renderer lights
//! it.

use glam::Vec3;

use super::materials::MaterialLanes;
use super::simd::{Lanes, V3, pow};
use crate::scene::{Falloff, Light};
use crate::world::World;

/// The lights and ambient term of a scene.
#[derive(Debug, Clone, Copy)]
pub struct Lighting<'a> {
    pub lights: &'a [Light],
    /// Ambient intensity Ia in [0, 1].
    pub ambient: f32,
    /// Distance attenuation; `None` when the scene has none (att = 1).
    pub falloff: Option<Falloff>,
}

impl<'a> Lighting<'a> {
    /// The lighting of `world`.
    pub fn new(world: &'a World) -> Lighting<'a> {
        Lighting {
            lights: &world.lights,
            ambient: world.ambient,
            falloff: world.falloff,
        }
    }

    /// Colour at points `p` with unit normals `n`, seen along unit `v` (from `p` toward the eye):
    ///
    /// `C = Ia·color + Σ I·att(d)·Lc ⊙ (Kd·max(0, N·L)·color + Ks·max(0, R·V)^p)`,
    /// L = normalize(Lp − p), R = reflect(−L, N), the specular term only where N·L > 0 and
    /// where it can show (R·V above the material's cutoff, see [`MaterialLanes`]).
    /// A normal facing away from the viewer is flipped first. `lit(i, light, facing)` is asked,
    /// for the lanes where light `i` faces the surface, which of them it reaches (the ray
    /// tracer's shadow test; the Z-buffer answers `facing`).
    #[inline(always)]
    pub fn shade_lanes<L: Lanes>(
        &self,
        p: V3<L>,
        n: V3<L>,
        v: V3<L>,
        m: &MaterialLanes<L>,
        lit: impl FnMut(usize, &Light, L::Mask) -> L::Mask,
    ) -> V3<L> {
        let mut c = m.color * L::splat(self.ambient);
        self.each_light(p, n, v, m, lit, |light, n_dot_l, specular, strength| {
            let diffuse = m.color * (m.diffuse * n_dot_l);
            let term = V3::new(
                diffuse.x + specular,
                diffuse.y + specular,
                diffuse.z + specular,
            );
            c += term.mul_elements(V3::splat(light.color)) * strength;
        });
        c
    }

    /// The lighting of [`Lighting::shade_lanes`] cut in two parts for an albedo that is known
    /// only later (Gouraud shading with per-pixel albedo: OpenGL's separate specular colour):
    /// the diffuse and ambient factor `D = Ia + Σ I·att(d)·Lc·Kd·max(0, N·L)` and the specular
    /// colour `S = Σ I·att(d)·Lc·Ks·max(0, R·V)^p`, so that the colour with albedo `a` is
    /// `a ⊙ D + S`: the same terms, summed in another order. `m.color` is not read.
    #[inline(always)]
    pub fn shade_parts_lanes<L: Lanes>(
        &self,
        p: V3<L>,
        n: V3<L>,
        v: V3<L>,
        m: &MaterialLanes<L>,
        lit: impl FnMut(usize, &Light, L::Mask) -> L::Mask,
    ) -> (V3<L>, V3<L>) {
        let (ambient, zero) = (L::splat(self.ambient), L::splat(0.0));
        let mut diffuse = V3::new(ambient, ambient, ambient);
        let mut specular = V3::new(zero, zero, zero);
        self.each_light(p, n, v, m, lit, |light, n_dot_l, highlight, strength| {
            let color = V3::splat(light.color);
            diffuse += color * (m.diffuse * n_dot_l * strength);
            specular += color * (highlight * strength);
        });
        (diffuse, specular)
    }

    /// The per-light work both forms share: for each light that faces and reaches some lane,
    /// `add(light, N·L, Ks·max(0, R·V)^p, I·att(d))`, the strength zero in the lanes it does
    /// not reach and the specular term zero where it cannot show. The normal is flipped toward
    /// the viewer first.
    #[inline(always)]
    fn each_light<L: Lanes>(
        &self,
        p: V3<L>,
        n: V3<L>,
        v: V3<L>,
        m: &MaterialLanes<L>,
        mut lit: impl FnMut(usize, &Light, L::Mask) -> L::Mask,
        mut add: impl FnMut(&Light, L, L, L),
    ) {
        let zero = L::splat(0.0);
        let n_dot_v = n.dot(v);
        let flip = n_dot_v.lt(zero);
        let n = V3::negate_where(flip, n);
        let n_dot_v = L::negate_where(flip, n_dot_v);
        for (i, light) in self.lights.iter().enumerate() {
            let to_light = V3::splat(light.position) - p;
            let d = to_light.length_squared().sqrt();
            let inv_d = L::splat(1.0) / d;
            // A point at the light (d = 0) makes this NaN, which fails the test below.
            let n_dot_l = n.dot(to_light) * inv_d;
            let facing = n_dot_l.gt(zero);
            if !L::any(facing) {
                continue;
            }
            let reached = lit(i, light, facing);
            if !L::any(reached) {
                continue;
            }
            // R·V for R = reflect(−L, N) = 2(N·L)N − L, without forming R.
            let r_dot_v = L::splat(2.0) * n_dot_l * n_dot_v - to_light.dot(v) * inv_d;
            // Where R·V is at or below the material's cutoff the highlight cannot show.
            let shiny = r_dot_v.gt(m.specular_cutoff);
            let specular = if L::any(shiny) {
                L::keep(shiny, m.specular * pow(r_dot_v.max(zero), m.shininess))
            } else {
                zero
            };
            let mut strength = L::keep(reached, L::splat(light.intensity));
            if let Some(Falloff { linear, quadratic }) = self.falloff {
                let spread = L::splat(1.0) + L::splat(linear) * d + L::splat(quadratic) * d * d;
                strength = strength / spread;
            }
            add(light, n_dot_l, specular, strength);
        }
    }

    /// [`Lighting::shade_lanes`] for one point: `lit(i, light)` says whether light `i`, which
    /// faces the surface, reaches `p`.
    #[inline]
    pub fn shade(
        &self,
        p: Vec3,
        n: Vec3,
        v: Vec3,
        m: &MaterialLanes<f32>,
        mut lit: impl FnMut(usize, &Light) -> bool,
    ) -> Vec3 {
        self.shade_lanes::<f32>(p.into(), n.into(), v.into(), m, |i, light, facing| {
            facing && lit(i, light)
        })
        .to_vec3()
    }
}

#[cfg(test)]
mod tests;
