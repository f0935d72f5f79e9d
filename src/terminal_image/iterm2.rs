//! iTerm2 inline images (also WezTerm): one OSC 1337 sequence carrying a base64 PNG, sized in
//! cells.

use super::preview::PreviewImage;
use super::{CellArea, base64_chunks, png};

/// The escape sequence that shows `image` over `area`.
pub fn encode(image: &PreviewImage, area: CellArea) -> Result<Vec<u8>, image::ImageError> {
    let bytes = png::encode(image)?;
    Ok(format!(
        "\x1b]1337;File=inline=1;size={};width={};height={};preserveAspectRatio=1:{}\x07",
        bytes.len(),
        area.cols,
        area.rows,
        base64_chunks::encode(&bytes)
    )
    .into_bytes())
}
