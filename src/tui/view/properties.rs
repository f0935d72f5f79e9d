//! The properties of the selected item, with the value being typed and its error inline.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{List, ListItem, ListState, StatefulWidget, Widget};

use super::pane;
use crate::tui::state::app::App;
use crate::tui::state::fields::Part;
use crate::tui::state::mode::Mode;
use crate::tui::state::selection::{self, Focus};
use crate::tui::view::theme;

/// Columns a label takes where there is room, before the space that separates it from its value.
const LABEL_COLUMNS: usize = 15;

/// Most columns the labels make room for: a number such as `-12.375`.
const VALUE_ROOM: usize = 8;

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
        let keys = part.keys();
        let values: Vec<String> = keys
            .iter()
            .map(|&key| part.value(key).map(|v| v.to_string()).unwrap_or_default())
            .collect();
        let width = label_width(area.width, values.iter().map(|v| v.chars().count()));
        let items: Vec<ListItem> = keys
            .into_iter()
            .zip(values)
            .enumerate()
            .map(|(i, (key, value))| {
                let label = Span::styled(
                    format!("{:<width$} ", shorten(&key.label(&part), width)),
                    theme::LABEL,
                );
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
                    _ => ListItem::new(Line::from(vec![label, Span::raw(value)])),
                }
            })
            .collect();
        // The measurements lead, read-only, so a short pane still shows them.
        let measured = measurement_lines(app);
        let first_field = measured.len();
        let items = [measured, items].concat();
        let highlight = if focused {
            theme::SELECTED
        } else {
            theme::PLAIN
        };
        let list = List::new(items)
            .block(pane("Properties", focused))
            .highlight_style(highlight)
            .highlight_symbol("▶");
        let mut state = ListState::default().with_selected(Some(first_field + app.field()));
        StatefulWidget::render(list, area, buf, &mut state);
    }
}

/// Read-only lines over the selected object's properties: its size, area, closure and volume
/// as the worker last measured them (world units); none for other items or before a measure.
fn measurement_lines(app: &App) -> Vec<ListItem<'static>> {
    let (selection::Item::Object(i), Some((object, m))) = (app.item(), &app.previews.shape) else {
        return Vec::new();
    };
    if i != *object {
        return Vec::new();
    }
    let size = m.size();
    let solid = match m.volume {
        Some(volume) => format!("{} · volume {volume:.3}", m.closure()),
        None => m.closure(),
    };
    let lines = [
        format!("size {:.3} × {:.3} × {:.3}", size.x, size.y, size.z),
        format!("area {:.3}", m.area),
        solid,
        format!(
            "non-manifold {} · degenerate {}",
            m.non_manifold_edges, m.degenerate_triangles
        ),
    ];
    lines
        .into_iter()
        .map(|text| ListItem::new(Line::styled(format!(" {text}"), theme::LABEL)))
        .collect()
}

/// Columns for the labels in a properties pane `pane_width` wide (borders included): 15 (the
/// values start in the same column on every item), fewer when the values need the room. Labels give way before
/// values do: a label is cut short so that the longest value shows whole, as long as a label
/// keeps 3 columns. Values longer than [`VALUE_ROOM`] (names, paths) are not given more.
pub fn label_width(pane_width: u16, values: impl Iterator<Item = usize>) -> usize {
    // Two borders, the highlight symbol, and a space between label and value.
    let room = usize::from(pane_width).saturating_sub(4);
    let longest_value = values.max().unwrap_or(0).min(VALUE_ROOM);
    LABEL_COLUMNS.min(room.saturating_sub(longest_value).max(3))
}

/// `label` in at most `width` columns, keeping the part that tells it from its neighbours: a
/// dotted label (`camera.target.x`) keeps its last part whole and shortens the parts before it,
/// the first ones first, to one letter each (`cam.target.x`, `c.t.x`); then it drops leading
/// parts after an ellipsis (`…x`); other labels are cut at the end.
pub fn shorten(label: &str, width: usize) -> String {
    let length = |parts: &[String]| {
        parts.iter().map(|p| p.chars().count()).sum::<usize>() + parts.len().saturating_sub(1)
    };
    let mut parts: Vec<String> = label.split('.').map(str::to_string).collect();
    if length(&parts) <= width {
        return label.to_string();
    }
    if parts.len() == 1 {
        return label.chars().take(width).collect();
    }
    let last = parts.len() - 1;
    for i in 0..last {
        let excess = length(&parts).saturating_sub(width);
        let keep = parts[i].chars().count().saturating_sub(excess).max(1);
        parts[i] = parts[i].chars().take(keep).collect();
    }
    if length(&parts) <= width {
        return parts.join(".");
    }
    while length(&parts) + 1 > width && parts.len() > 1 {
        parts.remove(0);
    }
    format!("…{}", parts.join("."))
        .chars()
        .take(width)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::{label_width, shorten};

    #[test]
    fn shortened_labels_keep_the_part_that_tells_them_apart() {
        assert_eq!(shorten("camera.target.x", 15), "camera.target.x");
        assert_eq!(shorten("camera.target.x", 12), "cam.target.x");
        assert_eq!(shorten("camera.target.y", 9), "c.targe.y");
        assert_eq!(shorten("camera.target.z", 5), "c.t.z");
        assert_eq!(shorten("camera.target.z", 3), "…z");
        assert_eq!(shorten("reflection", 8), "reflecti");
        for width in 3..16 {
            let labels: Vec<String> = ["x", "y", "z"]
                .iter()
                .map(|axis| shorten(&format!("camera.target.{axis}"), width))
                .collect();
            assert!(labels.iter().all(|l| l.chars().count() <= width));
            assert!(
                labels[0] != labels[1] && labels[1] != labels[2],
                "{labels:?}"
            );
        }
    }

    #[test]
    fn labels_give_way_before_values() {
        // Wide enough for both: the full label column.
        assert_eq!(label_width(40, [5].into_iter()), 15);
        // 20 columns leave 16 for label and value: the 5-character value keeps its room.
        assert_eq!(label_width(20, [5].into_iter()), 11);
        assert_eq!(label_width(14, [5].into_iter()), 5);
        // Labels keep 3 columns, and long values (names) are not given more than 8.
        assert_eq!(label_width(14, [30].into_iter()), 3);
        assert_eq!(label_width(20, [30].into_iter()), 8);
    }
}
