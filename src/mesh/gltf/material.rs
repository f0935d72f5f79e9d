//! glTF's metallic-roughness materials mapped onto rastray's Phong material.
//!
//! rastray lights with one Phong lobe (`Ks·max(0, R·V)^p`), a diffuse term (`Kd·N·L·color`) and,
//! in the ray tracer, a mirror term (`Kr·trace`). The mapping:
//! - colour = base colour factor (linear RGB, as glTF states it; alpha ignored);
//! - shininess p = 2/α² − 2 with α = roughness², the exponent whose Blinn–Phong lobe matches the
//!   GGX lobe of the same α; clamped to [1, 10000] (10000 is the scene's limit);
//! - specular Ks = F0·(p + 2)/(2π), at most 1: the peak of the energy-normalised lobe, with
//!   F0 = 0.04 for a dielectric blended toward the base colour's brightest channel by metallic;
//! - reflection Kr = metallic·(1 − roughness): polished metal is a mirror, rough metal is not;
//! - diffuse Kd = 1 − Kr: what the mirror takes no longer scatters.

use glam::Vec3;

use crate::scene::Material;

/// Largest Phong exponent a scene accepts.
const MAX_SHININESS: f32 = 10_000.0;
/// Reflectance at normal incidence of a typical dielectric (index of refraction 1.5).
const DIELECTRIC_F0: f32 = 0.04;

/// The Phong material for glTF factors: `base_color` linear RGB, `metallic` and `roughness`
/// in [0, 1] (values outside are clamped; NaN counts as 0).
pub fn phong_from_pbr(base_color: Vec3, metallic: f32, roughness: f32) -> Material {
    let unit = |x: f32| if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) };
    let color = Vec3::new(unit(base_color.x), unit(base_color.y), unit(base_color.z));
    let (metallic, roughness) = (unit(metallic), unit(roughness));
    let alpha = roughness * roughness;
    // p = 2/α² − 2; α = 0 (a perfect mirror) gives infinity, which the clamp turns into the limit.
    let shininess = (2.0 / (alpha * alpha) - 2.0).clamp(1.0, MAX_SHININESS);
    let f0 = DIELECTRIC_F0 + (color.max_element() - DIELECTRIC_F0) * metallic;
    let specular = (f0 * (shininess + 2.0) / std::f32::consts::TAU).min(1.0);
    let reflection = metallic * (1.0 - roughness);
    Material {
        color,
        diffuse: 1.0 - reflection,
        specular,
        shininess,
        reflection,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Object, Scene, Shape, validate};

    #[test]
    fn a_rough_dielectric_is_diffuse_with_no_mirror_and_a_faint_broad_highlight() {
        let m = phong_from_pbr(Vec3::new(0.8, 0.0, 0.0), 0.0, 1.0);
        assert_eq!(m.color, Vec3::new(0.8, 0.0, 0.0));
        assert_eq!(m.diffuse, 1.0);
        assert_eq!(m.reflection, 0.0);
        assert_eq!(m.shininess, 1.0, "2/1 − 2 = 0, clamped up to 1");
        assert!((m.specular - 0.04 * 3.0 / std::f32::consts::TAU).abs() < 1e-6);
    }

    #[test]
    fn half_rough_plastic_lands_near_the_default_material() {
        // α = 0.25: p = 2/0.0625 − 2 = 30; Ks = 0.04·32/2π ≈ 0.204.
        let m = phong_from_pbr(Vec3::splat(0.5), 0.0, 0.5);
        assert!((m.shininess - 30.0).abs() < 1e-3, "{}", m.shininess);
        assert!((m.specular - 0.2037).abs() < 1e-3, "{}", m.specular);
    }

    #[test]
    fn polished_metal_is_a_mirror_and_rough_metal_is_not() {
        let polished = phong_from_pbr(Vec3::new(1.0, 0.8, 0.3), 1.0, 0.0);
        assert_eq!(polished.reflection, 1.0);
        assert_eq!(polished.diffuse, 0.0);
        assert_eq!(polished.shininess, MAX_SHININESS);
        assert_eq!(polished.specular, 1.0);
        let rough = phong_from_pbr(Vec3::new(1.0, 0.8, 0.3), 1.0, 1.0);
        assert_eq!(rough.reflection, 0.0);
        assert_eq!(rough.diffuse, 1.0);
    }

    #[test]
    fn smoother_surfaces_get_tighter_highlights() {
        let exponents: Vec<f32> = [1.0, 0.8, 0.6, 0.4, 0.2, 0.1]
            .iter()
            .map(|&r| phong_from_pbr(Vec3::ONE, 0.0, r).shininess)
            .collect();
        assert!(exponents.windows(2).all(|w| w[0] < w[1]), "{exponents:?}");
    }

    #[test]
    fn out_of_range_and_nan_factors_still_give_a_valid_material() {
        for (c, m, r) in [
            (Vec3::new(2.0, -1.0, f32::NAN), 1.5, -0.5),
            (Vec3::ZERO, f32::NAN, f32::NAN),
            (Vec3::ONE, 0.3, 0.7),
        ] {
            let mut object = Object::new(Shape::Box {
                center: Vec3::ZERO,
                size: Vec3::ONE,
                segments: 1,
            });
            object.material = phong_from_pbr(c, m, r);
            let scene = Scene {
                objects: vec![object],
                ..Scene::default()
            };
            validate(&scene).unwrap_or_else(|e| panic!("{c} {m} {r}: {e:?}"));
        }
    }
}
