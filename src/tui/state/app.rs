//! The editor's state, by owner: the [`Document`] (scene, file, history), the [`ViewState`]
//! (camera and how the preview draws), the [`Selection`], the current [`Mode`], and what the
//! background threads delivered. Only [`crate::tui::update`] changes it; everything else reads it
//! through the accessors.

use std::path::PathBuf;

use super::document::Document;
use super::mode::Mode;
use super::selection::{Focus, Item, Selection};
use super::view_state::ViewState;
use crate::scene::Scene;
use crate::terminal_image::preview::{ColorMode, PreviewImage};
use crate::tui::persistence::disk_watch::DiskWatch;
use crate::tui::persistence::export_job::ExportJob;
use crate::tui::terminal::motion::{CoarseMask, MotionFilter};
use crate::warnings::Warning;

/// Whether a status message reports success or a problem.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tone {
    Info,
    Error,
}

/// A one-line message in the status bar.
#[derive(Debug, Clone, PartialEq)]
pub struct Status {
    pub text: String,
    pub tone: Tone,
}

/// A rendered preview and how long it took.
#[derive(Debug, Clone, PartialEq)]
pub struct Shot {
    pub image: PreviewImage,
    /// Render time, milliseconds.
    pub millis: f64,
    /// Pixels drawn coarse in the current frame (see [`crate::tui::terminal::motion`]).
    pub coarse: CoarseMask,
}

/// The latest frames from the render worker.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Previews {
    /// Latest single preview.
    pub shot: Option<Shot>,
    /// Latest compare previews, in [`crate::render::Algorithm::ALL`] order.
    pub compare: [Option<Shot>; 3],
    /// Triangles in the last world built.
    pub triangles: Option<usize>,
    /// What the overlays and the `uv` mode of the last request measured.
    pub measures: Option<crate::tui::worker::Measures>,
    /// The last scene object measured and its measurements (world units), for the properties.
    pub shape: Option<(usize, crate::mesh::Measurements)>,
    /// The last exact frame of each slot: the main preview, then the compare panes.
    motion: [MotionFilter; 4],
}

impl Previews {
    /// Decides, before a frame is drawn, which pixels of each preview are drawn coarse: with
    /// `cheap` (keys are arriving over a link that is paced), those that changed since the last
    /// exact frame; otherwise none, and this frame becomes the reference. Returns whether any
    /// pixel is drawn coarse.
    pub fn present(&mut self, mode: ColorMode, cheap: bool) -> bool {
        let shots = std::iter::once(&mut self.shot).chain(self.compare.iter_mut());
        let mut any = false;
        for (shot, filter) in shots.zip(&mut self.motion) {
            if let Some(shot) = shot {
                shot.coarse = filter.mask(&shot.image, mode, cheap);
                any |= shot.coarse.as_ref().is_some_and(|m| m.contains(&true));
            }
        }
        any
    }
}

/// The whole editor state.
#[derive(Debug)]
pub struct App {
    pub(in crate::tui) doc: Document,
    pub(in crate::tui) view: ViewState,
    pub(in crate::tui) selection: Selection,
    pub(in crate::tui) mode: Mode,
    pub(in crate::tui) status: Option<Status>,
    pub(in crate::tui) previews: Previews,
    /// The PNG export running in the background.
    pub(in crate::tui) export: Option<ExportJob>,
    /// Last mouse position of a drag in progress (column, row).
    pub(in crate::tui) drag: Option<(u16, u16)>,
    /// Set when the event loop should end.
    pub(in crate::tui) quit: bool,
    /// Warnings of the last world built; the status line shows those it did not have before.
    pub(in crate::tui) warnings: Vec<Warning>,
    /// The scene file and model files, watched for writes by other programs.
    pub(in crate::tui) disk: DiskWatch,
    /// Set when a tick changed what the screen shows (a reload); the event loop redraws.
    pub(in crate::tui) ticked_change: bool,
}

impl App {
    /// An editor on `scene`, loaded from `path` (or built in), with OBJ paths relative to
    /// `base_dir`; the view starts from the scene's camera.
    pub fn new(scene: Scene, path: Option<PathBuf>, base_dir: PathBuf) -> App {
        let mut app = App {
            view: ViewState::new(scene.camera),
            doc: Document::new(scene, path, base_dir),
            selection: Selection::default(),
            mode: Mode::Normal,
            status: None,
            previews: Previews::default(),
            export: None,
            drag: None,
            quit: false,
            warnings: Vec::new(),
            disk: DiskWatch::default(),
            ticked_change: false,
        };
        app.disk.sync(&app.doc);
        app
    }

    /// The same editor drawing its preview with `color`.
    pub fn with_color(mut self, color: ColorMode) -> App {
        self.view.set_color(color);
        self
    }

    /// The same editor drawing its preview with `graphics` (half blocks or real pixels).
    pub fn with_graphics(mut self, graphics: crate::tui::terminal::graphics::Graphics) -> App {
        self.view.set_graphics(graphics);
        self
    }

    /// The same editor drawing its interface without colours (`NO_COLOR`); the preview is a
    /// picture and keeps its own.
    pub fn with_plain_interface(mut self, plain: bool) -> App {
        self.view.set_plain(plain);
        self
    }

    /// The same editor showing render times or not (off for reproducible screen captures).
    pub fn with_timings(mut self, show: bool) -> App {
        self.view.set_show_timings(show);
        self
    }

    /// The scene, its file and its history.
    pub fn document(&self) -> &Document {
        &self.doc
    }

    /// The camera and drawing settings of the preview.
    pub fn view(&self) -> &ViewState {
        &self.view
    }

    /// The focused pane.
    pub fn focus(&self) -> Focus {
        self.selection.focus()
    }

    /// Index into the selected item's properties.
    pub fn field(&self) -> usize {
        self.selection.field()
    }

    /// What the keys currently do.
    pub fn mode(&self) -> &Mode {
        &self.mode
    }

    /// The latest status message.
    pub fn status(&self) -> Option<&Status> {
        self.status.as_ref()
    }

    /// Chooses how the next frame draws the previews: `cheap` while keys arrive over a paced
    /// link (see [`Previews::present`]). Returns whether the frame is a cheap one.
    pub fn present_previews(&mut self, cheap: bool) -> bool {
        self.previews.present(self.view.color(), cheap)
    }

    /// The latest preview frames.
    pub fn previews(&self) -> &Previews {
        &self.previews
    }

    /// Whether a PNG export is running.
    pub fn is_exporting(&self) -> bool {
        self.export.is_some()
    }

    /// Whether the event loop should end.
    pub fn should_quit(&self) -> bool {
        self.quit
    }

    /// The scene list: settings, then lights, then objects.
    pub fn items(&self) -> Vec<Item> {
        let scene = self.doc.scene();
        std::iter::once(Item::Settings)
            .chain((0..scene.lights.len()).map(Item::Light))
            .chain((0..scene.objects.len()).map(Item::Object))
            .collect()
    }

    /// The selected entry (the settings when the index is stale).
    pub fn item(&self) -> Item {
        self.items()
            .get(self.selection.item())
            .copied()
            .unwrap_or(Item::Settings)
    }

    /// The scene-list index of `item`.
    pub fn index_of(&self, item: Item) -> usize {
        self.items().iter().position(|&i| i == item).unwrap_or(0)
    }

    /// The file name shown in the status bar.
    pub fn title(&self) -> String {
        match self.doc.path() {
            Some(p) => crate::tui::text::clean(&p.display().to_string()),
            None => format!("({})", crate::tui::text::clean(self.doc.untitled_name())),
        }
    }

    /// Sets an informational status message.
    pub fn info(&mut self, text: impl Into<String>) {
        self.status = Some(Status {
            text: text.into(),
            tone: Tone::Info,
        });
    }

    /// Sets an error status message.
    pub fn error(&mut self, text: impl Into<String>) {
        self.status = Some(Status {
            text: text.into(),
            tone: Tone::Error,
        });
    }
}
