//! Pop-ups: the add menu, path prompts, the export dialog and the quit question.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{Clear, List, ListItem, ListState, Paragraph, StatefulWidget, Widget, Wrap};

use super::pane;
use crate::tui::input::keys::add_hotkey;
use crate::tui::state::mode::{AddKind, ExportField, ExportForm, LineEdit, PromptPurpose};
use crate::tui::view::theme;

/// A `width`×`height` rectangle centred in `area`, clipped to it.
pub fn centered(area: Rect, width: u16, height: u16) -> Rect {
    let (w, h) = (width.min(area.width), height.min(area.height));
    Rect::new(
        area.x + (area.width - w) / 2,
        area.y + (area.height - h) / 2,
        w,
        h,
    )
}

fn input_line(text: &str, active: bool) -> Span<'static> {
    let style = if active { theme::TYPING } else { theme::TYPED };
    Span::styled(format!("{}{}", text, if active { "▏" } else { "" }), style)
}

fn error_line(error: &Option<String>) -> Line<'static> {
    match error {
        Some(e) => Line::styled(format!("✗ {e}"), theme::INVALID),
        None => Line::default(),
    }
}

/// What can be added, with hotkeys.
pub struct AddMenu(pub usize);

impl Widget for AddMenu {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let popup = centered(area, 30, AddKind::ALL.len() as u16 + 2);
        Clear.render(popup, buf);
        let items: Vec<ListItem> = AddKind::ALL
            .iter()
            .map(|&k| {
                let hotkey = add_hotkey(k).unwrap_or(' ');
                ListItem::new(format!("{hotkey}  {}", k.label()))
            })
            .collect();
        let list = List::new(items)
            .block(pane("Add", true))
            .highlight_style(theme::SELECTED)
            .highlight_symbol("▶");
        StatefulWidget::render(
            list,
            popup,
            buf,
            &mut ListState::default().with_selected(Some(self.0)),
        );
    }
}

/// A typed path; the flag says whether the scene has unsaved edits.
pub struct Prompt<'a>(pub PromptPurpose, pub &'a LineEdit, pub bool);

impl Widget for Prompt<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let title = match self.0 {
            PromptPurpose::SaveAs => "Save scene as",
            PromptPurpose::Open if self.2 => "Open scene (unsaved edits are dropped)",
            PromptPurpose::Open => "Open scene",
            PromptPurpose::ObjPath => "OBJ, STL, PLY or glTF file (relative to the scene's folder)",
        };
        let popup = centered(area, 64, 5);
        Clear.render(popup, buf);
        Paragraph::new(vec![
            Line::from(input_line(&self.1.text, true)),
            error_line(&self.1.error),
            Line::styled("Enter accept · Esc cancel", theme::DIM),
        ])
        .wrap(Wrap { trim: false })
        .block(pane(title, true))
        .render(popup, buf);
    }
}

/// File, format, size, algorithm, samples, background and turntable frames of an export.
pub struct ExportDialog<'a>(pub &'a ExportForm);

impl Widget for ExportDialog<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let form = self.0;
        let popup = centered(area, 60, 12);
        Clear.render(popup, buf);
        let row = |label: &str, field: ExportField, value: String| {
            let active = form.field == field;
            Line::from(vec![
                Span::styled(
                    format!("{}{label:<11}", if active { "▶ " } else { "  " }),
                    if active { theme::ACCENT } else { theme::LABEL },
                ),
                input_line(&value, active),
            ])
        };
        let algorithm = format!("◀ {} ▶", form.algorithm);
        let format = match form.format {
            Some(format) => format!("◀ {format} ▶"),
            None => "◀ by extension ▶".to_string(),
        };
        let background = match form.transparent {
            true => "◀ transparent ▶",
            false => "◀ opaque ▶",
        };
        let mut turntable = row("turntable", ExportField::Turntable, form.turntable.clone());
        turntable.push_span(Span::styled(
            "  frames (.gif, .png); 0: image (.png, .exr)",
            theme::DIM,
        ));
        Paragraph::new(vec![
            row("file", ExportField::Path, form.path.clone()),
            row("size", ExportField::Size, form.size.clone()),
            row("algorithm", ExportField::Algorithm, algorithm),
            row("samples", ExportField::Samples, form.samples.clone()),
            row("format", ExportField::Format, format),
            row(
                "background",
                ExportField::Background,
                background.to_string(),
            ),
            turntable,
            error_line(&form.error),
            Line::styled(
                "↑↓ field · ←→ choose · Enter export · Esc cancel",
                theme::DIM,
            ),
        ])
        .block(pane("Export", true))
        .render(popup, buf);
    }
}

/// The question asked before quitting with unsaved edits.
pub struct ConfirmQuit;

impl Widget for ConfirmQuit {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let popup = centered(area, 44, 4);
        Clear.render(popup, buf);
        Paragraph::new(vec![
            Line::from("The scene has unsaved edits."),
            Line::styled("y quit · s save and quit · n stay", theme::WARNING),
        ])
        .block(pane("Quit?", true))
        .render(popup, buf);
    }
}
