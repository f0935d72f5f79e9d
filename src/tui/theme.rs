//! The editor's colours and text styles, named by what they mark. Widgets use these names and
//! write no colour of their own; only the preview's pixels bring other colours to the screen.

use ratatui::style::{Color, Modifier, Style};

/// The terminal's own colour: what a cell shows where the editor sets none.
pub const TERMINAL_DEFAULT: Color = Color::Reset;

/// Text with no style of its own.
pub const PLAIN: Style = Style::new();
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
