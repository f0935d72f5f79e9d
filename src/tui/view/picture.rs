//! The preview pane: the rendered image in text cells (half blocks, quadrants, sextants or
//! braille) or as a picture in real pixels (drawn by `tui::terminal::image_layer` over blank cells), or the
//! three algorithms side by side.

use ratatui::buffer::Buffer;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::Color;
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Widget};

use super::pen::Pen;
use super::{compare_panes, millis, pane};
use crate::terminal_image::glyph_cells::{self, CellChooser};
use crate::terminal_image::preview::{
    ColorMode, HalfBlock, PreviewImage, half_block_each, halves_match,
};
use crate::terminal_image::{GlyphSet, kitty_placeholder};
use crate::tui::state::app::{App, Shot};
use crate::tui::state::mode::Mode;
use crate::tui::state::selection::Focus;
use crate::tui::terminal::image_layer::{Placement, placeholder_colour};
use crate::tui::terminal::motion::CoarseMask;
use crate::tui::view::theme;

/// An image drawn into cells: with half blocks, cell (c, r) shows pixels (c, 2r) over
/// (c, 2r + 1); with a finer set, each cell is the glyph and two colours that best fit the
/// pixels under it.
pub struct Picture<'a> {
    pub image: &'a PreviewImage,
    pub mode: ColorMode,
    /// Pixels drawn in the 256-colour palette while the camera moves (see `tui::motion`).
    pub coarse: &'a CoarseMask,
    /// The glyph set.
    pub set: GlyphSet,
}

impl Widget for Picture<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        match self.set {
            GlyphSet::HalfBlock => self.half_blocks(area, buf),
            set => self.glyphs(set, area, buf),
        }
    }
}

impl Picture<'_> {
    /// Draws the image with `set`, resampled to the grid the encoder samples; a cell with any
    /// coarse pixel under it is drawn in the 256-colour palette. Colours close to the pen's are
    /// drawn with the pen's (see [`Pen`]).
    fn glyphs(&self, set: GlyphSet, area: Rect, buf: &mut Buffer) {
        let (cols, rows) = (u32::from(area.width), u32::from(area.height));
        if cols == 0 || rows == 0 || self.image.pixels.is_empty() {
            return;
        }
        let image = glyph_cells::fit(self.image, cols, rows);
        let mut chooser = CellChooser::new(set);
        let coarse = |col: u32, row: u32| {
            let Some(mask) = self.coarse.as_ref() else {
                return false;
            };
            let x0 = col * self.image.width / cols;
            let x1 = ((col + 1) * self.image.width).div_ceil(cols);
            let y0 = row * self.image.height / rows;
            let y1 = ((row + 1) * self.image.height).div_ceil(rows);
            (y0..y1.min(self.image.height)).any(|y| {
                (x0..x1.min(self.image.width)).any(|x| mask[(y * self.image.width + x) as usize])
            })
        };
        for row in 0..rows {
            let mut pen = Pen::default();
            for col in 0..cols {
                let mut cell = chooser.choose(&image, col, row);
                cell.bg = pen.bg(cell.bg);
                if cell.glyph != ' ' {
                    cell.fg = pen.fg(cell.fg);
                }
                let mode = if coarse(col, row) {
                    ColorMode::Ansi256
                } else {
                    self.mode
                };
                let fg = if cell.glyph == ' ' {
                    theme::TERMINAL_DEFAULT
                } else {
                    mode.color(cell.fg)
                };
                if let Some(c) = buf.cell_mut((area.x + col as u16, area.y + row as u16)) {
                    let mut utf8 = [0u8; 4];
                    c.set_symbol(cell.glyph.encode_utf8(&mut utf8))
                        .set_fg(fg)
                        .set_bg(mode.color(cell.bg));
                }
            }
        }
    }

    /// Draws the image at one pixel per column and two per row; an image of another size (one
    /// rendered for real pixels, shown while a dialog is open, or with square pixels on cells
    /// that are not 1:2) is sampled to that grid. Colours close to the pen's are drawn with the
    /// pen's (see [`Pen`]).
    fn half_blocks(&self, area: Rect, buf: &mut Buffer) {
        let (grid_w, grid_h) = (u32::from(area.width), 2 * u32::from(area.height));
        let scaled = self.image.width > grid_w || self.image.height > grid_h;
        let sample = |v: u32, grid: u32, size: u32| match scaled {
            true => {
                ((u64::from(v) * u64::from(size) + u64::from(size) / 2) / u64::from(grid.max(1)))
                    as u32
            }
            false => v,
        };
        for row in 0..area.height {
            let mut pen = Pen::default();
            for col in 0..area.width {
                let (x, y) = (col as u32, 2 * row as u32);
                let pixel = |x: u32, y: u32| {
                    let x = sample(x, grid_w, self.image.width);
                    let y = sample(y, grid_h, self.image.height);
                    let rgb = self.image.pixel(x, y)?;
                    let index = (y * self.image.width + x) as usize;
                    let coarse = self.coarse.as_ref().is_some_and(|m| m[index]);
                    Some((
                        rgb,
                        if coarse {
                            ColorMode::Ansi256
                        } else {
                            self.mode
                        },
                    ))
                };
                let cell = match (pixel(x, y), pixel(x, y + 1)) {
                    // A cell of one colour shows the background only.
                    (Some(u), Some(l)) if halves_match(u.0, l.0) => {
                        let c = (pen.bg_of_both(u.0, l.0), u.1);
                        half_block_each(Some(c), Some(c))
                    }
                    // Two colours stay two, whatever the pen makes of them.
                    (Some(u), Some(l)) => HalfBlock {
                        symbol: "▀",
                        fg: u.1.color(pen.fg(u.0)),
                        bg: l.1.color(pen.bg(l.0)),
                    },
                    (Some(u), None) => {
                        pen.default_bg();
                        half_block_each(Some((pen.fg(u.0), u.1)), None)
                    }
                    (None, l) => half_block_each(None, l),
                };
                if let Some(c) = buf.cell_mut((area.x + col, area.y + row)) {
                    c.set_symbol(cell.symbol).set_fg(cell.fg).set_bg(cell.bg);
                }
            }
        }
    }
}

/// Whether `shot`, shown over `area`, is a picture in real pixels: the editor draws with a
/// graphics protocol, the image has the size rendered for that area (frames rendered in half-block
/// size while keys arrive stay half blocks), no dialog or help is open over the preview, and the
/// pane has the focus where pictures leave with it (see `Graphics::hides_unfocused`).
fn shows_pixels(app: &App, area: Rect, shot: &Shot) -> bool {
    let size = app.view.pixel_size(area.width, area.height);
    size == Some((shot.image.width, shot.image.height))
        && matches!(app.mode, Mode::Normal | Mode::Edit(_))
        && app.view.pixels_while_focused()
}

/// The pictures the preview shows in real pixels when the panes are laid out with the picture
/// area `picture`: slot 0 the single preview, 1..=3 the compare panes.
pub fn placements(app: &App, picture: Rect) -> Vec<Placement<'_>> {
    let shots: Vec<(Rect, Option<&Shot>)> = if app.view.compare() {
        compare_panes(picture)
            .into_iter()
            .zip(&app.previews.compare)
            .map(|((_, _, image), shot)| (image, shot.as_ref()))
            .collect()
    } else {
        vec![(picture, app.previews.shot.as_ref())]
    };
    let offset = usize::from(app.view.compare());
    shots
        .into_iter()
        .enumerate()
        .filter_map(|(i, (area, shot))| {
            let shot = shot.filter(|s| shows_pixels(app, area, s))?;
            Some(Placement {
                slot: i + offset,
                area,
                image: &shot.image,
            })
        })
        .collect()
}

/// A shot drawn over `area` in `slot` (see [`placements`]): half blocks, or the cells under a
/// picture in real pixels: blank, or kitty's Unicode placeholders where the picture is drawn
/// with them (inside tmux, see `tui::terminal::image_layer`), the image id's low byte in the foreground.
fn draw_shot(app: &App, slot: usize, shot: &Shot, area: Rect, buf: &mut Buffer) {
    if shows_pixels(app, area, shot) {
        buf.set_style(area, theme::PICTURE_UNDER);
        let placeholders = app.view.graphics().placeholders;
        if placeholders.is_some() {
            buf.set_style(
                area,
                theme::PICTURE_UNDER.fg(Color::Indexed(placeholder_colour(slot))),
            );
        }
        for position in area.positions() {
            let (row, col) = (position.y - area.y, position.x - area.x);
            let symbol = placeholders.and_then(|high| kitty_placeholder::cell(row, col, high));
            if let Some(c) = buf.cell_mut(position) {
                c.set_symbol(symbol.as_deref().unwrap_or(" "));
            }
        }
    } else {
        Picture {
            image: &shot.image,
            mode: app.view.color(),
            coarse: &shot.coarse,
            set: app.view.graphics().cells,
        }
        .render(area, buf);
    }
}

/// The bordered preview pane.
pub struct PreviewPane<'a>(pub &'a App);

impl Widget for PreviewPane<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let app = self.0;
        let view = &app.view;
        let mut title = if view.compare() {
            "Preview · compare".to_string()
        } else {
            format!("Preview · {}", view.algorithm())
        };
        // The view-only tools in use: the projection, the preset, the spin.
        if view.camera().projection == crate::scene::Projection::Orthographic {
            title.push_str(" · ortho");
        }
        if let Some(preset) = view.preset() {
            title.push_str(&format!(" · {preset}"));
        }
        if view.spinning() {
            title.push_str(" · spinning");
        }
        if view.camera() != app.doc.scene().camera {
            // Looking around is not saved: say how to keep it.
            title.push_str(" · view moved, C keeps it");
        }
        let block = pane(&title, app.focus() == Focus::Preview);
        let inner = block.inner(area);
        block.render(area, buf);
        if view.compare() {
            for (i, (algorithm, label, image)) in compare_panes(inner).into_iter().enumerate() {
                let shot = app.previews.compare[i].as_ref();
                let text = match shot {
                    Some(s) => format!("{} {} {}", i + 1, algorithm, millis(app, s.millis)),
                    None => format!("{} {} …", i + 1, algorithm),
                };
                Paragraph::new(text)
                    .alignment(Alignment::Center)
                    .style(theme::HEADING)
                    .render(label, buf);
                if let Some(s) = shot {
                    draw_shot(app, i + 1, s, image, buf);
                }
            }
        } else if let Some(shot) = &app.previews.shot {
            draw_shot(app, 0, shot, inner, buf);
        } else {
            Paragraph::new(Line::styled("rendering…", theme::DIM))
                .alignment(Alignment::Center)
                .render(inner, buf);
        }
    }
}
