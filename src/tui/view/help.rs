//! The help overlay: every key, from the one key map.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Rect};
use ratatui::widgets::{Cell, Clear, Row, Table, Widget};

use super::dialogs::centered;
use super::pane;
use crate::tui::keys::KEYS;
use crate::tui::theme;

/// A centred table of [`KEYS`], scrolled down by the given number of rows.
pub struct HelpOverlay(pub usize);

impl Widget for HelpOverlay {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let popup = centered(area, 96, KEYS.len() as u16 + 3);
        Clear.render(popup, buf);
        let rows = KEYS.iter().skip(self.0).map(|k| {
            Row::new([
                Cell::from(k.context).style(theme::DIM),
                Cell::from(k.keys).style(theme::ACCENT),
                Cell::from(k.action),
            ])
        });
        Table::new(
            rows,
            [
                Constraint::Length(10),
                Constraint::Length(22),
                Constraint::Min(10),
            ],
        )
        .header(Row::new(["where", "keys", "what"]).style(theme::HEADING))
        .block(pane("Keys · j/k scroll · any other key closes", true))
        .render(popup, buf);
    }
}
