//! A frame's geometry, from meshes to binned screen triangles: the vertex stage once per distinct
//! position (a flat-shaded mesh repeats each position per face; the projection is the same),
//! triangle setup in parallel chunks, the planes of the varying for the triangles that remain,
//! and bins of rows. Everything lives in a [`RasterScratch`] kept from frame to frame, so a
//! preview of the same world allocates nothing that grows with the mesh.

use glam::Vec3;
use rayon::prelude::*;

use super::projected::{ProjectedVertices, project};
use super::screen_triangle::{Corners, MAX_FAN, ScreenTriangle, may_cover, setup_triangle};
use super::varying::Varying;
use crate::render::camera::View;
use crate::render::simd::WIDTH;
use crate::world::World;

/// Vertices per parallel task of the vertex stage.
const VERTEX_CHUNK: usize = 8192;
/// Triangles per parallel setup task.
const SETUP_CHUNK: usize = 4096;
/// Bits of a screen triangle's index within its setup chunk (see [`ScreenTriangles::get`]).
const INDEX_BITS: u32 = 15;
const _: () = assert!(SETUP_CHUNK * MAX_FAN < 1 << INDEX_BITS);
/// Rows per band: the unit of parallel work and of progress.
pub const BAND_ROWS: u32 = 8;

/// Working memory of the Z-buffer, kept from frame to frame by a renderer.
#[derive(Debug, Default)]
pub struct RasterScratch {
    /// The geometry of the frame.
    pub(super) geometry: Geometry,
    /// Per-vertex values a varying works out for whole objects (Gouraud's colours), per object.
    pub(super) per_vertex: Vec<Vec<Vec3>>,
}

/// The geometry of a frame: projected vertices, screen triangles and their bins.
#[derive(Debug, Default)]
pub struct Geometry {
    /// Projected distinct positions ([`crate::world::WorldObject::unique`]), per object.
    projected: Vec<ProjectedVertices>,
    /// The setup tasks and their screen triangles.
    chunks: Vec<SetupChunk>,
    /// Screen triangle ids per band of [`BAND_ROWS`] rows, in triangle order.
    bins: Vec<Vec<u32>>,
}

/// One setup task: triangles `start..end` of one object, and what they became.
#[derive(Debug, Default)]
struct SetupChunk {
    object: usize,
    start: usize,
    end: usize,
    triangles: Vec<ScreenTriangle>,
    corners: Vec<Corners>,
    /// Working space for the planes of the varying.
    mesh_triangles: Vec<u32>,
    values: Vec<[Vec3; 3]>,
}

/// The screen triangles of a frame, kept in the chunks that set them up in parallel. A
/// triangle's id is its chunk times 2^[`INDEX_BITS`] plus its index in the chunk; ids increase
/// in triangle order.
#[derive(Debug, Clone, Copy)]
pub struct ScreenTriangles<'a> {
    chunks: &'a [SetupChunk],
}

impl ScreenTriangles<'_> {
    /// The triangle with id `id`.
    #[inline(always)]
    pub fn get(&self, id: u32) -> &ScreenTriangle {
        &self.chunks[(id >> INDEX_BITS) as usize].triangles[(id & ((1 << INDEX_BITS) - 1)) as usize]
    }
}

impl Geometry {
    /// Sets up every triangle of `world` seen through `view`, in object then triangle order,
    /// with the planes of `varying`, and bins them into bands of rows; returns the triangles
    /// and the bins (screen triangle ids per band of [`BAND_ROWS`] rows, in triangle order).
    pub fn set_up(
        &mut self,
        world: &World,
        view: &View,
        varying: &mut dyn Varying,
    ) -> (ScreenTriangles<'_>, &[Vec<u32>]) {
        self.project(world, view);
        self.plan_chunks(world);
        let projected = &self.projected;
        self.chunks.par_iter_mut().for_each(|chunk| {
            let unique = &world.objects[chunk.object].unique;
            let projected = &projected[chunk.object];
            chunk.triangles.clear();
            chunk.corners.clear();
            for first in (chunk.start..chunk.end).step_by(WIDTH) {
                let group = &unique.triangles[first..(first + WIDTH).min(chunk.end)];
                let mut lanes = may_cover(view, projected, group);
                while lanes != 0 {
                    let lane = lanes.trailing_zeros() as usize;
                    lanes &= lanes - 1;
                    setup_triangle(
                        view,
                        projected,
                        &unique.positions,
                        group[lane],
                        chunk.object as u32,
                        (first + lane) as u32,
                        &mut chunk.triangles,
                        &mut chunk.corners,
                    );
                }
            }
        });
        let mut needed = vec![0; world.objects.len()];
        for chunk in &self.chunks {
            needed[chunk.object] += chunk.triangles.len();
        }
        varying.prepare(&needed);
        let varying = &*varying;
        self.chunks.par_iter_mut().for_each(|chunk| {
            chunk.mesh_triangles.clear();
            chunk
                .mesh_triangles
                .extend(chunk.corners.iter().map(|c| c.triangle));
            chunk.values.clear();
            varying.corners(chunk.object, &chunk.mesh_triangles, &mut chunk.values);
            for ((t, corners), values) in chunk
                .triangles
                .iter_mut()
                .zip(&chunk.corners)
                .zip(&chunk.values)
            {
                t.set_varying(corners, *values);
            }
        });
        self.bin(view.height);
        (
            ScreenTriangles {
                chunks: &self.chunks,
            },
            &self.bins,
        )
    }

    /// The vertex stage: every distinct position of every object projected once.
    fn project(&mut self, world: &World, view: &View) {
        self.projected
            .resize_with(world.objects.len(), ProjectedVertices::default);
        for (o, projected) in world.objects.iter().zip(&mut self.projected) {
            let positions = &o.unique.positions;
            projected.resize(positions.len());
            projected
                .runs_mut(VERTEX_CHUNK)
                .par_bridge()
                .for_each(|run| {
                    let vertices = &positions[run.first..run.first + run.len()];
                    project(view, vertices, run)
                });
        }
    }

    /// Splits every object's triangles into setup tasks.
    fn plan_chunks(&mut self, world: &World) {
        let mut n = 0;
        for (object, o) in world.objects.iter().enumerate() {
            let count = o.mesh.triangles.len();
            for start in (0..count).step_by(SETUP_CHUNK) {
                if n == self.chunks.len() {
                    self.chunks.push(SetupChunk::default());
                }
                let chunk = &mut self.chunks[n];
                (chunk.object, chunk.start, chunk.end) =
                    (object, start, (start + SETUP_CHUNK).min(count));
                n += 1;
            }
        }
        self.chunks.truncate(n);
    }

    /// Bins the screen triangles into bands of [`BAND_ROWS`] rows of an image `height` rows
    /// tall, in triangle order.
    fn bin(&mut self, height: u32) {
        let bands = height.div_ceil(BAND_ROWS) as usize;
        self.bins.resize_with(bands, Vec::new);
        self.bins.truncate(bands);
        self.bins.iter_mut().for_each(Vec::clear);
        for (c, chunk) in self.chunks.iter().enumerate() {
            let first = (c as u32) << INDEX_BITS;
            for (i, t) in chunk.triangles.iter().enumerate() {
                for band in (t.min_y as u32 / BAND_ROWS)..=(t.max_y as u32 / BAND_ROWS) {
                    self.bins[band as usize].push(first + i as u32);
                }
            }
        }
    }
}
