//! The kitty graphics protocol: a PNG sent in base64 pieces of 4096 bytes, displayed at once
//! (`a=T`) over a cell area (`c=`, `r=`), with the terminal's replies turned off (`q=2`).

use super::{CellArea, base64_chunks, png};
use crate::tui::preview::PreviewImage;

/// Largest base64 piece in one escape sequence, as the protocol requires.
pub const CHUNK: usize = 4096;

/// The escape sequences that show `image` over `area`.
pub fn encode(image: &PreviewImage, area: CellArea) -> Result<Vec<u8>, image::ImageError> {
    let pieces = base64_chunks::chunks(&png::encode(image)?, CHUNK);
    let mut out = Vec::new();
    for (i, piece) in pieces.iter().enumerate() {
        let more = u8::from(i + 1 < pieces.len());
        out.extend_from_slice(b"\x1b_G");
        if i == 0 {
            out.extend_from_slice(
                format!("a=T,f=100,q=2,c={},r={},", area.cols, area.rows).as_bytes(),
            );
        }
        out.extend_from_slice(format!("m={more};{piece}\x1b\\").as_bytes());
    }
    Ok(out)
}
