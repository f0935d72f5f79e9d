//! The camera flags `render` and `view` share: `--ortho`, `--view`, `--azimuth`,
//! `--elevation`, and the `{view}` field of an output name that writes one file per view.

use std::path::Path;

use clap::Args;
use rastray::World;
use rastray::preset_view::{self, PresetView};
use rastray::scene::Camera;

/// Where a view's name goes in an output file name.
const VIEW_FIELD: &str = "{view}";

#[derive(Debug, Clone, Args)]
pub struct CameraArgs {
    /// Orthographic camera (parallel rays), keeping the framing at the camera's target.
    #[arg(long)]
    pub ortho: bool,
    /// Look from a preset side at the scene's bounds, fitting them: front, back, left, right,
    /// top, bottom, iso; a comma list writes one file per view when the output names
    /// `{view}` (`-o out-{view}.png`).
    #[arg(long, value_delimiter = ',', value_parser = parse_view)]
    pub view: Vec<PresetView>,
    /// With --view: turn the camera this many degrees about the up axis from the preset.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub azimuth: f32,
    /// With --view: raise the camera this many degrees from the preset.
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub elevation: f32,
}

/// Parses a preset view's name for clap.
fn parse_view(s: &str) -> Result<PresetView, String> {
    PresetView::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = PresetView::ALL.iter().map(|v| v.name()).collect();
        format!("`{s}` is not a view: expected one of {}", names.join(", "))
    })
}

impl CameraArgs {
    /// Refuses what cannot be drawn before any work: several views into one `output` without
    /// a `{view}` field, angles that are not finite, or angles without a view.
    pub fn check(&self, output: Option<&Path>) -> anyhow::Result<()> {
        if !self.azimuth.is_finite() || !self.elevation.is_finite() {
            anyhow::bail!("--azimuth and --elevation must be finite numbers of degrees");
        }
        if self.view.is_empty() && (self.azimuth != 0.0 || self.elevation != 0.0) {
            anyhow::bail!("--azimuth and --elevation orbit from a preset: give --view too");
        }
        let templated = output.is_some_and(|o| o.to_string_lossy().contains(VIEW_FIELD));
        if self.view.len() > 1 && !templated {
            anyhow::bail!(
                "{} views need an output name with a {VIEW_FIELD} field (-o out-{VIEW_FIELD}.png); \
                 without it, give one view",
                self.view.len()
            );
        }
        Ok(())
    }

    /// The camera to draw `world` with from `view` (the scene's `camera` when `None`), made
    /// orthographic by --ortho, for an image of `aspect`.
    pub fn camera_for(
        &self,
        view: Option<PresetView>,
        camera: &Camera,
        world: &World,
        aspect: f32,
    ) -> Camera {
        let base = if self.ortho {
            camera.to_orthographic()
        } else {
            *camera
        };
        match (view, world.bounds()) {
            (Some(view), Some(bounds)) => {
                preset_view::place(&base, view, self.azimuth, self.elevation, bounds, aspect)
            }
            _ => base,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(views: &[PresetView]) -> CameraArgs {
        CameraArgs {
            ortho: false,
            view: views.to_vec(),
            azimuth: 0.0,
            elevation: 0.0,
        }
    }

    #[test]
    fn several_views_need_a_view_field() {
        let two = args(&[PresetView::Front, PresetView::Iso]);
        assert!(two.check(Some(Path::new("out.png"))).is_err());
        assert!(two.check(Some(Path::new("out-{view}.png"))).is_ok());
        assert!(
            args(&[PresetView::Top])
                .check(Some(Path::new("out.png")))
                .is_ok()
        );
    }
}
