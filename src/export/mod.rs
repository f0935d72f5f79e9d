//! Renders to files, each written atomically: still images as 8- or 16-bit PNG or as OpenEXR,
//! with coverage as alpha when the render has it, and turntables as GIF or animated PNG.
//!
//! `output` says what to write and holds [`render_to_file`], the one way the command line and
//! the editor write renders; `format` chooses the encoding from a file name and an explicit
//! request; `png`, `exr`, `gif_animation` and `apng` encode; `still` renders one image;
//! `turntable` orbits the camera and streams its frames through `animation` into one file;
//! `contact_sheet` lays thumbnails out in a titled grid; `join` makes one animation of still PNG frames rendered apart; `template` names the outputs
//! of many inputs and frames (`out/{stem}.png`); `destination` says where bytes go, and `stream` writes FIFOs, devices and standard output in
//! waits that a signal can end.

mod animation;
mod apng;
mod contact_sheet;
mod destination;
mod error;
mod exr;
mod format;
mod gif_animation;
mod join;
mod output;
mod png;
mod still;
mod stream;
mod template;
mod turntable;

pub use contact_sheet::{
    SheetImage, SheetLayout, TITLE_HEIGHT, Thumbnail, compose_sheet, save_sheet,
};
pub use destination::{Destination, Sink};
pub use error::ExportError;
pub use exr::encode_exr;
pub use format::{AnimationFormat, FormatError, ImageFormat, PngDepth};
pub use join::{JoinStats, join_frames};
pub use output::{Exported, Output, render_to, render_to_file};
pub use png::{PngSamples, encode_png, straight};
pub use still::{encode_image, render_image, save_image, save_image_to};
pub use template::{Field, FieldValues, OutputTemplate, TemplateError};
pub use turntable::{
    DEFAULT_FPS, MAX_FPS, MAX_FRAMES, Turntable, TurntableError, TurntableJob, TurntableStats,
    TurntableWorkers, render_turntable, render_turntable_with,
};
