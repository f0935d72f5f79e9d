//! The view: the camera the preview and the export look through, and how the preview draws.
//! Looking around is not editing: moving the view never touches the document. The view starts
//! from the scene's camera, and `C` copies it back into the scene as an edit.

use std::time::Instant;

use glam::Vec3;

use super::orbit;
use crate::preset_view::{self, PresetView};
use crate::render::{Algorithm, DisplayMode, OverlayKind, Overlays};
use crate::scene::{Camera, Scene, validate};
use crate::terminal_image::preview::ColorMode;
use crate::tui::terminal::graphics::Graphics;

/// How fast auto-spin turns the view, degrees per second (a turn in 24 s).
pub const SPIN_DEGREES_PER_SECOND: f32 = 15.0;

/// What the preview shows and how. Fields change only through the methods below.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewState {
    /// Where the preview looks from; always passes the scene file's camera rules.
    camera: Camera,
    /// Algorithm of the single preview.
    algorithm: Algorithm,
    /// Whether the preview shows the three algorithms side by side.
    compare: bool,
    /// How colours reach the terminal.
    color: ColorMode,
    /// Whether render times are shown (off for reproducible screen captures).
    show_timings: bool,
    /// Whether the interface is drawn without colours (`NO_COLOR`); the preview keeps its own.
    plain: bool,
    /// Half blocks, or real pixels over a graphics protocol.
    graphics: Graphics,
    /// Most pixels a picture in real pixels has: [`crate::tui::terminal::graphics::PIXEL_BUDGET`], or less
    /// over a slow link (see [`super::pixel_budget`]).
    pixel_budget: u64,
    /// How the preview shows surfaces.
    mode: DisplayMode,
    /// The overlays drawn over the preview (their selection is the editor's, set per render).
    overlays: Overlays,
    /// The preset view last chosen, if the view still looks from it.
    preset: Option<PresetView>,
    /// The scene's bounds (min, max) as last built, for fitting; `None` for an empty scene.
    bounds: Option<(Vec3, Vec3)>,
    /// When auto-spin last turned the view, while it spins.
    spinning_since: Option<Instant>,
    /// Whether the terminal reports this pane focused (focus reporting, see
    /// [`Graphics::hides_unfocused`]); true until it says otherwise.
    terminal_focused: bool,
}

impl ViewState {
    /// A Phong preview in truecolor, with timings, looking through `camera`.
    pub fn new(camera: Camera) -> ViewState {
        ViewState {
            camera,
            algorithm: Algorithm::Phong,
            compare: false,
            color: ColorMode::Truecolor,
            show_timings: true,
            plain: false,
            graphics: Graphics::default(),
            pixel_budget: crate::tui::terminal::graphics::PIXEL_BUDGET,
            mode: DisplayMode::Shaded,
            overlays: Overlays::default(),
            preset: None,
            bounds: None,
            spinning_since: None,
            terminal_focused: true,
        }
    }

    /// How the preview shows surfaces.
    pub fn mode(&self) -> DisplayMode {
        self.mode
    }

    /// Shows the display mode `steps` places on, wrapping around.
    pub fn cycle_mode(&mut self, steps: i32) {
        self.mode = self.mode.cycled(steps);
    }

    /// The overlays drawn over the preview.
    pub fn overlays(&self) -> Overlays {
        self.overlays
    }

    /// Turns overlay `kind` on or off.
    pub fn toggle_overlay(&mut self, kind: OverlayKind) {
        self.overlays.toggle(kind);
    }

    /// The camera the preview and the export look through.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// The single preview's algorithm.
    pub fn algorithm(&self) -> Algorithm {
        self.algorithm
    }

    /// Whether the three algorithms are shown side by side.
    pub fn compare(&self) -> bool {
        self.compare
    }

    /// How colours reach the terminal.
    pub fn color(&self) -> ColorMode {
        self.color
    }

    /// Whether render times are shown.
    pub fn show_timings(&self) -> bool {
        self.show_timings
    }

    /// Looks through `camera` (the scene's, on open, reset and scene camera edits).
    pub fn look_from(&mut self, camera: Camera) {
        self.camera = camera;
        self.preset = None;
    }

    /// Turns the view about its target by `yaw` degrees around +Y and `pitch` degrees upward.
    pub fn orbit(&mut self, yaw: f32, pitch: f32) {
        self.move_to(orbit::orbit(&self.camera, yaw, pitch));
    }

    /// Moves the view and its target sideways by fractions of the viewing distance.
    pub fn pan(&mut self, right: f32, up: f32) {
        self.move_to(orbit::pan(&self.camera, right, up));
    }

    /// Scales the viewing distance by `factor` (< 1 moves closer).
    pub fn zoom(&mut self, factor: f32) {
        self.move_to(orbit::zoom(&self.camera, factor));
    }

    /// The preset view the view looks from, if it still does.
    pub fn preset(&self) -> Option<PresetView> {
        self.preset
    }

    /// Whether auto-spin is on.
    pub fn spinning(&self) -> bool {
        self.spinning_since.is_some()
    }

    /// Notes the scene's bounds as last built (`None` for an empty scene).
    pub fn set_bounds(&mut self, bounds: Option<(Vec3, Vec3)>) {
        self.bounds = bounds;
    }

    /// Looks from the preset `step` places after the current one (the first when none),
    /// fitting the scene in a preview of `aspect` (width / height).
    pub fn step_preset(&mut self, step: i32, aspect: f32) {
        let next = match self.preset {
            Some(view) => view.step(step),
            None if step >= 0 => PresetView::ALL[0],
            None => PresetView::Iso,
        };
        if let Some(bounds) = self.bounds {
            self.move_to(preset_view::place(
                &self.camera,
                next,
                0.0,
                0.0,
                bounds,
                aspect,
            ));
            self.preset = Some(next);
        }
    }

    /// Fits the scene in a preview of `aspect`, looking the way the view looks now.
    pub fn fit_all(&mut self, aspect: f32) {
        if let Some(bounds) = self.bounds {
            let back = (self.camera.position - self.camera.target).normalize_or(Vec3::Z);
            let up = crate::render::View::new(&self.camera, 1, 1).up;
            let preset = self.preset;
            self.move_to(preset_view::fit(&self.camera, back, up, bounds, aspect));
            self.preset = preset;
        }
    }

    /// Switches between perspective and orthographic, keeping the framing at the target.
    pub fn toggle_projection(&mut self) {
        let preset = self.preset;
        self.move_to(self.camera.toggled_projection());
        self.preset = preset;
    }

    /// Starts auto-spin at `now`, or stops it.
    pub fn toggle_spin(&mut self, now: Instant) {
        self.spinning_since = match self.spinning_since {
            Some(_) => None,
            None => Some(now),
        };
    }

    /// While auto-spin is on, turns the view by the time since the last turn; returns whether
    /// it turned.
    pub fn spin(&mut self, now: Instant) -> bool {
        let Some(since) = self.spinning_since else {
            return false;
        };
        let seconds = now.saturating_duration_since(since).as_secs_f32();
        self.spinning_since = Some(now);
        self.orbit(seconds * SPIN_DEGREES_PER_SECOND, 0.0);
        seconds > 0.0
    }

    /// Takes `camera` when a scene file could hold it (finite, within range, not degenerate);
    /// a move that would leave those limits is ignored.
    fn move_to(&mut self, camera: Camera) {
        // The scene's camera rules, applied to the view alone.
        if validate(&Scene {
            camera,
            ..Scene::default()
        })
        .is_ok()
        {
            self.camera = camera;
            self.preset = None;
        }
    }

    /// Previews with `algorithm` alone.
    pub fn show_algorithm(&mut self, algorithm: Algorithm) {
        self.algorithm = algorithm;
        self.compare = false;
    }

    /// Switches between the single preview and the three side by side.
    pub fn toggle_compare(&mut self) {
        self.compare = !self.compare;
    }

    /// Whether the interface is drawn without colours.
    pub fn plain(&self) -> bool {
        self.plain
    }

    /// Draws the interface without colours (`true`) or with the theme's.
    pub fn set_plain(&mut self, plain: bool) {
        self.plain = plain;
    }

    /// Draws the preview with `color`.
    pub fn set_color(&mut self, color: ColorMode) {
        self.color = color;
    }

    /// Shows or hides render times.
    pub fn set_show_timings(&mut self, show: bool) {
        self.show_timings = show;
    }

    /// How the preview reaches the screen: half blocks or a graphics protocol.
    pub fn graphics(&self) -> &Graphics {
        &self.graphics
    }

    /// Draws the preview with `graphics`.
    pub fn set_graphics(&mut self, graphics: Graphics) {
        self.graphics = graphics;
    }

    /// Whether the preview may show pictures in real pixels as far as focus goes: always,
    /// unless [`Graphics::hides_unfocused`] and the terminal reported the pane unfocused.
    pub fn pixels_while_focused(&self) -> bool {
        self.terminal_focused || !self.graphics.hides_unfocused
    }

    /// Notes that the terminal reported the pane `focused` or not.
    pub fn set_terminal_focused(&mut self, focused: bool) {
        self.terminal_focused = focused;
    }

    /// Limits pictures in real pixels to `pixels` (at most [`crate::tui::terminal::graphics::PIXEL_BUDGET`]).
    pub fn set_pixel_budget(&mut self, pixels: u64) {
        self.pixel_budget = pixels;
    }

    /// The image size to render for a picture of `cols`×`rows` cells in real pixels, within
    /// the pixel budget; `None` without a graphics protocol.
    pub fn pixel_size(&self, cols: u16, rows: u16) -> Option<(u32, u32)> {
        self.graphics
            .pixel_size_within(cols, rows, self.pixel_budget)
    }
}
