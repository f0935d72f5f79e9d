//! A frame's geometry, from meshes to binned screen triangles: the vertex stage once per distinct
//! position (a flat-shaded mesh repeats each position per face; the projection is the same),
//! triangle setup in parallel chunks, and bins of rows, each chunk binning its own triangles.
//! The planes of the varying wait until a band has found which triangles it shows
//! ([`Corners::planes`]). Everything lives in a
//! [`RasterScratch`] kept from frame to frame, so a preview of the same world allocates nothing
//! that grows with the mesh.

use glam::Vec3;
use rayon::prelude::*;

use super::projected::{ProjectedVertices, project};
use super::screen_triangle::{Corners, Planes, ScreenTriangle, may_cover, setup_triangle};
use super::varying::Varying;
use crate::render::camera::View;
use crate::render::cpu::with_avx2;
use crate::render::simd::WIDTH;
use crate::world::World;

/// Vertices per parallel task of the vertex stage.
const VERTEX_CHUNK: usize = 8192;
/// Triangles per parallel setup task.
const SETUP_CHUNK: usize = 4096;
/// How far ahead, in triangles, setup asks for the projected corners of the triangles it will
/// test, when the vertex stage ran on several threads. A thread then reads corners another one
/// projected, and where the two cores share no cache each such read waits for the other core
/// (a cache line's round trip took 0.4 µs on the 2-vCPU VM in such spells, 0.09 µs otherwise).
/// Bunny at 160×96, 2 threads, kept renderer, median of 300 frames, alternating with the build
/// before: in the far spells Phong 0.716 → 0.629 ms and Gouraud 0.740 → 0.661 ms (medians of 14
/// samples), in the near ones 0.479 → 0.482 and 0.501 → 0.499 ms (124 samples). On 1 thread the
/// hints only cost (0.85 → 0.88 ms), so they are not given there.
const PREFETCH_AHEAD: usize = 64;
/// Pixels a band of rows holds at most, about: its depth and triangle ids (8 bytes a pixel, a
/// megabyte in all) then stay in about a core's L2 cache while it is drawn, and fewer
/// triangles straddle two bands (each band scans and sets up the planes of those it meets).
/// Bunny at 1920×1080, 1 thread, min of 40 frames, three alternations: 2^15 pixels (17 rows)
/// Gouraud 17.8–18.2, Phong 20.8–21.0 ms; 2^16 (32) 17.1–17.8, 20.0–20.7; 2^17 (64) 16.3–17.0,
/// 19.5–19.9 ms.
const BAND_PIXELS: u32 = 1 << 17;
/// Bands an image is cut into at least, where rows allow, so that threads share the work.
const MIN_BANDS: u32 = 16;
/// Rows a band holds at most.
const MAX_BAND_ROWS: u32 = 64;

/// Rows per band of a `width`×`height` image, the unit of parallel work and of progress:
/// bands as tall as [`BAND_PIXELS`] allows, so that a triangle spans few of them, but at least
/// [`MIN_BANDS`] of them where the image is tall enough.
pub fn band_rows(width: u32, height: u32) -> u32 {
    (BAND_PIXELS / width.max(1))
        .min(height.div_ceil(MIN_BANDS))
        .clamp(1, MAX_BAND_ROWS)
}

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
    /// Screen triangles per object in the last frame set up (empty before the first): what
    /// the varying's per-object work is planned by, the next frame's camera being usually
    /// close to the last's.
    survivors: Vec<usize>,
    /// Depth and triangle buffers of the bands being drawn, one set per render thread.
    pub(super) band_buffers: Vec<std::sync::Mutex<BandBuffers>>,
}

/// The buffers a thread draws a band of rows into, kept from frame to frame: at 1920×1080 a
/// band's are a megabyte, which fresh allocations would fault in every frame.
#[derive(Debug, Default)]
pub struct BandBuffers {
    /// 1/w of the nearest surface so far (0 = nothing).
    pub depth: Vec<f32>,
    /// Number + 1 in the band's bin of the triangle that drew the pixel (0 = nothing).
    pub id: Vec<u32>,
    /// Per id, whether the band shows the triangle (entry 0, no triangle, is unused).
    pub seen: Vec<bool>,
    /// Per id, the planes of a seen triangle's interpolants (entries of unseen ones are stale),
    /// for shaders of one varying, two, three, four and five (see [`PlanesOf`]).
    pub planes: Vec<Planes<1>>,
    pub planes_two: Vec<Planes<2>>,
    pub planes_three: Vec<Planes<3>>,
    pub planes_four: Vec<Planes<4>>,
    pub planes_five: Vec<Planes<5>>,
    /// Working space for the planes: the mesh triangles of a run of seen triangles of one
    /// object, their ids, and the varyings at their corners (each triangle's varyings one
    /// after the other).
    pub mesh_triangles: Vec<u32>,
    pub ids: Vec<u32>,
    pub values: Vec<[Vec3; 3]>,
}

/// Where [`BandBuffers`] keep the planes of triangles with `K` varyings: each count has its own
/// buffer, kept from frame to frame like the others.
pub trait PlanesOf<const K: usize> {
    /// The planes buffer for `K` varyings.
    fn planes_of(&mut self) -> &mut Vec<Planes<K>>;
}

impl PlanesOf<1> for BandBuffers {
    fn planes_of(&mut self) -> &mut Vec<Planes<1>> {
        &mut self.planes
    }
}

impl PlanesOf<2> for BandBuffers {
    fn planes_of(&mut self) -> &mut Vec<Planes<2>> {
        &mut self.planes_two
    }
}

impl PlanesOf<3> for BandBuffers {
    fn planes_of(&mut self) -> &mut Vec<Planes<3>> {
        &mut self.planes_three
    }
}

impl PlanesOf<4> for BandBuffers {
    fn planes_of(&mut self) -> &mut Vec<Planes<4>> {
        &mut self.planes_four
    }
}

impl PlanesOf<5> for BandBuffers {
    fn planes_of(&mut self) -> &mut Vec<Planes<5>> {
        &mut self.planes_five
    }
}

/// One setup task: triangles `start..end` of one object, and what they became.
#[derive(Debug, Default)]
struct SetupChunk {
    object: usize,
    start: usize,
    end: usize,
    triangles: Vec<ScreenTriangle>,
    corners: Vec<Corners>,
    /// The chunk's screen triangles that meet each band of rows, band after band, each band's
    /// in triangle order: band b's are `binned[bin_starts[b]..bin_starts[b + 1]]`.
    /// Copies, so that a band reads its triangles in sequence rather than scattered across the
    /// frame's (at 1920×1080, fetching them scattered took a fifth of the drawing time).
    binned: Vec<ScreenTriangle>,
    bin_starts: Vec<u32>,
    /// Working space of the binning: where each band's next triangle goes.
    bin_next: Vec<u32>,
}

/// The bands of rows a frame is drawn in, with the screen triangles each one meets.
#[derive(Debug, Clone, Copy)]
pub struct Bands<'a> {
    /// Rows per band; the last band may hold fewer.
    pub rows: u32,
    chunks: &'a [SetupChunk],
}

impl<'a> Bands<'a> {
    /// The screen triangles that meet band `band`, in triangle order.
    #[inline]
    pub fn triangles(&self, band: usize) -> impl Iterator<Item = &'a ScreenTriangle> + use<'a> {
        self.chunks.iter().flat_map(move |c| {
            &c.binned[c.bin_starts[band] as usize..c.bin_starts[band + 1] as usize]
        })
    }

    /// Where screen triangle `t` lies on its mesh triangle.
    #[inline]
    pub fn corners(&self, t: &ScreenTriangle) -> &'a Corners {
        &self.chunks[t.chunk as usize].corners[t.slot as usize]
    }
}

impl Geometry {
    /// Sets up every triangle of `world` seen through `view`, in object then triangle order,
    /// and bins them into bands of rows; returns the bands. `varying` is prepared for the
    /// planes the bands will ask of it.
    ///
    /// Once a frame of the world was set up, two parallel passes: the vertex stage (with
    /// `varying`'s per-object work beside it, planned by the last frame's survivors), then one
    /// pass per setup chunk that tests, sets up and bins its triangles. A small frame thus
    /// wakes the render threads twice rather than once per stage. The first frame plans the
    /// varying's work by its own survivors, after the setup pass.
    pub fn set_up(&mut self, world: &World, view: &View, varying: &mut dyn Varying) -> Bands<'_> {
        let planned = self.survivors.len() == world.objects.len();
        let projected = &mut self.projected;
        if planned {
            let survivors = &self.survivors;
            rayon::join(
                || project_all(projected, world, view),
                || varying.prepare(survivors),
            );
        } else {
            project_all(projected, world, view);
        }
        self.plan_chunks(world);
        let rows = band_rows(view.width, view.height);
        let bands = view.height.div_ceil(rows) as usize;
        let projected = &self.projected;
        // On one thread every vertex was projected by the thread reading it.
        let shared = rayon::current_num_threads() > 1;
        self.chunks
            .par_iter_mut()
            .enumerate()
            .for_each(|(k, chunk)| {
                with_avx2(
                    #[inline(always)]
                    || {
                        chunk.set_up(world, view, &projected[chunk.object], shared);
                        chunk.bin(k as u32, rows, bands);
                    },
                )
            });
        self.survivors.clear();
        self.survivors.resize(world.objects.len(), 0);
        for chunk in &self.chunks {
            self.survivors[chunk.object] += chunk.triangles.len();
        }
        if !planned {
            varying.prepare(&self.survivors);
        }
        Bands {
            rows,
            chunks: &self.chunks,
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
}

/// The vertex stage: every distinct position of every object projected once, in parallel runs
/// of [`VERTEX_CHUNK`] vertices.
fn project_all(projected: &mut Vec<ProjectedVertices>, world: &World, view: &View) {
    projected.resize_with(world.objects.len(), ProjectedVertices::default);
    // In parallel: each object finds its distinct positions on the first frame.
    projected
        .par_iter_mut()
        .zip(&world.objects)
        .for_each(|(projected, o)| projected.resize(o.unique().positions.len()));
    world
        .objects
        .par_iter()
        .zip(projected.par_iter_mut())
        .flat_map(|(o, projected)| {
            let positions = o.unique().positions;
            projected
                .runs_mut(VERTEX_CHUNK)
                .map(move |run| (positions, run))
        })
        .for_each(|(positions, run)| {
            let vertices = &positions[run.first..run.first + run.len()];
            project(view, vertices, run)
        });
}

impl SetupChunk {
    /// Tests and sets up the chunk's triangles of `world` seen through `view` (their object's
    /// vertices are `projected`), without the planes of the varying. Where other threads
    /// `shared` the vertex stage, it asks for the corners [`PREFETCH_AHEAD`] triangles ahead.
    #[inline(always)]
    fn set_up(&mut self, world: &World, view: &View, projected: &ProjectedVertices, shared: bool) {
        let unique = world.objects[self.object].unique();
        self.triangles.clear();
        self.corners.clear();
        // Room for every triangle at once: growing by doubling would copy and fault in twice
        // the memory.
        self.triangles.reserve(self.end - self.start);
        self.corners.reserve(self.end - self.start);
        for first in (self.start..self.end).step_by(WIDTH) {
            if shared
                && let Some(group) = unique.triangles.get(first + PREFETCH_AHEAD..)
                && let Some(group) = group.get(..WIDTH)
            {
                group
                    .iter()
                    .flatten()
                    .for_each(|&v| projected.prefetch(v as usize));
            }
            let group = &unique.triangles[first..(first + WIDTH).min(self.end)];
            let mut lanes = may_cover(view, projected, group);
            while lanes != 0 {
                let lane = lanes.trailing_zeros() as usize;
                lanes &= lanes - 1;
                setup_triangle(
                    view,
                    projected,
                    unique.positions,
                    group[lane],
                    self.object as u32,
                    (first + lane) as u32,
                    &mut self.triangles,
                    &mut self.corners,
                );
            }
        }
    }

    /// Bins the chunk's screen triangles into `bands` bands of `rows` rows, in triangle order;
    /// the chunk is number `chunk` of the frame's.
    #[inline(always)]
    fn bin(&mut self, chunk: u32, rows: u32, bands: usize) {
        let reach = |t: &ScreenTriangle| {
            (t.min_y as u32 / rows) as usize..=(t.max_y as u32 / rows) as usize
        };
        // A counting sort: how many triangles each band gets, where each band's run starts,
        // then each triangle copied into its bands' runs.
        self.bin_starts.clear();
        self.bin_starts.resize(bands + 1, 0);
        for t in &self.triangles {
            for band in reach(t) {
                self.bin_starts[band + 1] += 1;
            }
        }
        for b in 0..bands {
            self.bin_starts[b + 1] += self.bin_starts[b];
        }
        self.binned.clear();
        self.binned
            .resize(self.bin_starts[bands] as usize, ScreenTriangle::default());
        let next = &mut self.bin_next;
        next.clear();
        next.extend_from_slice(&self.bin_starts);
        for t in &self.triangles {
            for band in reach(t) {
                self.binned[next[band] as usize] = ScreenTriangle { chunk, ..*t };
                next[band] += 1;
            }
        }
    }
}
