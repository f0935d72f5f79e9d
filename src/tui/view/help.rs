//! The help overlay: every key, from the one key map.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Rect};
use ratatui::text::Span;
use ratatui::widgets::{Cell, Clear, Row, Table, Widget};

use super::dialogs::centered;
use super::pane;
use crate::tui::input::keys::KEYS;
use crate::tui::view::theme;

/// A centred table of [`KEYS`], scrolled down by the given number of rows.
pub struct HelpOverlay(pub usize);

impl Widget for HelpOverlay {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let popup = centered(area, 96, KEYS.len() as u16 + 3);
        Clear.render(popup, buf);
        let keys: Vec<String> = KEYS.iter().map(|k| k.keys()).collect();
        // The first two columns fit their widest entry; the descriptions take the rest.
        let width = |text: &str| Span::raw(text).width() as u16;
        let where_width = KEYS.iter().map(|k| width(k.context.label())).max();
        let keys_width = keys.iter().map(|k| width(k)).max();
        let rows = KEYS.iter().zip(&keys).skip(self.0).map(|(k, keys)| {
            Row::new([
                Cell::from(k.context.label()).style(theme::DIM),
                Cell::from(keys.as_str()).style(theme::ACCENT),
                Cell::from(k.what),
            ])
        });
        Table::new(
            rows,
            [
                Constraint::Length(where_width.unwrap_or(0)),
                Constraint::Length(keys_width.unwrap_or(0)),
                Constraint::Min(10),
            ],
        )
        .header(Row::new(["where", "keys", "what"]).style(theme::HEADING))
        .block(pane("Keys · j/k scroll · any other key closes", true))
        .render(popup, buf);
    }
}
