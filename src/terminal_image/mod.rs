//! Pictures as terminal output, one encoder per protocol: kitty graphics, sixel, iTerm2 inline
//! images, and text cells: half blocks, quadrants, sextants or braille, each cell the glyph and
//! two colours that best fit the pixels under it (`glyph_cells`), or a plain character ramp with
//! no escapes at all.
//! Every encoder takes an 8-bit sRGB [`PreviewImage`](preview::PreviewImage) and a
//! cell area and returns the bytes to print.

pub mod base64_chunks;
pub mod cell_area;
pub mod glyph_cells;
pub mod halfblock;
pub mod iterm2;
pub mod kitty;
pub mod kitty_placeholder;
pub mod median_cut;
pub mod passthrough;
pub mod png;
pub mod preview;
pub mod protocol;
pub mod resample;
pub mod sixel;

pub use cell_area::{CellArea, CellSize};
pub use glyph_cells::GlyphSet;
pub use preview::{ColorMode, PreviewImage};
pub use protocol::Protocol;
