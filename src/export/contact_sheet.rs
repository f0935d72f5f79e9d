//! Contact sheets: thumbnails in a grid, each titled below with its file's stem, as one 8-bit
//! sRGB image (`rastray render IN... --sheet sheet.png`, and `rastray view IN... --grid` in the
//! terminal). Titles are drawn with the bundled font; a title wider than its cell is cut short
//! with an ellipsis.

use std::io::Write;

use plotters::prelude::*;

use super::destination::Destination;
use super::error::ExportError;
use crate::bundled_font::{FONT, register_bundled_font};
use crate::render::{MAX_DIMENSION, Progress, RenderError};

/// Height of the title strip under each thumbnail, pixels.
pub const TITLE_HEIGHT: u32 = 20;
/// Colour of the sheet's background and title strips, 8-bit sRGB.
const BACKGROUND: [u8; 3] = [24, 24, 28];
/// Title text size, pixels.
const TITLE_SIZE: u32 = 14;
/// Average width of a title character at [`TITLE_SIZE`], pixels: titles longer than their
/// cell holds are cut.
const CHAR_WIDTH: u32 = 8;

/// One thumbnail: its title and its pixels, 8-bit sRGB RGB rows of the layout's cell size.
#[derive(Debug, Clone)]
pub struct Thumbnail {
    pub title: String,
    pub pixels: Vec<u8>,
}

/// How thumbnails sit on a sheet: `columns` per row, each `cell_width`×`cell_height` pixels
/// above a title strip of [`TITLE_HEIGHT`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SheetLayout {
    pub columns: u32,
    pub cell_width: u32,
    pub cell_height: u32,
}

/// An 8-bit sRGB RGB image, row-major from the top-left.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SheetImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<u8>,
}

impl SheetLayout {
    /// The layout of `count` thumbnails of `cell` pixels: `columns` when given, else the
    /// smallest count that makes the sheet about square (⌈√count⌉).
    pub fn new(count: usize, columns: Option<u32>, cell: (u32, u32)) -> SheetLayout {
        let square = (count as f64).sqrt().ceil().max(1.0) as u32;
        let columns = columns.unwrap_or(square).clamp(1, count.max(1) as u32);
        SheetLayout {
            columns,
            cell_width: cell.0,
            cell_height: cell.1,
        }
    }

    /// The sheet's width and height for `count` thumbnails, pixels.
    pub fn size(&self, count: usize) -> (u64, u64) {
        let rows = (count.max(1) as u64).div_ceil(u64::from(self.columns));
        (
            u64::from(self.columns) * u64::from(self.cell_width),
            rows * (u64::from(self.cell_height) + u64::from(TITLE_HEIGHT)),
        )
    }

    /// Refuses a sheet larger than rastray writes: [`MAX_DIMENSION`] pixels a side.
    pub fn check(&self, count: usize) -> Result<(), String> {
        let (width, height) = self.size(count);
        if width > u64::from(MAX_DIMENSION) || height > u64::from(MAX_DIMENSION) {
            return Err(format!(
                "a sheet of {count} thumbnails in {} columns would be {width}x{height} pixels; at most {MAX_DIMENSION} a side: use smaller cells or other columns",
                self.columns
            ));
        }
        Ok(())
    }
}

/// Lays `thumbnails` out row by row, left to right, and titles each.
pub fn compose_sheet(thumbnails: &[Thumbnail], layout: SheetLayout) -> Result<SheetImage, String> {
    layout.check(thumbnails.len())?;
    let (width, height) = layout.size(thumbnails.len());
    let (width, height) = (width as u32, height as u32);
    let mut pixels: Vec<u8> = BACKGROUND
        .iter()
        .copied()
        .cycle()
        .take(width as usize * height as usize * 3)
        .collect();
    let (cw, ch) = (layout.cell_width as usize, layout.cell_height as usize);
    let origin = |i: usize| {
        let (col, row) = (i as u32 % layout.columns, i as u32 / layout.columns);
        (
            col * layout.cell_width,
            row * (layout.cell_height + TITLE_HEIGHT),
        )
    };
    for (i, thumbnail) in thumbnails.iter().enumerate() {
        if thumbnail.pixels.len() != cw * ch * 3 {
            return Err(format!(
                "thumbnail {:?} is not {cw}x{ch} pixels",
                thumbnail.title
            ));
        }
        let (x, y) = origin(i);
        for row in 0..ch {
            let to = ((y as usize + row) * width as usize + x as usize) * 3;
            pixels[to..to + cw * 3].copy_from_slice(&thumbnail.pixels[row * cw * 3..][..cw * 3]);
        }
    }
    register_bundled_font();
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
        let style = (FONT, TITLE_SIZE)
            .into_font()
            .color(&RGBColor(230, 230, 230));
        for (i, thumbnail) in thumbnails.iter().enumerate() {
            let (x, y) = origin(i);
            let title = fit(&thumbnail.title, layout.cell_width);
            let at = (x as i32 + 4, (y + layout.cell_height) as i32 + 3);
            root.draw(&Text::new(title, at, style.clone()))
                .map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(SheetImage {
        width,
        height,
        pixels,
    })
}

/// `title` cut to what a cell `width` pixels wide shows, with an ellipsis when cut.
fn fit(title: &str, width: u32) -> String {
    let fits = (width.saturating_sub(8) / CHAR_WIDTH).max(1) as usize;
    if title.chars().count() <= fits {
        return title.to_string();
    }
    let mut cut: String = title.chars().take(fits.saturating_sub(1)).collect();
    cut.push('…');
    cut
}

/// Writes `sheet` to `destination` as an 8-bit PNG (a file atomically).
pub fn save_sheet(
    sheet: &SheetImage,
    destination: &Destination,
    progress: &Progress,
) -> Result<(), ExportError> {
    let path = destination.path();
    let mut bytes = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut bytes);
    image::ImageEncoder::write_image(
        encoder,
        &sheet.pixels,
        sheet.width,
        sheet.height,
        image::ExtendedColorType::Rgb8,
    )
    .map_err(|e| ExportError::encode(path, "png8", e))?;
    progress.check().map_err(RenderError::from)?;
    let mut sink = destination.open(progress)?;
    sink.write_all(&bytes)
        .map_err(|error| ExportError::io(path, error))?;
    sink.commit(progress).map_err(|error| error.at(path))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(title: &str, rgb: [u8; 3], w: usize, h: usize) -> Thumbnail {
        Thumbnail {
            title: title.to_string(),
            pixels: rgb.iter().copied().cycle().take(w * h * 3).collect(),
        }
    }

    #[test]
    fn thumbnails_fill_the_grid_row_by_row_with_titles_below() {
        let layout = SheetLayout::new(3, None, (60, 10));
        assert_eq!(layout.columns, 2, "⌈√3⌉ columns");
        let thumbs = [
            solid("red", [255, 0, 0], 60, 10),
            solid("green", [0, 255, 0], 60, 10),
            solid("blue", [0, 0, 255], 60, 10),
        ];
        let sheet = compose_sheet(&thumbs, layout).unwrap();
        assert_eq!((sheet.width, sheet.height), (120, 2 * (10 + TITLE_HEIGHT)));
        let at = |x: u32, y: u32| {
            let i = ((y * sheet.width + x) * 3) as usize;
            [sheet.pixels[i], sheet.pixels[i + 1], sheet.pixels[i + 2]]
        };
        assert_eq!(at(30, 5), [255, 0, 0]);
        assert_eq!(at(90, 5), [0, 255, 0]);
        assert_eq!(at(30, 10 + TITLE_HEIGHT + 5), [0, 0, 255]);
        assert_eq!(at(90, 10 + TITLE_HEIGHT + 5), BACKGROUND, "the empty cell");
        // Each title strip holds text: some pixels brighter than the background.
        for (x0, y0) in [(0, 10), (60, 10), (0, 10 + TITLE_HEIGHT + 10)] {
            let lit = (x0..x0 + 60)
                .flat_map(|x| (y0..y0 + TITLE_HEIGHT).map(move |y| (x, y)))
                .filter(|&(x, y)| at(x, y)[0] > 120)
                .count();
            assert!(lit > 10, "a title at ({x0}, {y0}): {lit} lit pixels");
        }
    }

    #[test]
    fn long_titles_are_cut_and_huge_sheets_refused() {
        assert_eq!(fit("bunny", 256), "bunny");
        let cut = fit("a-very-long-model-file-name", 64);
        assert!(cut.ends_with('…') && cut.chars().count() == 7, "{cut}");
        let layout = SheetLayout::new(400, Some(100), (256, 256));
        assert!(layout.check(400).unwrap_err().contains("25600x"));
        assert_eq!(SheetLayout::new(2, Some(9), (8, 8)).columns, 2);
    }
}
