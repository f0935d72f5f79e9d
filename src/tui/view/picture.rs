//! The preview pane: the rendered image as half blocks, or the three algorithms side by side.

use ratatui::buffer::Buffer;
use ratatui::layout::{Alignment, Rect};
use ratatui::text::Line;
use ratatui::widgets::{Paragraph, Widget};

use super::{compare_panes, millis, pane};
use crate::tui::app::App;
use crate::tui::motion::CoarseMask;
use crate::tui::preview::{ColorMode, PreviewImage, half_block_each};
use crate::tui::selection::Focus;
use crate::tui::theme;

/// An image drawn into cells: cell (c, r) shows pixels (c, 2r) over (c, 2r + 1).
pub struct Picture<'a> {
    pub image: &'a PreviewImage,
    pub mode: ColorMode,
    /// Pixels drawn in the 256-colour palette while the camera moves (see `tui::motion`).
    pub coarse: &'a CoarseMask,
}

impl Widget for Picture<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        for row in 0..area.height {
            for col in 0..area.width {
                let (x, y) = (col as u32, 2 * row as u32);
                let pixel = |x: u32, y: u32| {
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
                let cell = half_block_each(pixel(x, y), pixel(x, y + 1));
                if let Some(c) = buf.cell_mut((area.x + col, area.y + row)) {
                    c.set_symbol(cell.symbol).set_fg(cell.fg).set_bg(cell.bg);
                }
            }
        }
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
                    Picture {
                        image: &s.image,
                        mode: view.color(),
                        coarse: &s.coarse,
                    }
                    .render(image, buf);
                }
            }
        } else if let Some(shot) = &app.previews.shot {
            Picture {
                image: &shot.image,
                mode: view.color(),
                coarse: &shot.coarse,
            }
            .render(inner, buf);
        } else {
            Paragraph::new(Line::styled("rendering…", theme::DIM))
                .alignment(Alignment::Center)
                .render(inner, buf);
        }
    }
}
