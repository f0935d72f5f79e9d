//! The properties of the selected item, with the value being typed and its error inline.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{List, ListItem, ListState, StatefulWidget, Widget};

use super::pane;
use crate::tui::app::App;
use crate::tui::fields::Part;
use crate::tui::mode::Mode;
use crate::tui::selection::Focus;
use crate::tui::theme;

/// Label and value of every property of the selected item.
pub struct Properties<'a>(pub &'a App);

impl Widget for Properties<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let app = self.0;
        let focused = app.focus() == Focus::Properties;
        let Some(part) = Part::of(app.doc.scene(), app.item()) else {
            pane("Properties", focused).render(area, buf);
            return;
        };
        // Labels take up to 16 columns, leaving at least 6 for the value in a narrow pane.
        let width = 16.min(area.width.saturating_sub(9) as usize);
        let items: Vec<ListItem> = part
            .keys()
            .into_iter()
            .enumerate()
            .map(|(i, key)| {
                let label = Span::styled(format!("{:<width$}", key.label(&part)), theme::LABEL);
                match &app.mode {
                    Mode::Edit(line) if i == app.field() => {
                        let mut lines = vec![Line::from(vec![
                            label,
                            Span::styled(format!("{}▏", line.text), theme::TYPING),
                        ])];
                        if let Some(error) = &line.error {
                            lines.push(Line::styled(format!("  ✗ {error}"), theme::INVALID));
                        }
                        ListItem::new(lines)
                    }
                    _ => {
                        let value = part.value(key).map(|v| v.to_string()).unwrap_or_default();
                        ListItem::new(Line::from(vec![label, Span::raw(value)]))
                    }
                }
            })
            .collect();
        let highlight = if focused {
            theme::SELECTED
        } else {
            theme::PLAIN
        };
        let list = List::new(items)
            .block(pane("Properties", focused))
            .highlight_style(highlight)
            .highlight_symbol("▶");
        let mut state = ListState::default().with_selected(Some(app.field()));
        StatefulWidget::render(list, area, buf, &mut state);
    }
}
