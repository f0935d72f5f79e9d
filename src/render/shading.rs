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
        mut lit: impl FnMut(usize, &Light, L::Mask) -> L::Mask,
    ) -> V3<L> {
        let (n, n_dot_v) = toward_viewer(n, v);
        let mut c = m.color * L::splat(self.ambient);
        for (i, light) in self.lights.iter().enumerate() {
            let Some(t) = self.light_terms(i, light, p, n, n_dot_v, v, m, &mut lit) else {
                continue;
            };
            let diffuse = m.color * (m.diffuse * t.n_dot_l);
            let term = V3::new(
                diffuse.x + t.specular,
                diffuse.y + t.specular,
                diffuse.z + t.specular,
            );
            c += term.mul_elements(V3::splat(light.color)) * t.strength;
        }
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
        mut lit: impl FnMut(usize, &Light, L::Mask) -> L::Mask,
    ) -> (V3<L>, V3<L>) {
        let (n, n_dot_v) = toward_viewer(n, v);
        let (ambient, zero) = (L::splat(self.ambient), L::splat(0.0));
        let mut diffuse = V3::new(ambient, ambient, ambient);
        let mut specular = V3::new(zero, zero, zero);
        for (i, light) in self.lights.iter().enumerate() {
            let Some(t) = self.light_terms(i, light, p, n, n_dot_v, v, m, &mut lit) else {
                continue;
            };
            let color = V3::splat(light.color);
            diffuse += color * (m.diffuse * t.n_dot_l * t.strength);
            specular += color * (t.specular * t.strength);
        }
        (diffuse, specular)
    }

    /// What light `i` (`light`) gives points `p` with unit normals `n` turned toward the viewer
    /// (`n_dot_v` = N·V ≥ 0), seen along `v`: N·L, the specular term `Ks·max(0, R·V)^p` (zero
    /// where it cannot show) and the strength `I·att(d)` (zero in the lanes it does not reach);
    /// `None` when it faces or reaches none of them. A plain function rather than a closure
    /// handed to a shared loop: a closure is compiled apart, without the caller's AVX-512, and
    /// its lane arithmetic then becomes calls (Phong at 1920×1080 took 40% longer).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn light_terms<L: Lanes>(
        &self,
        i: usize,
        light: &Light,
        p: V3<L>,
        n: V3<L>,
        n_dot_v: L,
        v: V3<L>,
        m: &MaterialLanes<L>,
        lit: &mut impl FnMut(usize, &Light, L::Mask) -> L::Mask,
    ) -> Option<LightTerms<L>> {
        let zero = L::splat(0.0);
        let to_light = V3::splat(light.position) - p;
        let d = to_light.length_squared().sqrt();
        let inv_d = L::splat(1.0) / d;
        // A point at the light (d = 0) makes this NaN, which fails the test below.
        let n_dot_l = n.dot(to_light) * inv_d;
        let facing = n_dot_l.gt(zero);
        if !L::any(facing) {
            return None;
        }
        let reached = lit(i, light, facing);
        if !L::any(reached) {
            return None;
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
        Some(LightTerms {
            n_dot_l,
            specular,
            strength,
        })
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

/// What one light gives a point: see [`Lighting::light_terms`].
struct LightTerms<L> {
    n_dot_l: L,
    specular: L,
    strength: L,
}

/// The normal `n` turned toward the viewer (along `v`) where it faces away, and N·V after.
#[inline(always)]
fn toward_viewer<L: Lanes>(n: V3<L>, v: V3<L>) -> (V3<L>, L) {
    let n_dot_v = n.dot(v);
    let flip = n_dot_v.lt(L::splat(0.0));
    (V3::negate_where(flip, n), L::negate_where(flip, n_dot_v))
}

#[cfg(test)]
mod tests;
