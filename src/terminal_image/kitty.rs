//! The kitty graphics protocol: a PNG sent in base64 pieces of 4096 bytes, displayed at once
//! (`a=T`) over a cell area (`c=`, `r=`), with the terminal's replies turned off (`q=2`).
//! The editor gives each picture an id, so that it can replace and delete it.

use super::preview::PreviewImage;
use super::{CellArea, base64_chunks, png};

/// Largest base64 piece in one escape sequence, as the protocol requires.
pub const CHUNK: usize = 4096;

/// The escape sequences that show `image` over `area` at the cursor.
pub fn encode(image: &PreviewImage, area: CellArea) -> Result<Vec<u8>, image::ImageError> {
    encode_pieces(image, area, None).map(|pieces| pieces.concat())
}

/// The escape sequences, one per piece, that show `image` over `area` at the cursor as image
/// `id` (when given), leaving the cursor where it was (`C=1`). Kept apart so that each piece can
/// travel in a passthrough sequence of its own.
pub fn encode_pieces(
    image: &PreviewImage,
    area: CellArea,
    id: Option<u32>,
) -> Result<Vec<Vec<u8>>, image::ImageError> {
    let id = id.map(|id| format!("i={id},C=1,")).unwrap_or_default();
    pieces(
        image,
        &format!("a=T,f=100,q=2,{id}c={},r={},", area.cols, area.rows),
    )
}

/// The escape sequences that send `image` as image `id` with a virtual placement (`U=1`) of
/// `area`: nothing is drawn until cells hold its Unicode placeholders (see
/// [`super::kitty_placeholder`]). Sending an id again replaces that image.
pub fn encode_virtual(
    image: &PreviewImage,
    area: CellArea,
    id: u32,
) -> Result<Vec<u8>, image::ImageError> {
    let head = format!("a=T,U=1,f=100,q=2,i={id},c={},r={},", area.cols, area.rows);
    pieces(image, &head).map(|pieces| pieces.concat())
}

/// `image` as a PNG in base64 pieces, one escape sequence each, the first opening with the
/// control keys `head`.
fn pieces(image: &PreviewImage, head: &str) -> Result<Vec<Vec<u8>>, image::ImageError> {
    let pieces = base64_chunks::chunks(&png::encode(image)?, CHUNK);
    let mut out = Vec::with_capacity(pieces.len());
    for (i, piece) in pieces.iter().enumerate() {
        let more = u8::from(i + 1 < pieces.len());
        let mut sequence = b"\x1b_G".to_vec();
        if i == 0 {
            sequence.extend_from_slice(head.as_bytes());
        }
        sequence.extend_from_slice(format!("m={more};{piece}\x1b\\").as_bytes());
        out.push(sequence);
    }
    Ok(out)
}

/// Deletes image `id` and its placements, freeing its data (`d=I`).
pub fn delete(id: u32) -> Vec<u8> {
    format!("\x1b_Ga=d,d=I,i={id},q=2\x1b\\").into_bytes()
}

/// Deletes every image placed on the screen (`d=A`), freeing their data.
pub const DELETE_ALL: &[u8] = b"\x1b_Ga=d,d=A,q=2\x1b\\";

/// The query that asks whether the terminal speaks the protocol: a one-pixel RGB image sent
/// directly (`t=d`) only to be checked (`a=q`). A kitty terminal answers `i=31;OK`.
pub const QUERY: &[u8] = b"\x1b_Gi=31,s=1,v=1,a=q,t=d,f=24;AAAA\x1b\\";
