//! MTL materials mapped onto rastray's Phong material.
//!
//! MTL states the Phong model's own terms, so the mapping is direct:
//! - colour = `Kd`, each channel clamped to [0, 1] (linear, as exporters such as Blender write
//!   their base colour); diffuse Kd = 1, since `Kd` already holds the strength. With no `Kd`, the
//!   colour is white when the material has a `map_Kd` (the texture alone colours it), else
//!   rastray's default grey;
//! - specular Ks = the brightest channel of `Ks`, clamped to [0, 1] (rastray's highlight takes
//!   the light's colour, so a tint of `Ks` is lost); no `Ks` means no highlight;
//! - shininess p = `Ns`, clamped to [0, 10000] (MTL writes 0 to 1000); no `Ns`, the default 32;
//! - reflection Kr = 0 (`illum` modes with ray-traced reflection are read past).

use glam::Vec3;

use super::mtl::MtlMaterial;
use crate::scene::Material;
use crate::scene::limits::SHININESS;

/// The Phong material for an MTL block.
pub fn phong_from_mtl(mtl: &MtlMaterial) -> Material {
    let default = Material::default();
    let unit = |x: f32| x.clamp(0.0, 1.0);
    let color = match (mtl.diffuse, &mtl.diffuse_map) {
        (Some(kd), _) => kd.map(unit),
        (None, Some(_)) => Vec3::ONE,
        (None, None) => default.color,
    };
    let diffuse = if mtl.diffuse.is_some() || mtl.diffuse_map.is_some() {
        1.0
    } else {
        default.diffuse
    };
    Material {
        color,
        diffuse,
        specular: mtl.specular.map_or(0.0, |ks| unit(ks.max_element())),
        shininess: mtl
            .shininess
            .map_or(default.shininess, |p| p.clamp(SHININESS.min, SHININESS.max)),
        reflection: 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blenders_default_material_maps_term_by_term() {
        // As Blender 3.4 writes its default material.
        let m = phong_from_mtl(&MtlMaterial {
            name: "Material".into(),
            diffuse: Some(Vec3::splat(0.8)),
            specular: Some(Vec3::splat(0.5)),
            shininess: Some(250.0),
            diffuse_map: None,
        });
        assert_eq!(m.color, Vec3::splat(0.8));
        assert_eq!((m.diffuse, m.specular, m.shininess), (1.0, 0.5, 250.0));
        assert_eq!(m.reflection, 0.0);
    }

    #[test]
    fn out_of_range_values_are_clamped_and_absent_ones_defaulted() {
        let m = phong_from_mtl(&MtlMaterial {
            diffuse: Some(Vec3::new(2.0, -1.0, 0.5)),
            specular: Some(Vec3::new(0.1, 3.0, 0.2)),
            shininess: Some(1e9),
            ..MtlMaterial::default()
        });
        assert_eq!(m.color, Vec3::new(1.0, 0.0, 0.5));
        assert_eq!((m.specular, m.shininess), (1.0, 10_000.0));
        let textured = phong_from_mtl(&MtlMaterial {
            diffuse_map: Some("wood.png".into()),
            ..MtlMaterial::default()
        });
        assert_eq!(textured.color, Vec3::ONE, "the texture alone colours it");
        let bare = phong_from_mtl(&MtlMaterial::default());
        assert_eq!(bare.color, Material::default().color);
        assert_eq!(bare.specular, 0.0);
    }
}
