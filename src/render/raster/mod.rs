//! The Z-buffer: one rasterizer (`zbuffer`) hands covered pixels, eight at a time
//! (`fragments`), to a shader; Gouraud lights the vertices and interpolates the colour, Phong
//! interpolates the normal and lights every pixel.

mod alpha_cut;
mod colored;
mod coverage;
mod fragment_texels;
mod fragments;
mod gouraud;
mod gouraud_parts;
mod hits;
mod lane_sampler;
mod phong;
mod projected;
#[cfg(target_arch = "x86_64")]
mod scan_avx2;
mod screen_triangle;
mod setup;
mod shader;
mod snap;
mod spans;
mod varying;
mod zbuffer;

pub(crate) use coverage::raster_coverage;
pub(crate) use gouraud::render_gouraud;
pub(crate) use hits::raster_hits;
pub(crate) use phong::render_phong;
#[cfg(test)]
use phong::render_phong_unpaired;
pub(crate) use setup::RasterScratch;
#[cfg(test)]
pub(crate) use zbuffer::coverage_counts;

#[cfg(test)]
mod tests;
