//! Textures as all three algorithms read them: the texture coordinates at a point and the level
//! of detail from the pixel's footprint there, worked out by one formula so that Phong and the
//! ray tracer choose the same level.
//!
//! The footprint is a ray cone: a pixel spans the angle `spread` = 2·tan(fov/2) / image height
//! (radians, small), so at distance `d` along its ray (the whole path, reflections included:
//! a mirror widens the cone as far again) it is `spread·d` wide, and on a surface whose normal
//! makes cosine `cos` with the ray it covers `(spread·d)² / |cos|` of area. A triangle maps
//! world area to texture area by its texel density (UV area / world area), so the footprint
//! covers `texels × density × area` texels of level 0, and the level is half the base-2
//! logarithm of that. An orthographic view's rays are parallel: its pixel is
//! `2·half_height / image height` wide at every distance (`base`, world units), and `spread` is 0.
//! The Z-buffer takes the depth and normal of its pixel, the ray tracer
//! those of its hit: the same numbers, so the same level.

use glam::{Vec2, Vec3, Vec4};

use crate::mesh::Mesh;
use crate::mesh::texture::{AlphaMode, TextureBinding};
use crate::render::camera::View;
use crate::render::simd::{Lanes, coarse_log2};
use crate::world::{World, WorldObject};

/// Steepest incidence the footprint is widened for: at grazing angles beyond it (cosine below
/// 1/64) the level stops growing, as a GPU's anisotropy limit does.
const MIN_COSINE: f32 = 1.0 / 64.0;

/// A part's alpha cut-out (glTF `alphaMode: MASK`) as the renderers test it.
struct Mask<'a> {
    /// A point whose alpha is below this is no surface.
    cutoff: f32,
    /// The base colour factor's alpha.
    factor: f32,
    /// The texture whose alpha multiplies in, with the mesh's coordinates, when drawn textured.
    texture: Option<(&'a TextureBinding, &'a [Vec2])>,
    /// The vertex alpha at each triangle's corners, which multiplies in, when it has one.
    corner_alphas: Option<&'a [[f32; 3]]>,
}

/// The textures of a world's objects and the cone spread of the view.
pub struct ObjectTextures<'a> {
    /// Per object, its texture and its mesh's texture coordinates, when it is drawn textured.
    textured: Vec<Option<(&'a TextureBinding, &'a [Vec2])>>,
    /// Whether any object is textured: worlds without textures skip every lookup.
    pub any: bool,
    /// Per object, its alpha cut-out, when its appearance is `MASK`.
    masks: Vec<Option<Mask<'a>>>,
    /// Whether any object is cut out: worlds without masks never test alpha.
    pub any_mask: bool,
    /// The objects, whose instances' shared meshes are in their own space: their corners are
    /// moved out ([`WorldObject::world_corners`]) before any footprint is measured.
    objects: &'a [WorldObject],
    /// The angle a pixel spans, radians.
    spread: f32,
    /// The width a pixel spans at distance 0, world units (orthographic views; 0 in perspective).
    base: f32,
}

impl<'a> ObjectTextures<'a> {
    /// The textures of `world`'s objects, seen through `view`.
    pub fn new(world: &'a World, view: &View) -> ObjectTextures<'a> {
        let pixel = 2.0 * view.half_height / view.image_height as f32;
        if view.orthographic {
            ObjectTextures {
                base: pixel,
                ..ObjectTextures::with_spread(world, 0.0)
            }
        } else {
            ObjectTextures::with_spread(world, pixel)
        }
    }

    /// The textures of `world`'s objects, a pixel spanning `spread` radians (0: every lookup
    /// reads the finest level).
    pub fn with_spread(world: &'a World, spread: f32) -> ObjectTextures<'a> {
        let textured: Vec<_> = world
            .objects
            .iter()
            .map(|o| match (&o.appearance.base_color, &o.local_mesh().uvs) {
                (Some(binding), Some(uvs)) => Some((binding, &uvs[..])),
                _ => None,
            })
            .collect();
        let masks: Vec<_> = world
            .objects
            .iter()
            .zip(&textured)
            .map(|(o, texture)| match o.appearance.alpha_mode {
                AlphaMode::Opaque => None,
                AlphaMode::Mask { cutoff } => Some(Mask {
                    cutoff,
                    factor: o.appearance.alpha_factor,
                    texture: *texture,
                    corner_alphas: o.appearance.corner_alphas.as_deref(),
                }),
            })
            .collect();
        ObjectTextures {
            objects: &world.objects,
            any: textured.iter().any(Option::is_some),
            textured,
            any_mask: masks.iter().any(Option::is_some),
            masks,
            spread,
            base: 0.0,
        }
    }

    /// Whether object `object` is cut out by alpha (its appearance is `MASK`).
    #[inline]
    pub fn is_masked(&self, object: usize) -> bool {
        self.masks[object].is_some()
    }

    /// Whether the point at barycentrics (`u`, `v`) (the weights of the second and third
    /// corners) of triangle `triangle` of object `object` (whose mesh is `mesh`) is cut out:
    /// its alpha, the base colour factor's times the texture's (read as the colour is, at path
    /// length `distance` along unit `dir`, the normal interpolated there) times the vertex
    /// alpha interpolated there, is below the cutoff.
    /// Always false on an object that is not masked.
    #[allow(clippy::too_many_arguments)]
    pub fn is_cut(
        &self,
        object: usize,
        mesh: &Mesh,
        triangle: u32,
        u: f32,
        v: f32,
        distance: f32,
        dir: Vec3,
    ) -> bool {
        let Some(mask) = &self.masks[object] else {
            return false;
        };
        let mut alpha = mask.factor;
        if let Some(corners) = mask.corner_alphas {
            let [a, b, c] = corners[triangle as usize];
            alpha *= a * (1.0 - u - v) + b * u + c * v;
        }
        if let Some((binding, uvs)) = mask.texture {
            let abc = mesh.triangles[triangle as usize].map(|i| i as usize);
            let w = [1.0 - u - v, u, v];
            let uv = abc.map(|i| uvs[i]);
            let (p, normals) = self.objects[object].world_corners(triangle);
            let at = uv[0] * w[0] + uv[1] * w[1] + uv[2] * w[2];
            let n = normals
                .iter()
                .zip(w)
                .map(|(&n, w)| n * w)
                .sum::<Vec3>()
                .normalize_or_zero();
            let density = texel_density(p, uv);
            alpha *= self
                .sample_binding(binding, at, density, distance, n.dot(dir))
                .w;
        }
        alpha < mask.cutoff
    }

    /// Whether object `object` is drawn textured.
    #[inline]
    pub fn is_textured(&self, object: usize) -> bool {
        self.textured[object].is_some()
    }

    /// The texture coordinates at the corners of triangle `triangle` of object `object` (whose
    /// mesh is `mesh`), and the triangle's texel density; `None` for an untextured object.
    #[inline]
    pub fn corners(&self, object: usize, mesh: &Mesh, triangle: u32) -> Option<([Vec2; 3], f32)> {
        let (_, uvs) = self.textured[object]?;
        let abc = mesh.triangles[triangle as usize];
        let uv = abc.map(|i| uvs[i as usize]);
        let p = match &self.objects[object].instance {
            Some(instance) => instance.corners(abc).0,
            None => abc.map(|i| mesh.positions[i as usize]),
        };
        Some((uv, texel_density(p, uv)))
    }

    /// The linear RGBA texture colour of object `object` (textured) at `uv`, on a triangle of
    /// texel density `density`, seen at path length `distance` along a ray whose direction
    /// makes cosine `cos` with the surface normal.
    #[inline]
    pub fn sample(&self, object: usize, uv: Vec2, density: f32, distance: f32, cos: f32) -> Vec4 {
        let Some((binding, _)) = self.textured[object] else {
            return Vec4::ONE;
        };
        self.sample_binding(binding, uv, density, distance, cos)
    }

    /// The texture and sampler of object `object`, when it is drawn textured.
    #[inline]
    pub fn binding(&self, object: usize) -> Option<&'a TextureBinding> {
        self.textured[object].map(|(binding, _)| binding)
    }

    /// The texels of level 0 of object `object`'s texture (0 when untextured), as an `f32`.
    #[inline]
    pub fn texel_count(&self, object: usize) -> f32 {
        match self.textured[object] {
            Some((binding, _)) => {
                let (w, h) = binding.texture.size();
                w as f32 * h as f32
            }
            None => 0.0,
        }
    }

    /// The linear RGBA colour of object `object` (textured) at `uv` at level of detail `lod`
    /// ([`ObjectTextures::level_of_detail`]); white on an untextured object.
    #[inline(always)]
    pub fn sample_at_level(&self, object: usize, uv: Vec2, lod: f32) -> Vec4 {
        match self.textured[object] {
            Some((binding, _)) => binding.sampler.sample(&binding.texture, uv, lod),
            None => Vec4::ONE,
        }
    }

    /// The level of detail, per lane, of a texture of `texels` texels at level 0 on a triangle
    /// of texel density `density`, seen at path length `distance` along a ray whose direction
    /// makes cosine `cos` with the surface normal: half the base-2 logarithm of the texels the
    /// footprint covers. One lane (the ray tracer's) gives the bits of eight (the Z-buffer's).
    #[inline(always)]
    pub fn level_of_detail<L: Lanes>(&self, texels: L, density: L, distance: L, cos: L) -> L {
        let width = L::splat(self.base) + L::splat(self.spread) * distance;
        let slant = cos.max(-cos).max(L::splat(MIN_COSINE));
        let covered = texels * density * width * width / slant;
        L::splat(0.5) * coarse_log2(covered)
    }

    /// [`ObjectTextures::sample`] of `binding`.
    #[inline]
    fn sample_binding(
        &self,
        binding: &TextureBinding,
        uv: Vec2,
        density: f32,
        distance: f32,
        cos: f32,
    ) -> Vec4 {
        let texture = &binding.texture;
        let (w, h) = texture.size();
        let lod = self.level_of_detail(w as f32 * h as f32, density, distance, cos);
        binding.sampler.sample(texture, uv, lod)
    }
}

/// The ratio of a triangle's area in texture space (UV units²) to its area in the world (world
/// units²), for corners at `p` with coordinates `uv`; 0 for a triangle of no world area.
#[inline]
pub fn texel_density(p: [Vec3; 3], uv: [Vec2; 3]) -> f32 {
    let world = (p[1] - p[0]).cross(p[2] - p[0]).length();
    let texture = (uv[1] - uv[0]).perp_dot(uv[2] - uv[0]).abs();
    if world > 0.0 && world.is_finite() {
        texture / world
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn density_is_uv_area_over_world_area() {
        let p = [
            Vec3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ];
        let uv = [Vec2::ZERO, Vec2::X, Vec2::Y];
        assert_eq!(texel_density(p, uv), 0.25);
        assert_eq!(texel_density([Vec3::ZERO; 3], uv), 0.0);
    }
}
