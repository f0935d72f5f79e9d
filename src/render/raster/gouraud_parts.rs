//! Gouraud shading with a per-pixel albedo (OpenGL's separate specular colour): where some mesh
//! has vertex colours, each vertex is lit with albedo 1 into its diffuse and ambient factor `D`
//! and its specular colour `S` ([`Lighting::shade_parts_lanes`]); both are interpolated with
//! the vertex colour, and each pixel takes `albedo ⊙ D + S`, the albedo being the material
//! colour times the interpolated vertex colour. A highlight keeps the light's colour whatever
//! the surface's. Three varyings: `D`, `S`, the vertex colour.
//!
//! A mesh without colours in such a world is lit as plain Gouraud shading lights it, its lit
//! colour carried as `D` (with `S` = 0 and vertex colour 1, unused): its pixels take the
//! interpolated `D` as it is, the bits of a world without colours.

use glam::Vec3;

use super::colored::ColoredObjects;
use super::fragment_texels::fragment_texels;
use super::fragments::Fragments;
use super::gouraud::{light_whole, next_corners, objects_lit_whole};
use super::shader::Shader;
use super::varying::{NormalsColorsAndUvs, Varying};
use crate::mesh::Mesh;
use crate::render::camera::{View, Viewer};
use crate::render::materials::{MaterialLanes, ObjectMaterials};
use crate::render::prefetch;
use crate::render::shading::Lighting;
use crate::render::simd::{Lanes8, LanesJob, V3, WIDTH, run_on_best_lanes};
use crate::render::texturing::ObjectTextures;
use crate::world::World;

/// The vertex stage: `D` and `S` of each vertex (or, on a mesh without colours, its lit colour
/// and zero), and its colour. Lanes are independent, so a vertex gets the same values whichever
/// vertices share its lanes.
pub struct LitParts<'a> {
    world: &'a World,
    viewer: Viewer,
    lighting: Lighting<'a>,
    materials: ObjectMaterials,
    /// Per object, the two lit parts of every vertex, `D` (or the colour) for all vertices then
    /// `S` (or zero), for the objects lit whole this frame.
    whole: &'a mut Vec<Vec<Vec3>>,
    /// Which objects were lit whole this frame.
    lit_whole: Vec<bool>,
}

impl<'a> LitParts<'a> {
    /// The vertex stage of `world` seen from `eye`, lighting whole objects into `whole`, the
    /// renderer's scratch kept from frame to frame.
    pub fn new(world: &'a World, viewer: Viewer, whole: &'a mut Vec<Vec<Vec3>>) -> LitParts<'a> {
        LitParts {
            world,
            viewer,
            lighting: Lighting::new(world),
            materials: ObjectMaterials::new(world),
            whole,
            lit_whole: vec![false; world.objects.len()],
        }
    }

    /// The two parts at the eight vertices `p`, `n` of `object`, whose material is `material`.
    #[inline(always)]
    fn light<L: Lanes8>(
        &self,
        object: usize,
        material: &MaterialLanes<L>,
        p: V3<L>,
        n: V3<L>,
    ) -> (V3<L>, V3<L>) {
        let v = self.viewer.toward(p);
        let o = &self.world.objects[object];
        if o.mesh.colors.is_some() || o.is_textured() {
            self.lighting
                .shade_parts_lanes(p, n, v, material, |_, _, facing| facing)
        } else {
            let zero = L::splat(0.0);
            let c = self
                .lighting
                .shade_lanes(p, n, v, material, |_, _, facing| facing);
            (c, V3::new(zero, zero, zero))
        }
    }
}

impl Varying for LitParts<'_> {
    fn prepare(&mut self, triangles_needed: &[usize]) {
        let lit = objects_lit_whole(self.world, triangles_needed);
        let mut whole = std::mem::take(&mut *self.whole);
        let this = &*self;
        light_whole(self.world, &lit, &mut whole, |object, mesh, parts| {
            let count = mesh.positions.len();
            parts.clear();
            parts.resize(2 * count, Vec3::ZERO);
            let (first, second) = parts.split_at_mut(count);
            run_on_best_lanes(LightAll {
                lit: this,
                object,
                mesh,
                first,
                second,
            });
        });
        *self.whole = whole;
        self.lit_whole = lit;
    }

    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        let mesh = &self.world.objects[object].mesh;
        let colors = mesh.colors.as_deref();
        let color_corners =
            |abc: [u32; 3]| colors.map_or([Vec3::ONE; 3], |c| abc.map(|i| c[i as usize]));
        if self.lit_whole[object] {
            let parts = &self.whole[object];
            let count = mesh.positions.len();
            for &t in triangles {
                let abc = mesh.triangles[t as usize];
                out.push(abc.map(|i| parts[i as usize]));
                out.push(abc.map(|i| parts[count + i as usize]));
                out.push(color_corners(abc));
            }
            return;
        }
        // All the loads first, so that the misses overlap.
        for &t in triangles {
            for i in mesh.triangles[t as usize] {
                prefetch::ahead(&mesh.positions[i as usize]);
                prefetch::ahead(&mesh.normals[i as usize]);
            }
        }
        let corners = 3 * triangles.len();
        let mut parts = vec![Vec3::ZERO; 2 * corners];
        let (first, second) = parts.split_at_mut(corners);
        run_on_best_lanes(LightCorners {
            lit: self,
            object,
            triangles,
            first,
            second,
        });
        for (k, &t) in triangles.iter().enumerate() {
            let at = 3 * k;
            out.push([first[at], first[at + 1], first[at + 2]]);
            out.push([second[at], second[at + 1], second[at + 2]]);
            out.push(color_corners(mesh.triangles[t as usize]));
        }
    }

    fn prefetch(&self, object: usize, triangle: u32) {
        prefetch::ahead(&self.world.objects[object].mesh.triangles[triangle as usize]);
    }
}

/// Lights every vertex of `mesh` (of `object`), in order, into `first` and `second`.
struct LightAll<'a> {
    lit: &'a LitParts<'a>,
    object: usize,
    mesh: &'a Mesh,
    first: &'a mut [Vec3],
    second: &'a mut [Vec3],
}

impl LanesJob for LightAll<'_> {
    type Output = ();

    #[inline(always)]
    fn run<L: Lanes8>(self) {
        let material = &self.lit.materials.splat::<L>(self.object);
        let mesh = self.mesh;
        let vertices = mesh.positions.chunks(WIDTH).zip(mesh.normals.chunks(WIDTH));
        let outputs = self
            .first
            .chunks_mut(WIDTH)
            .zip(self.second.chunks_mut(WIDTH));
        for ((p, n), (first, second)) in vertices.zip(outputs) {
            let count = p.len();
            let (a, b) = self
                .lit
                .light(self.object, material, V3::gather(p), V3::gather(n));
            first.copy_from_slice(&a.to_vec3s()[..count]);
            second.copy_from_slice(&b.to_vec3s()[..count]);
        }
    }
}

/// Lights the corners of mesh triangles `triangles` of `object`, three per triangle into
/// `first` and `second`.
struct LightCorners<'a> {
    lit: &'a LitParts<'a>,
    object: usize,
    triangles: &'a [u32],
    first: &'a mut [Vec3],
    second: &'a mut [Vec3],
}

impl LanesJob for LightCorners<'_> {
    type Output = ();

    #[inline(always)]
    fn run<L: Lanes8>(self) {
        let mesh = &self.lit.world.objects[self.object].mesh;
        let material = &self.lit.materials.splat::<L>(self.object);
        let mut vertices = self
            .triangles
            .iter()
            .flat_map(|&t| mesh.triangles[t as usize])
            .map(|i| i as usize);
        let outputs = self
            .first
            .chunks_mut(WIDTH)
            .zip(self.second.chunks_mut(WIDTH));
        for (first, second) in outputs {
            let count = first.len();
            let (p, n) = next_corners(mesh, &mut vertices, count);
            let (a, b) = self.lit.light(self.object, material, p, n);
            first.copy_from_slice(&a.to_vec3s()[..count]);
            second.copy_from_slice(&b.to_vec3s()[..count]);
        }
    }
}

/// The fragment stage: `albedo ⊙ D + S` from the three interpolated varyings, the albedo the
/// material colour times the vertex colour, on meshes with colours; `D`, the lit colour, on
/// the others.
pub struct SeparateSpecular {
    /// Per object, the colour the interpolated vertex colour is multiplied by: the material
    /// colour on a mesh with colours, white on one without (unused).
    albedo: Vec<Vec3>,
    colored: ColoredObjects,
}

impl SeparateSpecular {
    /// The albedo colours of `world`'s objects.
    pub fn new(world: &World) -> SeparateSpecular {
        SeparateSpecular {
            albedo: world
                .objects
                .iter()
                .map(|o| match o.mesh.colors.is_some() || o.is_textured() {
                    true => o.material.color,
                    false => Vec3::ONE,
                })
                .collect(),
            colored: ColoredObjects::with_textures(world),
        }
    }

    /// The material colours of `fragments`' objects (white where the lit colour is kept).
    #[inline(always)]
    fn albedo<L: Lanes8>(&self, objects: &[u32; WIDTH]) -> V3<L> {
        if objects.iter().all(|&o| o == objects[0]) {
            V3::splat(self.albedo[objects[0] as usize])
        } else {
            V3::gather(&objects.map(|o| self.albedo[o as usize]))
        }
    }
}

impl Shader<3> for SeparateSpecular {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L, 3>, row: &mut [Vec3]) {
        let objects = &fragments.object;
        let albedo = self.albedo(objects);
        let [diffuse, specular, color] = fragments.varying;
        let lit = albedo.mul_elements(color).mul_elements(diffuse);
        let c = V3::new(lit.x + specular.x, lit.y + specular.y, lit.z + specular.z);
        fragments.write(self.colored.select(objects, c, diffuse), row);
    }
}

/// The vertex stage where some mesh is textured: [`LitParts`]' `D`, `S` and colour (the colour
/// left out where no mesh has vertex colours, `colors` false), then the texture coordinates and
/// texel density and the vertex normal of [`NormalsColorsAndUvs::without_colors`] (the normal
/// for the footprint's cosine, as Phong takes it).
pub struct TexturedParts<'a> {
    pub parts: LitParts<'a>,
    pub uvs: NormalsColorsAndUvs<'a>,
    pub colors: bool,
}

impl Varying for TexturedParts<'_> {
    fn prepare(&mut self, triangles_needed: &[usize]) {
        self.parts.prepare(triangles_needed);
    }

    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        let start = out.len();
        self.parts.corners(object, triangles, out);
        let lit = out.split_off(start);
        let mut more = Vec::with_capacity(2 * triangles.len());
        self.uvs.corners(object, triangles, &mut more);
        let kept = if self.colors { 3 } else { 2 };
        for (lit, more) in lit.chunks_exact(3).zip(more.chunks_exact(2)) {
            out.extend_from_slice(&lit[..kept]);
            out.push(more[1]);
            out.push(more[0]);
        }
    }

    fn prefetch(&self, object: usize, triangle: u32) {
        self.parts.prefetch(object, triangle);
    }
}

/// The fragment stage with textures: [`SeparateSpecular`] with the albedo also times the
/// texture's colour on textured meshes, the level chosen as Phong chooses it.
pub struct TexturedSeparateSpecular<'a> {
    pub plain: SeparateSpecular,
    pub view: &'a View,
    pub textures: ObjectTextures<'a>,
}

impl TexturedSeparateSpecular<'_> {
    /// `albedo ⊙ D + S` of `fragments`, the albedo their material colour times `color` times
    /// their texture colour (from `normal` and `uvd`), where the object is textured or coloured;
    /// `D` elsewhere.
    #[inline(always)]
    fn shade_parts<L: Lanes8, const K: usize>(
        &self,
        fragments: &Fragments<L, K>,
        [diffuse, specular, normal, uvd]: [V3<L>; 4],
        color: Option<V3<L>>,
        row: &mut [Vec3],
    ) {
        let objects = &fragments.object;
        let texels = fragment_texels(&self.textures, self.view, fragments, normal, uvd);
        let albedo = self.plain.albedo::<L>(objects).mul_elements(texels);
        let albedo = color.map_or(albedo, |color| albedo.mul_elements(color));
        let lit = albedo.mul_elements(diffuse);
        let c = V3::new(lit.x + specular.x, lit.y + specular.y, lit.z + specular.z);
        fragments.write(self.plain.colored.select(objects, c, diffuse), row);
    }
}

/// With vertex colours: `D`, `S`, the colour, (u, v, density), the normal.
impl Shader<5> for TexturedSeparateSpecular<'_> {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L, 5>, row: &mut [Vec3]) {
        let [diffuse, specular, color, uvd, normal] = fragments.varying;
        let parts = [diffuse, specular, normal, uvd];
        self.shade_parts(fragments, parts, Some(color), row);
    }
}

/// Where no mesh has vertex colours: `D`, `S`, (u, v, density), the normal. The albedo is the
/// material colour times the texture's, with no interpolated colour of 1 (not exactly 1 once
/// interpolated) multiplied in.
impl Shader<4> for TexturedSeparateSpecular<'_> {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L, 4>, row: &mut [Vec3]) {
        let [diffuse, specular, uvd, normal] = fragments.varying;
        self.shade_parts(fragments, [diffuse, specular, normal, uvd], None, row);
    }
}
