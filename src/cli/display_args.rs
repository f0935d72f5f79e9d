//! `--mode` and `--overlay`, shared by `render` and `view`: how surfaces are shown and what is
//! drawn over them.

use clap::Args;
use rastray::World;
use rastray::render::{
    DisplayMode, Overlays, RenderOptions, ground_grid, objects_without_uvs, overlay_bounds,
};

#[derive(Debug, Clone, Args)]
pub struct DisplayArgs {
    /// Display mode: shaded, wire (edges over the shaded image), hidden-line, normals
    /// (world-space normal as (n+1)/2), depth (near white, far black) or uv (a checker over the
    /// texture coordinates).
    #[arg(long, default_value = "shaded", value_parser = parse_mode)]
    pub mode: DisplayMode,
    /// Lines over the image, comma-separated: grid (ground grid), axes (gizmo in the
    /// bottom-left corner), bbox (the scene's bounding box), outline (around every object).
    #[arg(long, value_name = "LIST", value_parser = parse_overlays)]
    pub overlay: Option<Overlays>,
}

impl DisplayArgs {
    /// `options` with this mode and these overlays.
    pub fn apply(&self, options: RenderOptions) -> RenderOptions {
        RenderOptions {
            mode: self.mode,
            overlays: self.overlay.unwrap_or_default(),
            ..options
        }
    }

    /// Says on stderr what the image cannot show by itself: objects without texture
    /// coordinates in `uv` mode, the grid's spacing, the bounding box's size.
    pub fn print_notes(&self, world: &World) {
        let missing = objects_without_uvs(world);
        if self.mode == DisplayMode::Uv && missing > 0 {
            eprintln!(
                "warning: --mode uv: {missing} of {} objects have no texture coordinates; they are drawn grey",
                world.objects.len()
            );
        }
        let overlays = self.overlay.unwrap_or_default();
        if overlays.grid
            && let Some(grid) = ground_grid(world)
        {
            eprintln!("grid: spacing {} at y = {:.3}", grid.spacing, grid.level);
        }
        if overlays.bbox
            && let Some((lo, hi)) = overlay_bounds(world, None)
        {
            let size = hi - lo;
            eprintln!(
                "bounding box: {:.3} x {:.3} x {:.3} (x from {:.3} to {:.3}, y from {:.3} to {:.3}, z from {:.3} to {:.3})",
                size.x, size.y, size.z, lo.x, hi.x, lo.y, hi.y, lo.z, hi.z
            );
        }
    }
}

fn parse_mode(s: &str) -> Result<DisplayMode, String> {
    s.parse()
        .map_err(|e: rastray::render::UnknownMode| e.to_string())
}

fn parse_overlays(s: &str) -> Result<Overlays, String> {
    s.parse()
        .map_err(|e: rastray::render::UnknownOverlay| e.to_string())
}
