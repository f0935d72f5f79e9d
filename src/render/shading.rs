//! The one lighting function every renderer calls: the Phong model summed over point lights.

use glam::{Vec3, Vec3A};

use crate::scene::{Falloff, Light, Material};

/// The lights and ambient term of a scene.
#[derive(Debug, Clone, Copy)]
pub struct Lighting<'a> {
    pub lights: &'a [Light],
    /// Ambient intensity Ia in [0, 1].
    pub ambient: f32,
    pub falloff: Falloff,
}

impl Lighting<'_> {
    /// Colour at point `p` with unit normal `n`, seen along unit `v` (from `p` toward the eye):
    ///
    /// `C = Ia·color + Σ I·att(d)·Lc ⊙ (Kd·max(0, N·L)·color + Ks·max(0, R·V)^p)`,
    /// L = normalize(Lp − p), R = reflect(−L, N), the specular term only where N·L > 0.
    /// A normal facing away from the viewer is flipped first. `lit(i, light)` says whether light
    /// `i` reaches `p` (the ray tracer's shadow test; always true for the Z-buffer).
    #[inline]
    pub fn shade(
        &self,
        p: Vec3,
        n: Vec3,
        v: Vec3,
        m: &Material,
        mut lit: impl FnMut(usize, &Light) -> bool,
    ) -> Vec3 {
        // SIMD vectors inside: this runs once per pixel for Phong and once per ray hit.
        let (p, v) = (Vec3A::from(p), Vec3A::from(v));
        let n = Vec3A::from(n);
        let n = if n.dot(v) < 0.0 { -n } else { n };
        let color = Vec3A::from(m.color);
        let mut c = color * self.ambient;
        for (i, light) in self.lights.iter().enumerate() {
            let to_light = Vec3A::from(light.position) - p;
            let d2 = to_light.length_squared();
            if d2 <= 0.0 {
                continue;
            }
            let inv_d = d2.sqrt().recip();
            let n_dot_l = n.dot(to_light) * inv_d;
            if n_dot_l <= 0.0 || !lit(i, light) {
                continue;
            }
            let l = to_light * inv_d;
            let r = 2.0 * n_dot_l * n - l; // reflect(−L, N)
            let r_dot_v = r.dot(v);
            let specular = if r_dot_v > 0.0 && m.specular > 0.0 {
                m.specular * r_dot_v.powf(m.shininess)
            } else {
                0.0
            };
            let mut strength = light.intensity;
            if self.falloff != Falloff::default() {
                strength *= self.falloff.attenuation(d2.sqrt());
            }
            c += strength
                * Vec3A::from(light.color)
                * (m.diffuse * n_dot_l * color + Vec3A::splat(specular));
        }
        c.into()
    }
}
