//! Z-buffer with Gouraud shading: light the vertices, interpolate the colour. Where some mesh
//! has vertex colours, the lit parts and the colour are interpolated apart instead
//! (`gouraud_parts`); a world without them is drawn here alone.
//!
//! Only vertices of triangles that a band shows are lit: at the editor's preview size most
//! triangles of a real mesh cover no pixel centre, and of those that do, about half are hidden
//! behind others. Where most of an object's vertices were needed in the last frame, the whole
//! object is lit at once, in order, beside the vertex stage.

use glam::Vec3;
use rayon::prelude::*;

use super::gouraud_parts::{LitParts, SeparateSpecular, TexturedParts, TexturedSeparateSpecular};
use super::setup::RasterScratch;
use super::shader::VaryingColor;
use super::varying::{NormalsColorsAndUvs, Varying};
use super::zbuffer::draw;
use crate::mesh::Mesh;
use crate::render::camera::{View, Viewer};
use crate::render::materials::{MaterialLanes, ObjectMaterials};
use crate::render::prefetch;
use crate::render::progress::{Cancelled, Progress};
use crate::render::shading::Lighting;
use crate::render::simd::{Lanes8, LanesJob, V3, WIDTH, run_on_best_lanes};
use crate::render::texturing::ObjectTextures;
use crate::world::World;

/// Renders `world` through `view` into `out` (`view.width`×`view.height` pixels).
pub fn render_gouraud(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    out: &mut [Vec3],
) -> Result<(), Cancelled> {
    let RasterScratch {
        geometry,
        per_vertex,
    } = scratch;
    let colors = world.objects.iter().any(|o| o.mesh.colors.is_some());
    if world.objects.iter().any(|o| o.is_textured()) {
        let mut parts = TexturedParts {
            parts: LitParts::new(world, view.viewer(), per_vertex),
            uvs: NormalsColorsAndUvs::without_colors(world),
            colors,
        };
        let shader = TexturedSeparateSpecular {
            plain: SeparateSpecular::new(world),
            view,
            textures: ObjectTextures::new(world, view),
        };
        return match colors {
            true => draw::<5>(geometry, world, view, progress, &mut parts, &shader, out),
            false => draw::<4>(geometry, world, view, progress, &mut parts, &shader, out),
        };
    }
    if colors {
        let mut parts = LitParts::new(world, view.viewer(), per_vertex);
        let shader = SeparateSpecular::new(world);
        return draw::<3>(geometry, world, view, progress, &mut parts, &shader, out);
    }
    let mut colors = LitVertices {
        world,
        viewer: view.viewer(),
        lighting: Lighting::new(world),
        materials: ObjectMaterials::new(world),
        whole: per_vertex,
        lit_whole: vec![false; world.objects.len()],
    };
    // Fragment stage: the interpolated colour is the pixel's colour.
    draw::<1>(
        geometry,
        world,
        view,
        progress,
        &mut colors,
        &VaryingColor,
        out,
    )
}

/// The vertex stage of Gouraud shading as a varying: each vertex lit with its normal, seen from
/// the eye. Lanes are independent, so a vertex gets the same colour whichever vertices share
/// its lanes.
struct LitVertices<'a> {
    world: &'a World,
    viewer: Viewer,
    lighting: Lighting<'a>,
    materials: ObjectMaterials,
    /// Colours of every vertex, `[object][vertex]`, for the objects lit whole.
    whole: &'a mut Vec<Vec<Vec3>>,
    /// Which objects were lit whole this frame.
    lit_whole: Vec<bool>,
}

impl LitVertices<'_> {
    /// Colours of the eight vertices `p`, `n` of `object`.
    #[inline(always)]
    fn light<L: Lanes8>(&self, material: &MaterialLanes<L>, p: V3<L>, n: V3<L>) -> V3<L> {
        let v = self.viewer.toward(p);
        self.lighting
            .shade_lanes(p, n, v, material, |_, _, facing| facing)
    }
}

impl Varying for LitVertices<'_> {
    fn prepare(&mut self, triangles_needed: &[usize]) {
        let lit = objects_lit_whole(self.world, triangles_needed);
        let mut whole = std::mem::take(&mut *self.whole);
        let this = &*self;
        light_whole(self.world, &lit, &mut whole, |object, mesh, colors| {
            colors.clear();
            colors.reserve(mesh.positions.len());
            run_on_best_lanes(LightAll {
                lit: this,
                object,
                mesh,
                colors,
            });
        });
        *self.whole = whole;
        self.lit_whole = lit;
    }

    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        let mesh = &self.world.objects[object].mesh;
        if self.lit_whole[object] {
            let colors = &self.whole[object];
            out.extend(
                triangles
                    .iter()
                    .map(|&t| mesh.triangles[t as usize].map(|i| colors[i as usize])),
            );
            return;
        }
        // All the loads first, so that the misses overlap.
        for &t in triangles {
            for i in mesh.triangles[t as usize] {
                prefetch::ahead(&mesh.positions[i as usize]);
                prefetch::ahead(&mesh.normals[i as usize]);
            }
        }
        let start = out.len();
        out.resize(start + triangles.len(), [Vec3::ZERO; 3]);
        run_on_best_lanes(LightCorners {
            lit: self,
            object,
            triangles,
            colors: bytemuck::cast_slice_mut(&mut out[start..]),
        });
    }

    fn prefetch(&self, object: usize, triangle: u32) {
        prefetch::ahead(&self.world.objects[object].mesh.triangles[triangle as usize]);
    }
}

/// Lights every vertex of `mesh` (of `object`), in order, appending their colours to `colors`.
struct LightAll<'a> {
    lit: &'a LitVertices<'a>,
    object: usize,
    mesh: &'a Mesh,
    colors: &'a mut Vec<Vec3>,
}

impl LanesJob for LightAll<'_> {
    type Output = ();

    #[inline(always)]
    fn run<L: Lanes8>(self) {
        let material = &self.lit.materials.splat::<L>(self.object);
        let mesh = self.mesh;
        for (p, n) in mesh.positions.chunks(WIDTH).zip(mesh.normals.chunks(WIDTH)) {
            let count = p.len();
            let c = self.lit.light(material, V3::gather(p), V3::gather(n));
            self.colors.extend_from_slice(&c.to_vec3s()[..count]);
        }
    }
}

/// Lights the corners of mesh triangles `triangles` of `object`, three colours per triangle
/// into `colors`.
struct LightCorners<'a> {
    lit: &'a LitVertices<'a>,
    object: usize,
    triangles: &'a [u32],
    colors: &'a mut [Vec3],
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
        for colors in self.colors.chunks_mut(WIDTH) {
            let (p, n) = next_corners(mesh, &mut vertices, colors.len());
            let lit = self.lit.light(material, p, n);
            colors.copy_from_slice(&lit.to_vec3s()[..colors.len()]);
        }
    }
}

/// Which objects of `world` to light whole this frame, given how many of their triangles will
/// be shown (`triangles_needed`): those with at least a third as many as vertices, where lighting
/// each vertex once, in order, costs less than lighting the shown triangles' corners.
pub(super) fn objects_lit_whole(world: &World, triangles_needed: &[usize]) -> Vec<bool> {
    world
        .objects
        .iter()
        .zip(triangles_needed)
        .map(|(o, &needed)| 3 * needed >= o.mesh.positions.len())
        .collect()
}

/// Runs `light(object, mesh, values)` in parallel for each object of `world` that `lit` marks,
/// on its buffer in `whole` (one per object, kept from frame to frame).
pub(super) fn light_whole(
    world: &World,
    lit: &[bool],
    whole: &mut Vec<Vec<Vec3>>,
    light: impl Fn(usize, &Mesh, &mut Vec<Vec3>) + Sync,
) {
    whole.resize_with(world.objects.len(), Vec::new);
    whole
        .par_iter_mut()
        .zip(&world.objects)
        .enumerate()
        .zip(lit)
        .filter(|(_, lit)| **lit)
        .for_each(|((object, (values, o)), _)| light(object, &o.mesh, values));
}

/// The positions and normals of the next `count` (1..=[`WIDTH`]) vertices of `mesh` that
/// `vertices` yields, in lanes; lanes past the last vertex repeat it.
#[inline(always)]
pub(super) fn next_corners<L: Lanes8>(
    mesh: &Mesh,
    vertices: &mut impl Iterator<Item = usize>,
    count: usize,
) -> (V3<L>, V3<L>) {
    let mut ids = [0; WIDTH];
    for id in &mut ids[..count] {
        *id = vertices.next().expect("three vertices per triangle");
    }
    for k in count..WIDTH {
        ids[k] = ids[count - 1];
    }
    let gather = |values: &[Vec3]| {
        let v = ids.map(|i| values[i]);
        V3::new(
            L::from_array(v.map(|v| v.x)),
            L::from_array(v.map(|v| v.y)),
            L::from_array(v.map(|v| v.z)),
        )
    };
    (gather(&mesh.positions), gather(&mesh.normals))
}
