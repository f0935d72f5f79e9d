//! `rastray view IN... --grid`: a contact sheet in the terminal. Each input is rendered by one
//! renderer as a square thumbnail; the thumbnails of a row are drawn as one picture in the
//! protocol in use (pixels or cells), and a text line under it names each one by its file's
//! stem. Rows are printed as they are ready, so a long list shows its first row at once. A file
//! that fails is reported on its own line and left out; the run then ends with exit code 1.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use rastray::render::{Frame, Progress, RenderOptions, Renderer};
use rastray::terminal_image::preview::PreviewImage;
use rastray::terminal_image::{CellArea, CellSize, Protocol};
use rastray::text_escape::Escaped;
use rastray::world::MeshFileCache;

use super::camera_args::CameraArgs;
use super::display_args::DisplayArgs;

/// Columns of a thumbnail when `--columns` is absent: as many thumbnails of about this width as
/// fit the terminal.
const THUMBNAIL_COLS: u32 = 24;

/// Blank columns between two thumbnails.
const GAP_COLS: u32 = 1;

/// The colour of the gaps between thumbnails (and of a row's empty places): the editor's
/// preview background.
const GAP_COLOR: [u8; 3] = [0, 0, 0];

/// How the thumbnails sit in the terminal, in cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GridLayout {
    /// Thumbnails per row, at least 1.
    pub columns: u32,
    /// Each thumbnail's area: square in pixels on the terminal's cells.
    pub thumbnail: CellArea,
}

impl GridLayout {
    /// The layout of `count` thumbnails across `cols` terminal columns: `columns` per row when
    /// asked, else as many of about [`THUMBNAIL_COLS`] columns as fit, never more than `count`.
    pub fn new(count: usize, cols: u32, columns: Option<u32>, cell: CellSize) -> GridLayout {
        let count = u32::try_from(count.max(1)).unwrap_or(u32::MAX);
        let columns = columns
            .unwrap_or((cols + GAP_COLS) / (THUMBNAIL_COLS + GAP_COLS))
            .clamp(1, count);
        let width = (cols.saturating_sub((columns - 1) * GAP_COLS) / columns).max(1);
        GridLayout {
            columns,
            thumbnail: CellArea::for_aspect(width, 1.0, cell),
        }
    }

    /// The cells of a whole row: `columns` thumbnails and the gaps between them.
    pub fn row(&self) -> CellArea {
        CellArea {
            cols: self.columns * self.thumbnail.cols + (self.columns - 1) * GAP_COLS,
            rows: self.thumbnail.rows,
        }
    }

    /// The title line under a row: each title cut to its thumbnail's width (with `…`) and
    /// centred under it. Titles are shown escaped, so a file name cannot move the cursor.
    pub fn title_line(&self, titles: &[String]) -> String {
        let width = self.thumbnail.cols as usize;
        let mut line = String::new();
        for (i, title) in titles.iter().enumerate() {
            if i > 0 {
                line.push_str(&" ".repeat(GAP_COLS as usize));
            }
            let shown = Escaped(title).to_string();
            let chars: Vec<char> = shown.chars().collect();
            let cut: String = if chars.len() > width {
                chars[..width.saturating_sub(1)]
                    .iter()
                    .chain(std::iter::once(&'…'))
                    .collect()
            } else {
                shown
            };
            let pad = width - cut.chars().count();
            line.push_str(&" ".repeat(pad / 2));
            line.push_str(&cut);
            line.push_str(&" ".repeat(pad - pad / 2));
        }
        line.trim_end().to_string()
    }
}

/// What every thumbnail shares.
pub struct GridRequest<'a> {
    pub inputs: &'a [PathBuf],
    pub protocol: Protocol,
    /// Terminal columns to fill.
    pub cols: u32,
    pub cell: CellSize,
    pub columns: Option<u32>,
    /// Algorithm, samples and the like; the size is the thumbnail's.
    pub options: RenderOptions,
    pub display: &'a DisplayArgs,
    pub camera: &'a CameraArgs,
    /// For a model file: the axis of the file that points up.
    pub up: Option<rastray::scene::UpAxis>,
}

/// Renders the inputs (sorted, each once) row by row to stdout.
pub fn run(request: &GridRequest) -> anyhow::Result<ExitCode> {
    let mut inputs = request.inputs.to_vec();
    inputs.sort();
    inputs.dedup();
    let layout = GridLayout::new(inputs.len(), request.cols, request.columns, request.cell);
    let (width, height) = request
        .protocol
        .picture_size(layout.thumbnail, request.cell);
    let mut options = request.display.apply(RenderOptions {
        width,
        height,
        alpha: false,
        ..request.options
    });
    // Text cells are too coarse for the box's written lengths.
    options.overlays.labels &= request.protocol.has_pixels();
    options.check()?;
    let mut renderer = Renderer::new(options);
    let mut frame = Frame::default();
    let mut row: Vec<(String, PreviewImage)> = Vec::new();
    let mut failed = Vec::new();
    let mut shown = 0;
    for input in &inputs {
        match thumbnail(input, request, &mut renderer, &mut frame) {
            Ok(image) => {
                row.push((stem(input), image));
                shown += 1;
            }
            Err(error) => {
                let name = Escaped(&input.display().to_string()).to_string();
                let message = Escaped(&format!("{error:#}")).to_string();
                let _ = std::io::stdout().flush();
                if message.starts_with(&name) {
                    eprintln!("error: {message}");
                } else {
                    eprintln!("error: {name}: {message}");
                }
                failed.push(name);
            }
        }
        if row.len() == layout.columns as usize {
            print_row(&layout, request, &row)?;
            row.clear();
        }
    }
    if !row.is_empty() {
        print_row(&layout, request, &row)?;
    }
    if failed.is_empty() {
        return Ok(ExitCode::SUCCESS);
    }
    eprintln!(
        "showed {shown} of {} inputs; failed: {}",
        inputs.len(),
        failed.join(", ")
    );
    Ok(ExitCode::from(1))
}

/// One input rendered at the thumbnail's size, its camera placed by the first `--view`.
fn thumbnail(
    input: &Path,
    request: &GridRequest,
    renderer: &mut Renderer,
    frame: &mut Frame,
) -> anyhow::Result<PreviewImage> {
    let up = request
        .up
        .filter(|_| rastray::model_scene::is_model_file(input));
    let (scene, report) = super::load_world(Some(input), up, MeshFileCache::default())?;
    let world = std::sync::Arc::new(report.world);
    let options = renderer.options();
    let aspect = options.width as f32 / options.height as f32;
    let camera = request.camera.camera_for(
        request.camera.view.first().copied(),
        &scene.camera,
        &world,
        aspect,
    );
    renderer.render(&world, &camera, &Progress::new(), frame)?;
    Ok(PreviewImage::from_frame(frame))
}

/// Draws one row of thumbnails side by side as one picture, then their titles.
fn print_row(
    layout: &GridLayout,
    request: &GridRequest,
    row: &[(String, PreviewImage)],
) -> anyhow::Result<()> {
    let area = layout.row();
    let (width, height) = request.protocol.picture_size(area, request.cell);
    let mut picture = PreviewImage {
        width,
        height,
        pixels: vec![GAP_COLOR; width as usize * height as usize],
    };
    for (i, (_, image)) in row.iter().enumerate() {
        // The thumbnail's first column, in cells, then in the row picture's pixels.
        let col = i as u32 * (layout.thumbnail.cols + GAP_COLS);
        let x0 = (u64::from(col) * u64::from(width) / u64::from(area.cols)) as u32;
        blit(&mut picture, image, x0);
    }
    let mut bytes = request
        .protocol
        .encode(&picture, area)
        .context("cannot encode the picture")?;
    if request.protocol.has_pixels() {
        bytes.push(b'\n');
    }
    let titles: Vec<String> = row.iter().map(|(title, _)| title.clone()).collect();
    bytes.extend_from_slice(layout.title_line(&titles).as_bytes());
    bytes.push(b'\n');
    super::stdout::bytes(&bytes);
    Ok(())
}

/// Copies `image` into `picture` with its left edge at column `x0`, clipped to `picture`.
fn blit(picture: &mut PreviewImage, image: &PreviewImage, x0: u32) {
    let width = image.width.min(picture.width.saturating_sub(x0)) as usize;
    for y in 0..image.height.min(picture.height) as usize {
        let from = y * image.width as usize;
        let to = y * picture.width as usize + x0 as usize;
        picture.pixels[to..to + width].copy_from_slice(&image.pixels[from..from + width]);
    }
}

fn stem(input: &Path) -> String {
    input
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thumbnails_fill_the_width_with_gaps() {
        let layout = GridLayout::new(10, 80, None, CellSize::default());
        // (80 + 1) / 25 = 3 columns of (80 - 2) / 3 = 26 cells.
        assert_eq!(layout.columns, 3);
        assert_eq!(layout.thumbnail.cols, 26);
        assert_eq!(layout.row().cols, 80);
        // Square in pixels on 10×20 cells: 260 px wide is 13 rows of 20 px.
        assert_eq!(layout.thumbnail.rows, 13);
    }

    #[test]
    fn never_more_columns_than_inputs() {
        let layout = GridLayout::new(2, 200, None, CellSize::default());
        assert_eq!(layout.columns, 2);
        let asked = GridLayout::new(9, 80, Some(4), CellSize::default());
        assert_eq!(asked.columns, 4);
        assert_eq!(asked.thumbnail.cols, 19);
    }

    #[test]
    fn titles_are_cut_and_centred_under_their_thumbnails() {
        let layout = GridLayout::new(2, 21, Some(2), CellSize::default());
        assert_eq!(layout.thumbnail.cols, 10);
        let line = layout.title_line(&["cube".into(), "stanford-bunny".into()]);
        assert_eq!(line, "   cube    stanford-…");
    }

    #[test]
    fn titles_cannot_carry_escapes() {
        let layout = GridLayout::new(1, 40, None, CellSize::default());
        let line = layout.title_line(&["a\x1b[2Jb".into()]);
        assert!(!line.contains('\x1b'), "{line:?}");
    }
}
