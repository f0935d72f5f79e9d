//! The lighting function against a direct transcription of the README's formula, and one lane
//! against eight: the ray tracer and the Z-buffer must light a point to the same bits.

use std::f32::consts::{PI, TAU};

use glam::Vec3;
use proptest::prelude::*;

use super::Lighting;
use crate::render::materials::{MaterialLanes, SPECULAR_FLOOR};
use crate::render::simd::{F32x8, V3, WIDTH};
use crate::scene::{Falloff, Light, Material};

/// A unit vector from two angles in radians.
fn direction(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    )
}

/// One shading problem: a point, its normal, the view direction, a material and two lights.
#[derive(Debug, Clone)]
struct Case {
    p: Vec3,
    n: Vec3,
    v: Vec3,
    material: Material,
    lights: Vec<Light>,
}

fn case() -> impl Strategy<Value = Case> {
    let vector = || (-3.0f32..3.0, -3.0f32..3.0, -3.0f32..3.0).prop_map(Vec3::from);
    let unit = || (0.0f32..PI, 0.0f32..TAU).prop_map(|(t, f)| direction(t, f));
    let light = (
        vector(),
        0.0f32..2.0,
        (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0),
    )
        .prop_map(|(offset, intensity, (r, g, b))| Light {
            position: offset * 2.0 + Vec3::new(0.0, 5.0, 0.0),
            intensity,
            color: Vec3::new(r, g, b),
            ..Light::default()
        });
    let material = (
        (0.0f32..=1.0, 0.0f32..=1.0, 0.0f32..=1.0),
        0.0f32..=1.0,
        0.0f32..=1.0,
        0.0f32..300.0,
    )
        .prop_map(|((r, g, b), diffuse, specular, shininess)| Material {
            color: Vec3::new(r, g, b),
            diffuse,
            specular,
            shininess,
            reflection: 0.0,
        });
    (
        vector(),
        unit(),
        unit(),
        material,
        prop::collection::vec(light, 1..4),
    )
        .prop_map(|(p, n, v, material, lights)| Case {
            p,
            n,
            v,
            material,
            lights,
        })
}

/// The README's formula, transcribed with glam and libm:
/// C = Ia·color + Σ I·att(d)·Lc ⊙ (Kd·max(0, N·L)·color + Ks·max(0, R·V)^p), specular only where
/// N·L > 0, the normal flipped toward the viewer.
fn reference(c: &Case, ambient: f32, falloff: Option<Falloff>) -> Vec3 {
    let m = &c.material;
    let n = if c.n.dot(c.v) < 0.0 { -c.n } else { c.n };
    let mut color = ambient * m.color;
    for light in &c.lights {
        let to_light = light.position - c.p;
        let l = to_light.normalize();
        let n_dot_l = n.dot(l);
        if n_dot_l <= 0.0 {
            continue;
        }
        let r = 2.0 * n_dot_l * n - l;
        let specular = m.specular * r.dot(c.v).max(0.0).powf(m.shininess);
        let att = falloff.map_or(1.0, |f| f.attenuation(to_light.length()));
        color += light.intensity * att * light.color * (m.diffuse * n_dot_l * m.color + specular);
    }
    color
}

fn brightest(lights: &[Light]) -> f32 {
    lights
        .iter()
        .map(|l| l.intensity * l.color.max_element())
        .fold(0.0, f32::max)
}

proptest! {
    #[test]
    fn the_lighting_function_is_the_readme_formula(
        c in case(),
        ambient in 0.0f32..=1.0,
        linear in 0.0f32..0.5,
        quadratic in 0.0f32..0.5,
    ) {
        for falloff in [None, Falloff::new(linear, quadratic)] {
            let lighting = Lighting {
                lights: &c.lights,
                ambient,
                falloff,
            };
            let m = MaterialLanes::new(&c.material, brightest(&c.lights));
            let got = lighting.shade(c.p, c.n, c.v, &m, |_, _| true);
            let want = reference(&c, ambient, falloff);
            // f32 rounding, plus the highlights dropped below the floor (one per light at most).
            let tolerance = 1e-4 * want.max_element().max(1.0) + c.lights.len() as f32 * SPECULAR_FLOOR;
            prop_assert!(
                (got - want).abs().max_element() <= tolerance,
                "got {got}, formula {want}, tolerance {tolerance}"
            );
        }
    }

    #[test]
    fn eight_lanes_give_the_bits_of_one(cases in prop::collection::vec(case(), WIDTH)) {
        // The ray tracer lights one point at a time and the Z-buffer eight: a lane must be the
        // same to the bit, or the two would disagree where the design says they agree. All lanes
        // share the first case's lights.
        let lights = cases[0].lights.clone();
        let lighting = Lighting { lights: &lights, ambient: 0.1, falloff: None };
        let singles: Vec<MaterialLanes<f32>> = cases
            .iter()
            .map(|c| MaterialLanes::new(&c.material, brightest(&lights)))
            .collect();
        let lanes = |f: &dyn Fn(&Case) -> Vec3| {
            let vectors: Vec<Vec3> = cases.iter().map(f).collect();
            V3::<F32x8>::gather(&vectors)
        };
        let material = MaterialLanes::gather(std::array::from_fn(|k| &singles[k]));
        let many = lighting
            .shade_lanes(lanes(&|c| c.p), lanes(&|c| c.n), lanes(&|c| c.v), &material, |_, _, f| f)
            .to_vec3s();
        for (k, c) in cases.iter().enumerate() {
            let one = lighting.shade(c.p, c.n, c.v, &singles[k], |_, _| true);
            prop_assert_eq!(one.to_array().map(f32::to_bits), many[k].to_array().map(f32::to_bits));
        }
    }
}

#[test]
fn a_highlight_below_the_floor_is_dropped_and_one_above_is_kept() {
    let lights = [Light {
        position: Vec3::new(0.0, 0.0, 10.0),
        intensity: 1.0,
        color: Vec3::ONE,
        ..Light::default()
    }];
    let lighting = Lighting {
        lights: &lights,
        ambient: 0.0,
        falloff: None,
    };
    let material = Material {
        color: Vec3::ZERO,
        diffuse: 0.0,
        specular: 1.0,
        shininess: 100.0,
        reflection: 0.0,
    };
    let m = MaterialLanes::new(&material, 1.0);
    // Cutoff: (2^-14)^(1/100) = 0.9074.
    assert!(
        (m.specular_cutoff - 0.907_4).abs() < 1e-3,
        "{}",
        m.specular_cutoff
    );
    // A point on the light's axis seen along a direction whose R·V is just above or below it.
    let n = Vec3::Z;
    let shade = |r_dot_v: f32| {
        let v = Vec3::new((1.0 - r_dot_v * r_dot_v).sqrt(), 0.0, r_dot_v);
        lighting.shade(Vec3::ZERO, n, v, &m, |_, _| true).x
    };
    let above = shade(0.92);
    assert!((above - 0.92f32.powf(100.0)).abs() < 1e-6, "{above}");
    assert_eq!(shade(0.90), 0.0, "0.9^100 = 2.7e-5 is below the floor");
    // Without a highlight at all, the cutoff is unreachable.
    let matte = MaterialLanes::new(
        &Material {
            specular: 0.0,
            ..material
        },
        1.0,
    );
    assert!(matte.specular_cutoff > 1.0);
}
