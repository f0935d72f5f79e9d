//! Coverage for alpha: which pixel centres some triangle covers, found by the same scan
//! conversion and depth test that draw the colours, so alpha and colour agree on every edge.

use glam::Vec3;
use rayon::prelude::*;

use super::fragments::Fragments;
use super::setup::RasterScratch;
use super::shader::Shader;
use super::varying::PerVertex;
use super::zbuffer::draw;
use crate::render::camera::View;
use crate::render::progress::{Cancelled, Progress};
use crate::render::simd::{Lanes8, V3};
use crate::world::World;

/// What the coverage shader writes into a covered pixel: a value no background can take
/// (backgrounds are finite colours).
const COVERED: Vec3 = Vec3::splat(f32::NAN);

/// Writes [`COVERED`] into every pixel it shades.
struct Covered;

impl Shader for Covered {
    #[inline(always)]
    fn shade<L: Lanes8>(&self, fragments: &Fragments<L>, row: &mut [Vec3]) {
        fragments.write(V3::splat(COVERED), row);
    }
}

/// Writes 1 into `covered` where some triangle of `world` covers the pixel centre of `view`
/// and 0 elsewhere (`view.width`×`view.height` values); `work` is as large and is overwritten.
pub fn raster_coverage(
    scratch: &mut RasterScratch,
    world: &World,
    view: &View,
    progress: &Progress,
    work: &mut [Vec3],
    covered: &mut [f32],
) -> Result<(), Cancelled> {
    debug_assert!(
        world.background.is_finite(),
        "a background is a finite colour"
    );
    draw(
        &mut scratch.geometry,
        world,
        view,
        progress,
        &mut PerVertex::normals(world),
        &Covered,
        work,
    )?;
    covered
        .par_iter_mut()
        .zip(work.par_iter())
        .for_each(|(c, pixel)| *c = if pixel.x.is_nan() { 1.0 } else { 0.0 });
    Ok(())
}
