//! Pictures as terminal output, one encoder per protocol: kitty graphics, sixel, iTerm2 inline
//! images, and half-block text (coloured, or a plain character ramp with no escapes at all).
//! Every encoder takes an 8-bit sRGB [`PreviewImage`](crate::tui::preview::PreviewImage) and a
//! cell area and returns the bytes to print.

pub mod base64_chunks;
pub mod cell_area;
pub mod halfblock;
pub mod iterm2;
pub mod kitty;
pub mod median_cut;
pub mod passthrough;
pub mod png;
pub mod protocol;
pub mod sixel;

pub use cell_area::{CellArea, CellSize};
pub use protocol::Protocol;
