//! The one way to render: a [`Renderer`] built from [`RenderOptions`], which prepares a world
//! once (the ray tracer's BVH) and then renders it from any camera into a frame the caller owns.

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec3;
use rayon::ThreadPool;
use rayon::prelude::*;

use super::algorithm::Algorithm;
use super::camera::View;
use super::display_mode::DisplayMode;
use super::error::RenderError;
use super::frame::{Frame, box_filter};
use super::mode_shading::ModeShading;
use super::options::RenderOptions;
use super::overlay::{Canvas, GrownHits, draw_labels, draw_overlays, outline_reach};
use super::prepared::Prepared;
use super::progress::{Cancelled, Progress};
use super::raster::{RasterScratch, raster_coverage, raster_hits, render_gouraud, render_phong};
use super::ray::{primary_coverage, primary_hits, trace_into};
use super::scratch::Scratch;
use super::stats::{RayCounts, RenderStats};
use super::surface_hit::SurfaceHit;
use crate::scene::Camera;
use crate::world::World;

/// Samples rendered at once: larger images are rendered in strips of about this many samples,
/// each box-filtered before the next starts, so memory stays bounded and progress flows.
const STRIP_SAMPLES: u64 = 1 << 22;

/// Renders worlds with one set of options. Like a committed Embree scene, it prepares a world
/// once and answers many renders of it: the ray tracer's BVH is built the first time the ray
/// tracer draws a world and kept while renders pass that same `Arc<World>` (a camera move or
/// new options keep it; another world replaces it).
///
/// ```no_run
/// # use std::sync::Arc;
/// # use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
/// # fn demo(world: Arc<rastray::World>, cameras: &[rastray::scene::Camera]) -> Result<(), rastray::render::RenderError> {
/// let mut renderer = Renderer::new(RenderOptions::new(Algorithm::Ray, 640, 360));
/// let mut frame = Frame::default();
/// for camera in cameras {
///     // The BVH is built by the first render only.
///     let stats = renderer.render(&world, camera, &Progress::new(), &mut frame)?;
///     println!("{} ms", stats.total().as_secs_f64() * 1e3);
/// }
/// # Ok(())
/// # }
/// ```
#[derive(Debug)]
pub struct Renderer {
    options: RenderOptions,
    /// The pool of `options.threads` threads, started by the first render that asks for it.
    pool: Option<ThreadPool>,
    /// The world last rendered, with what was built for it.
    scene: Option<Prepared>,
    scratch: Scratch,
}

impl Renderer {
    /// A renderer with `options`, which are checked when it renders.
    pub fn new(options: RenderOptions) -> Renderer {
        Renderer {
            options,
            pool: None,
            scene: None,
            scratch: Scratch::default(),
        }
    }

    /// The options renders use.
    pub fn options(&self) -> &RenderOptions {
        &self.options
    }

    /// Renders from now on with `options`; the prepared world is kept.
    pub fn set_options(&mut self, options: RenderOptions) {
        self.options = options;
    }

    /// Prepares `world` for the options' algorithm now rather than in the next render: keeps
    /// it, and builds the ray tracer's BVH unless one was built for this very world already.
    /// A cancelled `progress` stops it before it builds anything, or soon after, mid-build.
    pub fn prepare(
        &mut self,
        world: &Arc<World>,
        progress: &Progress,
    ) -> Result<RenderStats, RenderError> {
        let algorithm = self.options.algorithm;
        let scene = &mut self.scene;
        let prepared = on_pool(&mut self.pool, self.options.threads, || {
            prepare_scene(scene, world, algorithm, progress).map(|(_, stats)| stats)
        })?;
        Ok(prepared?)
    }

    /// Renders `world` seen by `camera` into `frame`, which takes the options' size; its buffer
    /// is kept when it has that size already (a live preview then skips faulting in fresh
    /// memory, which for 1920×1080 costs as much as a render). Supersampling renders N× larger
    /// and box-filters down, the same for every algorithm; with [`RenderOptions::alpha`], a
    /// first pass finds which samples some surface covers, and their share is the alpha.
    /// `progress` counts rows of the supersampled image, once per pass; cancelling it stops
    /// the render with [`RenderError::Cancelled`].
    pub fn render(
        &mut self,
        world: &Arc<World>,
        camera: &Camera,
        progress: &Progress,
        frame: &mut Frame,
    ) -> Result<RenderStats, RenderError> {
        let options = self.options;
        options.check()?;
        let (scene, scratch) = (&mut self.scene, &mut self.scratch);
        let rendered = on_pool(&mut self.pool, options.threads, || {
            render_frame(&options, scene, scratch, world, camera, progress, frame)
        })?;
        Ok(rendered?)
    }
}

/// Runs `work` on a pool of `threads` threads, kept in `pool` and started again only when the
/// count changes, or on rayon's global pool (one thread per core) when `threads` is `None`.
///
/// Either way the whole of `work` runs on a pool thread, so its parallel stages hand work
/// between the pool's threads rather than to and from the caller's: on the global pool, the
/// bunny at 160×96 on 1 thread took about 10 context switches per frame from the caller's
/// thread, and about 1.6 with the frame inside the pool.
fn on_pool<R: Send>(
    pool: &mut Option<ThreadPool>,
    threads: Option<std::num::NonZeroUsize>,
    work: impl FnOnce() -> R + Send,
) -> Result<R, RenderError> {
    let Some(threads) = threads.map(|n| n.get()) else {
        return Ok(crate::pool_thread::on_pool_thread(work));
    };
    if pool
        .as_ref()
        .is_none_or(|p| p.current_num_threads() != threads)
    {
        let started = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("rastray-render-{i}"))
            .build()
            .map_err(|e| RenderError::Threads {
                threads,
                message: e.to_string(),
            })?;
        *pool = Some(started);
    }
    Ok(pool.as_ref().expect("started above").install(work))
}

/// Makes `scene` hold `world` prepared for `algorithm`, replacing another world; returns it with
/// the figures of the preparation.
fn prepare_scene<'a>(
    scene: &'a mut Option<Prepared>,
    world: &Arc<World>,
    algorithm: Algorithm,
    progress: &Progress,
) -> Result<(&'a Prepared, RenderStats), Cancelled> {
    if scene.as_ref().is_none_or(|s| !s.is_of(world)) {
        *scene = Some(Prepared::new(world));
    }
    let prepared = scene.as_mut().expect("set above");
    let mut stats = RenderStats {
        prepare: prepared.build_for(algorithm, progress)?,
        triangles: world.triangle_count(),
        ..RenderStats::default()
    };
    if algorithm == Algorithm::Ray {
        stats.bvh_build = prepared.accel().map_or(Duration::ZERO, |a| a.build_time);
    }
    Ok((prepared, stats))
}

/// The body of [`Renderer::render`], on the pool it runs on.
fn render_frame(
    options: &RenderOptions,
    scene: &mut Option<Prepared>,
    scratch: &mut Scratch,
    world: &Arc<World>,
    camera: &Camera,
    progress: &Progress,
    frame: &mut Frame,
) -> Result<RenderStats, Cancelled> {
    let started = Instant::now();
    let n = options.samples;
    let full = View::new(camera, options.width * n, options.height * n);
    // A display mode other than `shaded`, or an overlay, needs the surface at each sample: a
    // pass of its own. Only `shaded` and `wire` draw the lit image.
    let decorated = options.mode != DisplayMode::Shaded || options.overlays.any();
    let lit = matches!(options.mode, DisplayMode::Shaded | DisplayMode::Wire);
    let passes = options.alpha as u64 + lit as u64 + decorated as u64;
    progress.start(full.height as u64 * passes);
    let strip_rows = (STRIP_SAMPLES / (full.width as u64 * (n * n) as u64))
        .clamp(1, options.height as u64) as u32;
    frame.reshape(options.width, options.height, options.alpha);
    let (prepared, mut stats) = prepare_scene(scene, world, options.algorithm, progress)?;
    let world = prepared.world_for(options.algorithm);
    let no_rays = RayCounts::default;
    let draw = |raster: &mut RasterScratch, view: &View, out: &mut [Vec3]| match options.algorithm {
        Algorithm::Gouraud => {
            render_gouraud(raster, world, view, progress, out).map(|()| no_rays())
        }
        Algorithm::Phong => render_phong(raster, world, view, progress, out).map(|()| no_rays()),
        Algorithm::Ray => {
            let accel = prepared.accel().expect("prepared for the ray tracer");
            trace_into(accel, world, view, options, progress, out)
        }
    };
    // Coverage, for alpha, by the algorithm's own test: the rasterizer's depth buffer (drawn
    // into `work`) or the primary rays' hits.
    let cover = |raster: &mut RasterScratch,
                 view: &View,
                 work: &mut [Vec3],
                 covered: &mut [f32]| match options.algorithm {
        Algorithm::Gouraud | Algorithm::Phong => {
            raster_coverage(raster, world, view, progress, work, covered)
        }
        Algorithm::Ray => {
            let accel = prepared.accel().expect("prepared for the ray tracer");
            primary_coverage(accel, world, view, progress, covered)
        }
    };
    // Draws `view` into `out`; with alpha, finds the coverage first and leaves the background
    // out of the colours, which are then premultiplied.
    let draw_covered =
        |raster: &mut RasterScratch, view: &View, out: &mut [Vec3], covered: Option<&mut [f32]>| {
            let Some(covered) = covered else {
                return draw(raster, view, out);
            };
            cover(raster, view, out, covered)?;
            let cast = draw(raster, view, out)?;
            leave_out_background(out, covered);
            Ok(cast)
        };
    // The surface at each sample of `view`, as the algorithm finds it, into `hits`; the
    // Z-buffer draws into `work` on the way.
    let find_hits = |raster: &mut RasterScratch,
                     view: &View,
                     work: &mut Vec<Vec3>,
                     hits: &mut Vec<SurfaceHit>| {
        let len = view.width as usize * view.height as usize;
        hits.resize(len, SurfaceHit::MISS);
        match options.algorithm {
            Algorithm::Gouraud | Algorithm::Phong => {
                work.resize(len, Vec3::ZERO);
                raster_hits(raster, world, view, progress, work, hits)
            }
            Algorithm::Ray => {
                let accel = prepared.accel().expect("prepared for the ray tracer");
                primary_hits(accel, world, view, progress, hits)
            }
        }
    };
    // Draws `view` into `out` in the options' display mode, with their overlays: the lit image
    // (for `shaded` and `wire`) or the coverage alone, then the surface hits, then the mode's
    // colours and the overlays from them.
    let draw_decorated = |scratch: &mut DecorationScratch,
                          view: &View,
                          out: &mut [Vec3],
                          mut covered: Option<&mut [f32]>| {
        let DecorationScratch {
            raster,
            hits,
            work,
            depth,
        } = scratch;
        let cast = if lit {
            draw_covered(raster, view, out, covered.as_deref_mut())?
        } else {
            if let Some(covered) = covered.as_deref_mut() {
                cover(raster, view, out, covered)?;
            }
            no_rays()
        };
        // The outline looks a line's width past the strip's top and bottom: the hits of those
        // rows too, so that it does not break where two strips meet.
        let (above, below) = if options.overlays.outline {
            let reach = outline_reach(n);
            (
                reach.min(view.row_offset),
                reach.min(view.image_height - view.row_offset - view.height),
            )
        } else {
            (0, 0)
        };
        let grown = View {
            row_offset: view.row_offset - above,
            height: view.height + above + below,
            ..*view
        };
        find_hits(raster, &grown, work, hits)?;
        let width = view.width as usize;
        let strip_hits = &hits[above as usize * width..][..view.height as usize * width];
        if options.mode != DisplayMode::Shaded {
            ModeShading::new(world, view, options.mode, n).apply(strip_hits, out);
        }
        if options.overlays.any() {
            depth.clear();
            depth.par_extend(strip_hits.par_iter().map(|hit| {
                if hit.is_hit() {
                    hit.depth(world, view)
                } else {
                    f32::INFINITY
                }
            }));
            let mut canvas = Canvas {
                view,
                samples: n,
                out,
                depth,
            };
            let grown_hits = GrownHits {
                hits,
                above: above as usize,
            };
            draw_overlays(&options.overlays, world, &grown_hits, &mut canvas);
        }
        if let (false, Some(covered)) = (lit, covered) {
            leave_out_background(out, covered);
        }
        Ok(cast)
    };
    let draw_strip = |scratch: &mut DecorationScratch,
                      view: &View,
                      out: &mut [Vec3],
                      covered: Option<&mut [f32]>| {
        if decorated {
            draw_decorated(scratch, view, out, covered)
        } else {
            draw_covered(scratch.raster, view, out, covered)
        }
    };
    let width = options.width as usize;
    let mut rays = RayCounts::default();
    // Supersampled strips are drawn into one scratch strip and box-filtered into the frame;
    // without supersampling a strip is drawn straight into the frame's rows.
    for first in (0..options.height).step_by(strip_rows as usize) {
        let rows = strip_rows.min(options.height - first);
        let view = full.rows(first * n, rows * n);
        let range = first as usize * width..(first + rows) as usize * width;
        let out = &mut frame.pixels[range.clone()];
        let alpha = frame.alpha.as_deref_mut().map(|a| &mut a[range]);
        let Scratch {
            samples,
            coverage,
            raster,
            hits,
            work,
            depth,
        } = &mut *scratch;
        let decoration = &mut DecorationScratch {
            raster,
            hits,
            work,
            depth,
        };
        let cast = if n == 1 {
            draw_strip(decoration, &view, out, alpha)?
        } else {
            let len = view.width as usize * view.height as usize;
            samples.resize(len, Vec3::ZERO);
            let covered = alpha.is_some().then(|| {
                coverage.resize(len, 0.0);
                &mut coverage[..]
            });
            let cast = draw_strip(decoration, &view, samples, covered)?;
            let filtering = Instant::now();
            box_filter(samples, view.width, n, out);
            if let Some(alpha) = alpha {
                box_filter(coverage, view.width, n, alpha);
            }
            stats.filter += filtering.elapsed();
            cast
        };
        rays = rays + cast;
    }
    draw_labels(&options.overlays, world, camera, frame);
    stats.rays = rays;
    stats.draw = started
        .elapsed()
        .saturating_sub(stats.prepare + stats.filter);
    Ok(stats)
}

/// The working memory of one strip's display mode and overlays, borrowed from [`Scratch`].
struct DecorationScratch<'a> {
    raster: &'a mut RasterScratch,
    hits: &'a mut Vec<SurfaceHit>,
    work: &'a mut Vec<Vec3>,
    depth: &'a mut Vec<f32>,
}

/// Zeroes the colour of every sample no surface covers (`covered` 0; 1 keeps it): the colours
/// become premultiplied by coverage.
fn leave_out_background(colors: &mut [Vec3], covered: &[f32]) {
    colors
        .par_iter_mut()
        .zip(covered)
        .for_each(|(color, &c)| *color *= c);
}
