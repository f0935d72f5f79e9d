//! Z-buffer with Phong shading: interpolate the normal, light every pixel. Where some mesh has
//! vertex colours, the colour is interpolated too, a second varying, and the albedo of each
//! pixel is the material colour times it; a world without them keeps the one varying.

use glam::Vec3;

use super::colored::ColoredObjects;
use super::fragment_texels::fragment_texels;
use super::fragments::Fragments;
use super::setup::RasterScratch;
use super::shader::Shader;
use super::varying::{NormalsAndColors, NormalsColorsAndUvs, PerVertex};
use super::zbuffer::draw;
use crate::render::camera::View;
use crate::render::materials::{MaterialLanes, ObjectMaterials};
use crate::render::progress::{Cancelled, Progress};
use crate::render::shading::Lighting;
use crate::render::simd::{Lanes, Lanes8, V3};
use crate::render::texturing::ObjectTextures;
use crate::world::World;

/// Renders `world` through `view` into `out` (`view.width`×`view.height` pixels).
pub fn render_phong(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let shader = PhongShader::new(world, view);
    let textured = UncoloredTextures(&shader);
    draw_normals(scratch, world, view, progress, &shader, &textured, out)
}

/// Draws with `shader`, the vertex normals as the varying, the vertex colours as a second one
/// where some mesh of `world` has them, and the texture coordinates as a third where some mesh
/// is textured (as the second, with `textured`, where no mesh has colours).
fn draw_normals<S: Shader<1> + Shader<2> + Shader<3>>(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    shader: &S,
    textured: &impl Shader<2>,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let geometry = &mut scratch.geometry;
    let colored = world.objects.iter().any(|o| o.mesh.colors.is_some());
    if world.objects.iter().any(|o| o.is_textured()) {
        if !colored {
            let varyings = &mut NormalsColorsAndUvs::without_colors(world);
            return draw::<2>(geometry, world, view, progress, varyings, textured, out);
        }
        let varyings = &mut NormalsColorsAndUvs::new(world);
        return draw::<3>(geometry, world, view, progress, varyings, shader, out);
    }
    if colored {
        let varyings = &mut NormalsAndColors::new(world);
        return draw::<2>(geometry, world, view, progress, varyings, shader, out);
    }
    let normals = &mut PerVertex::normals(world);
    draw::<1>(geometry, world, view, progress, normals, shader, out)
}

/// [`render_phong`] lighting every batch of eight pixels alone, never two at once: what the
/// pairs must give, bit for bit.
#[cfg(test)]
pub(super) fn render_phong_unpaired(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    /// `S`, one batch at a time.
    struct OneAtATime<'s, S>(&'s S);
    impl<S: Shader<K>, const K: usize> Shader<K> for OneAtATime<'_, S> {
        fn shade<L: Lanes8>(&self, fragments: &Fragments<L, K>, row: &mut [Vec3]) {
            self.0.shade(fragments, row);
        }
    }
    let phong = PhongShader::new(world, view);
    let uncolored = UncoloredTextures(&phong);
    let (shader, textured) = (OneAtATime(&phong), OneAtATime(&uncolored));
    draw_normals(scratch, world, view, progress, &shader, &textured, out)
}

/// Lights every pixel with its interpolated normal. The surface point is found on the pixel's
/// ray at the interpolated depth, which is the perspective-correct interpolated position, and
/// the very point the ray tracer's primary ray meets.
struct PhongShader<'a> {
    view: &'a View,
    lighting: Lighting<'a>,
    materials: ObjectMaterials,
    colored: ColoredObjects,
    textures: ObjectTextures<'a>,
}

impl Shader<1> for PhongShader<'_> {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L>, row: &mut [Vec3]) {
        let color = self.light(
            fragments.columns(),
            fragments.y,
            fragments.depth,
            fragments.varying[0],
            &self.materials.of_lanes(&fragments.object),
        );
        fragments.write(color, row);
    }

    const SHADES_TWO: bool = true;

    #[inline(always)]
    fn shade_two<L: Lanes8>(&self, low: &Fragments<L>, high: &Fragments<L>, row: &mut [Vec3]) {
        debug_assert_eq!(low.y, high.y);
        let color = self.light(
            L::pair(low.columns(), high.columns()),
            low.y,
            L::pair(low.depth, high.depth),
            V3::pair(low.varying[0], high.varying[0]),
            &self.materials.of_pair::<L>(&low.object, &high.object),
        );
        let (low_color, high_color) = V3::halves(color);
        low.write(low_color, row);
        high.write(high_color, row);
    }
}

/// `Shader<K>` for `$shader`, whose Phong shader is `$phong` (an expression of `$s`, the
/// shader), finding each fragment's albedo the way `$albedo` says; one batch or two at once.
macro_rules! albedo_shader {
    ($shader:ty, $k:literal, $albedo:ty, |$s:ident| $phong:expr) => {
        impl Shader<$k> for $shader {
            #[inline(always)]
            fn shade<L: Lanes8>(&self, fragments: &Fragments<L, $k>, row: &mut [Vec3]) {
                let $s = self;
                $phong.shade_albedo::<$albedo, L, $k>(fragments, row);
            }

            const SHADES_TWO: bool = true;

            #[inline(always)]
            fn shade_two<L: Lanes8>(
                &self,
                low: &Fragments<L, $k>,
                high: &Fragments<L, $k>,
                row: &mut [Vec3],
            ) {
                let $s = self;
                $phong.shade_two_albedo::<$albedo, L, $k>(low, high, row);
            }
        }
    };
}

// With the vertex colour as the second varying: the albedo is the material colour times it,
// on meshes with colours; the others keep their material colour as it is.
albedo_shader!(PhongShader<'_>, 2, VertexColors, |s| s);

// With the texture coordinates as the third varying: the albedo is also times the texture's
// colour, on textured meshes, at the level of the pixel's footprint (see
// [`crate::render::texturing`]); other meshes are multiplied by exactly 1.
albedo_shader!(PhongShader<'_>, 3, ColorsAndTexture, |s| s);

/// Phong's shader where some mesh is textured and none has vertex colours: the second varying
/// is the texture coordinates and density, and the albedo is the material colour times the
/// texture's colour, the bits [`PhongShader`]'s three varyings give (which multiply no colour
/// in on meshes without colours).
struct UncoloredTextures<'s, 'a>(&'s PhongShader<'a>);

albedo_shader!(UncoloredTextures<'_, '_>, 2, TextureOnly, |s| s.0);

/// How Phong finds the albedo of fragments with `K` varyings from their material colours.
/// Types, not closures: a closure is not inlined into the caller's AVX context.
trait Albedo<const K: usize> {
    /// The albedo of `fragments` whose material colours are `color`.
    fn albedo<L: Lanes8>(phong: &PhongShader, fragments: &Fragments<L, K>, color: V3<L>) -> V3<L>;
}

/// Times the vertex colour, the second varying ([`PhongShader::albedo`]).
struct VertexColors;

impl Albedo<2> for VertexColors {
    #[inline(always)]
    fn albedo<L: Lanes8>(phong: &PhongShader, fragments: &Fragments<L, 2>, color: V3<L>) -> V3<L> {
        phong.albedo(fragments, color)
    }
}

/// Times the vertex colour and the texture ([`PhongShader::textured_albedo`]).
struct ColorsAndTexture;

impl Albedo<3> for ColorsAndTexture {
    #[inline(always)]
    fn albedo<L: Lanes8>(phong: &PhongShader, fragments: &Fragments<L, 3>, color: V3<L>) -> V3<L> {
        phong.textured_albedo(fragments, color)
    }
}

/// Times the texture, the texture coordinates and density the second varying.
struct TextureOnly;

impl Albedo<2> for TextureOnly {
    #[inline(always)]
    fn albedo<L: Lanes8>(phong: &PhongShader, fragments: &Fragments<L, 2>, color: V3<L>) -> V3<L> {
        phong.times_texels(fragments, fragments.varying[1], color)
    }
}

impl PhongShader<'_> {
    /// Lights `fragments` with their albedo as `A` finds it, into `row`.
    #[inline(always)]
    fn shade_albedo<A: Albedo<K>, L: Lanes8, const K: usize>(
        &self,
        fragments: &Fragments<L, K>,
        row: &mut [Vec3],
    ) {
        let mut material = self.materials.of_lanes(&fragments.object);
        material.color = A::albedo(self, fragments, material.color);
        self.light_fragments(fragments, &material, row);
    }

    /// Lights batches `low` and `high` of one row at once with their albedo as `A` finds it.
    #[inline(always)]
    fn shade_two_albedo<A: Albedo<K>, L: Lanes8, const K: usize>(
        &self,
        low: &Fragments<L, K>,
        high: &Fragments<L, K>,
        row: &mut [Vec3],
    ) {
        debug_assert_eq!(low.y, high.y);
        let mut material = self.materials.of_pair::<L>(&low.object, &high.object);
        let (low_color, high_color) = V3::halves(material.color);
        // Each batch's albedo alone: the bits of lighting it alone.
        material.color = V3::pair(
            A::albedo(self, low, low_color),
            A::albedo(self, high, high_color),
        );
        self.light_two(low, high, &material, row);
    }
}

impl<'a> PhongShader<'a> {
    /// Lights two batches `low` and `high` of one row (the normal their first varying) with
    /// `material`, both batches' lanes side by side, into `row`.
    #[inline(always)]
    fn light_two<L: Lanes8, const K: usize>(
        &self,
        low: &Fragments<L, K>,
        high: &Fragments<L, K>,
        material: &MaterialLanes<L::Pair>,
        row: &mut [Vec3],
    ) {
        let color = self.light(
            L::pair(low.columns(), high.columns()),
            low.y,
            L::pair(low.depth, high.depth),
            V3::pair(low.varying[0], high.varying[0]),
            material,
        );
        let (low_color, high_color) = V3::halves(color);
        low.write(low_color, row);
        high.write(high_color, row);
    }

    /// Lights `fragments` (the normal their first varying) with `material` into `row`.
    #[inline(always)]
    fn light_fragments<L: Lanes8, const K: usize>(
        &self,
        fragments: &Fragments<L, K>,
        material: &MaterialLanes<L>,
        row: &mut [Vec3],
    ) {
        let color = self.light(
            fragments.columns(),
            fragments.y,
            fragments.depth,
            fragments.varying[0],
            material,
        );
        fragments.write(color, row);
    }

    /// Lights `world`'s materials with its lights, seen through `view`.
    fn new(world: &'a World, view: &'a View) -> PhongShader<'a> {
        PhongShader {
            view,
            lighting: Lighting::new(world),
            materials: ObjectMaterials::new(world),
            colored: ColoredObjects::new(world),
            textures: ObjectTextures::new(world, view),
        }
    }

    /// The albedo of `fragments` whose material colours are `color`: times the interpolated
    /// vertex colour (the second varying) in the lanes whose object has colours, then times the
    /// texture colour (from the normal, the first varying, and the texture coordinates and
    /// density, the third).
    #[inline(always)]
    fn textured_albedo<L: Lanes8>(&self, fragments: &Fragments<L, 3>, color: V3<L>) -> V3<L> {
        let color = self.albedo(fragments, color);
        self.times_texels(fragments, fragments.varying[2], color)
    }

    /// `color` times the texture colour of `fragments` (the normal their first varying) with
    /// texture coordinates and density `uvd`.
    #[inline(always)]
    fn times_texels<L: Lanes8, const K: usize>(
        &self,
        fragments: &Fragments<L, K>,
        uvd: V3<L>,
        color: V3<L>,
    ) -> V3<L> {
        let normal = fragments.varying[0];
        let texels = fragment_texels(&self.textures, self.view, fragments, normal, uvd);
        color.mul_elements(texels)
    }

    /// The albedo of `fragments` whose material colours are `color`: times the interpolated
    /// vertex colour (the second varying) in the lanes whose object has colours.
    #[inline(always)]
    fn albedo<L: Lanes8, const K: usize>(
        &self,
        fragments: &Fragments<L, K>,
        color: V3<L>,
    ) -> V3<L> {
        let tinted = color.mul_elements(fragments.varying[1]);
        self.colored.select(&fragments.object, tinted, color)
    }

    /// The colours of pixels in columns `x` of row `y` whose surface lies at depth `depth` on
    /// their rays, with interpolated normals `varying` and materials `material`: each lane as
    /// it would be alone.
    #[inline(always)]
    fn light<P: Lanes>(
        &self,
        x: P,
        y: u32,
        depth: P,
        varying: V3<P>,
        material: &MaterialLanes<P>,
    ) -> V3<P> {
        let (p, v) = self
            .view
            .surface_point(x + P::splat(0.5), P::splat(y as f32 + 0.5), depth);
        let n = varying.normalize_or_zero();
        self.lighting
            .shade_lanes(p, n, v, material, |_, _, facing| facing)
    }
}
