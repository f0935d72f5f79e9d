//! The view: the camera the preview and the export look through, and how the preview draws.
//! Looking around is not editing: moving the view never touches the document. The view starts
//! from the scene's camera, and `C` copies it back into the scene as an edit.

use super::graphics::Graphics;
use super::orbit;
use super::preview::ColorMode;
use crate::render::{Algorithm, DisplayMode, OverlayKind, Overlays};
use crate::scene::{Camera, Scene, validate};

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
    /// How the preview shows surfaces.
    mode: DisplayMode,
    /// The overlays drawn over the preview (their selection is the editor's, set per render).
    overlays: Overlays,
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
            mode: DisplayMode::Shaded,
            overlays: Overlays::default(),
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
}
