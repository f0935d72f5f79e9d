//! The editor's colours and text styles, named by what they mark. Widgets use these names and
//! write no colour of their own; only the preview's pixels bring other colours to the screen.

use ratatui::buffer::Buffer;
use ratatui::layout::{Position, Rect};
use ratatui::style::{Color, Modifier, Style};

pub use crate::terminal_image::preview::TERMINAL_DEFAULT;

/// Text with no style of its own.
pub const PLAIN: Style = Style::new();
/// Cells under a picture in real pixels: blank on the terminal's background. Their foreground,
/// which a blank cell never shows and which costs no byte, is one no other blank cell has, so
/// that whatever replaces them (a dialog's blank cells included) counts as a change and is
/// written, wiping a sixel or iTerm2 picture from those cells.
pub const PICTURE_UNDER: Style = Style::new()
    .fg(Color::Indexed(16))
    .bg(TERMINAL_DEFAULT)
    .remove_modifier(Modifier::all());
/// Hints, separators, placeholders, an unfocused pane's border, the help's context column.
pub const DIM: Style = Style::new().fg(Color::DarkGray);
/// Property labels and inactive dialog fields.
pub const LABEL: Style = Style::new().fg(Color::Gray);
/// The focused pane's border, key names in the help, the active dialog field.
pub const ACCENT: Style = Style::new().fg(Color::Yellow);
/// The focused pane's title.
pub const ACCENT_TITLE: Style = ACCENT.add_modifier(Modifier::BOLD);
/// Headings: the help's column titles, the compare view's labels.
pub const HEADING: Style = Style::new().add_modifier(Modifier::BOLD);

/// The highlighted row of the focused list or menu.
pub const SELECTED: Style = Style::new().bg(Color::Yellow).fg(Color::Black);
/// The highlighted row of the scene list when another pane has the focus.
pub const SELECTED_UNFOCUSED: Style = Style::new().add_modifier(Modifier::REVERSED);

/// The line being typed, with its cursor.
pub const TYPING: Style = Style::new().fg(Color::Black).bg(Color::White);
/// A dialog value not being typed into.
pub const TYPED: Style = Style::new().fg(Color::White);
/// An inline error under a typed value.
pub const INVALID: Style = Style::new().fg(Color::Red);

/// The algorithm (or "Compare") at the start of the status bar.
pub const ALGORITHM: Style = Style::new().fg(Color::Cyan).add_modifier(Modifier::BOLD);
/// The unsaved-edits marker, and the question asked before quitting.
pub const WARNING: Style = Style::new().fg(Color::Yellow);
/// A status message reporting success.
pub const INFO: Style = Style::new().fg(Color::Green);
/// A status message reporting a problem.
pub const ERROR: Style = Style::new().fg(Color::Red).add_modifier(Modifier::BOLD);
/// The export's progress bar.
pub const PROGRESS: Style = Style::new().fg(Color::Magenta).bg(Color::Black);

/// The scene list's tag of the camera and scene settings.
pub const TAG_SETTINGS: Style = Style::new().fg(Color::Cyan);
/// The scene list's tag of a light.
pub const TAG_LIGHT: Style = Style::new().fg(Color::Yellow);
/// The scene list's tag of an object.
pub const TAG_OBJECT: Style = Style::new().fg(Color::Green);

/// Takes the colours out of `area` except `keep` (the preview's picture): what `NO_COLOR` asks
/// of the interface. A cell that had a background (a highlighted row, the typing line) is shown
/// reversed instead, so highlights stay visible.
pub fn strip_colors(buf: &mut Buffer, area: Rect, keep: Rect) {
    for y in area.top()..area.bottom() {
        for x in area.left()..area.right() {
            if keep.contains(Position { x, y }) {
                continue;
            }
            let Some(cell) = buf.cell_mut((x, y)) else {
                continue;
            };
            if cell.bg != TERMINAL_DEFAULT {
                cell.modifier.insert(Modifier::REVERSED);
            }
            cell.fg = TERMINAL_DEFAULT;
            cell.bg = TERMINAL_DEFAULT;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stripping_leaves_the_picture_and_turns_backgrounds_into_reverse() {
        let area = Rect::new(0, 0, 4, 2);
        let mut buf = Buffer::empty(area);
        buf.set_style(area, SELECTED);
        buf.set_style(Rect::new(2, 0, 2, 2), Style::new().fg(Color::Rgb(1, 2, 3)));
        strip_colors(&mut buf, area, Rect::new(3, 0, 1, 2));
        let picture = &buf[(3, 1)];
        assert_eq!(
            (picture.fg, picture.bg),
            (Color::Rgb(1, 2, 3), Color::Yellow)
        );
        assert!(!picture.modifier.contains(Modifier::REVERSED));
        for x in 0..3 {
            let cell = &buf[(x, 0)];
            assert_eq!(
                (cell.fg, cell.bg),
                (TERMINAL_DEFAULT, TERMINAL_DEFAULT),
                "x={x}"
            );
            assert!(cell.modifier.contains(Modifier::REVERSED), "x={x}");
        }
    }
}
