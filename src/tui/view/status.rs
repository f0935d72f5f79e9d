//! The status bar: algorithm, frame time, preview size, triangles, how the preview is drawn
//! (half blocks, kitty, sixel, iTerm2), unsaved marker, file, the
//! latest message or the export's progress, and the keys that matter in the current pane.

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Gauge, Paragraph, Widget};

use super::millis;
use crate::render::DisplayMode;
use crate::tui::state::app::{App, Tone};
use crate::tui::state::mode::Mode;
use crate::tui::state::selection::Focus;
use crate::tui::text::clean;
use crate::tui::view::theme;

/// Two lines at the bottom of the screen.
pub struct StatusBar<'a>(pub &'a App);

/// The keys worth showing for the current mode and pane.
pub fn hints(app: &App) -> &'static str {
    match (&app.mode, app.focus()) {
        (Mode::Edit(_), _) => "type a value · Enter accept · Esc cancel · Ctrl-u clear",
        (Mode::Prompt(..), _) => "type a path · Enter accept · Esc cancel",
        (Mode::Export(_), _) => "↑↓ field · ←→ algorithm · Enter export · Esc cancel",
        (Mode::AddMenu(_), _) => "↑↓ choose · Enter add · i b p l m · Esc cancel",
        (Mode::ConfirmQuit, _) => "y quit without saving · s save and quit · n stay",
        (Mode::Help(_), _) => "↑↓ / j k scroll · any other key closes the help",
        (Mode::Normal, Focus::List) => {
            "↑↓ select · → properties · a add · d dup · x del · 1 2 3 algo · c compare · s save · e export · ? help · q quit"
        }
        (Mode::Normal, Focus::Properties) => {
            "↑↓ property · ←→ step (Shift ×10) · Enter type · u undo · Tab pane · ? help · q quit"
        }
        (Mode::Normal, Focus::Preview) => {
            "←→↑↓ orbit · Shift pan · +/- zoom · r reset · C set camera · 1 2 3 algo · c compare · ? help · q quit"
        }
    }
}

/// `hints` shortened to `width` columns: hints are dropped from the end, but the help and quit
/// keys (`? …`, `q …`) always stay.
pub fn fit_hints(hints: &str, width: usize) -> String {
    const SEPARATOR: &str = " · ";
    let mut items: Vec<&str> = hints.split(SEPARATOR).collect();
    let essential = |item: &str| item.starts_with("? ") || item.starts_with("q ");
    let length = |items: &[&str]| {
        items.iter().map(|i| i.chars().count()).sum::<usize>()
            + SEPARATOR.chars().count() * items.len().saturating_sub(1)
    };
    while length(&items) > width {
        let Some(drop) = items.iter().rposition(|i| !essential(i)) else {
            break;
        };
        items.remove(drop);
    }
    items.join(SEPARATOR)
}

impl Widget for StatusBar<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let app = self.0;
        let [top, bottom] = Layout::vertical([Constraint::Length(1); 2]).areas(area);
        let sep = || Span::styled(" │ ", theme::DIM);
        let compare = app.view.compare();
        let algorithm = if compare {
            "Compare".to_string()
        } else {
            app.view.algorithm().to_string()
        };
        let mut spans = vec![Span::styled(format!(" {algorithm}"), theme::ALGORITHM)];
        if let Some(shot) = &app.previews.shot
            && !compare
        {
            spans.extend([
                sep(),
                Span::raw(millis(app, shot.millis)),
                sep(),
                Span::raw(format!("{}×{} px", shot.image.width, shot.image.height)),
            ]);
        }
        if let Some(t) = app.previews.triangles {
            spans.extend([sep(), Span::raw(format!("{t} tris"))]);
        }
        spans.extend(display_spans(app).into_iter().flat_map(|s| [sep(), s]));
        spans.extend([sep(), Span::raw(app.view.graphics().label())]);
        spans.push(sep());
        if app.doc.is_dirty() {
            spans.push(Span::styled("● modified ", theme::WARNING));
        }
        spans.push(Span::raw(app.title()));
        if let Some(status) = &app.status {
            let style = match status.tone {
                Tone::Info => theme::INFO,
                Tone::Error => theme::ERROR,
            };
            spans.extend([sep(), Span::styled(clean(&status.text), style)]);
        }
        let line = Line::from(spans);
        match &app.export {
            Some(job) => {
                let gauge_width = 34.min(top.width / 2);
                let [text, gauge] =
                    Layout::horizontal([Constraint::Min(0), Constraint::Length(gauge_width)])
                        .areas(top);
                Paragraph::new(line).render(text, buf);
                Gauge::default()
                    .gauge_style(theme::PROGRESS)
                    .ratio(job.progress.fraction().clamp(0.0, 1.0))
                    .label(format!(
                        "export {:.0}% · {} s · Esc",
                        job.progress.fraction() * 100.0,
                        job.started.elapsed().as_secs()
                    ))
                    .render(gauge, buf);
            }
            None => Paragraph::new(line).render(top, buf),
        }
        let shown = fit_hints(hints(app), usize::from(bottom.width).saturating_sub(1));
        Paragraph::new(Line::styled(format!(" {shown}"), theme::DIM)).render(bottom, buf);
    }
}

/// The display mode when it is not `shaded`, the grid's spacing and the bounding box's size
/// when they are drawn, and the objects the `uv` mode cannot show.
fn display_spans(app: &App) -> Vec<Span<'static>> {
    let (mode, overlays) = (app.view.mode(), app.view.overlays());
    let measures = app.previews.measures.unwrap_or_default();
    let mut spans = Vec::new();
    if mode != DisplayMode::Shaded {
        spans.push(Span::styled(mode.name(), theme::ALGORITHM));
    }
    if let (true, Some(spacing)) = (overlays.grid, measures.grid_spacing) {
        spans.push(Span::raw(format!("grid {spacing}")));
    }
    if let (true, Some(size)) = (overlays.bbox, measures.box_size) {
        let [x, y, z] = size.to_array().map(short_number);
        spans.push(Span::raw(format!("box {x}×{y}×{z}")));
    }
    if mode == DisplayMode::Uv && measures.without_uvs > 0 {
        let n = measures.without_uvs;
        let text = format!("{n} object{} without UVs", if n == 1 { "" } else { "s" });
        spans.push(Span::styled(text, theme::WARNING));
    }
    spans
}

/// `value` with four significant digits at most and no trailing zeros: 2, 0.25, 1234, 0.001.
fn short_number(value: f32) -> String {
    let digits = 3 - value.abs().max(1e-9).log10().floor().clamp(-6.0, 3.0) as i32;
    let text = format!("{:.*}", digits.max(0) as usize, value);
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::short_number;

    #[test]
    fn numbers_keep_four_significant_digits_without_trailing_zeros() {
        assert_eq!(short_number(2.0), "2");
        assert_eq!(short_number(0.25), "0.25");
        assert_eq!(short_number(14.000001), "14");
        assert_eq!(short_number(1234.6), "1235");
        assert_eq!(short_number(0.0012346), "0.001235");
    }

    use super::fit_hints;

    #[test]
    fn hints_give_way_from_the_end_but_help_and_quit_stay() {
        let hints = "↑↓ select · a add · d dup · ? help · q quit";
        assert_eq!(fit_hints(hints, 80), hints);
        assert_eq!(fit_hints(hints, 30), "↑↓ select · ? help · q quit");
        assert_eq!(fit_hints(hints, 10), "? help · q quit");
        for width in 15..60 {
            let fitted = fit_hints(hints, width);
            assert!(fitted.chars().count() <= width, "{width}: {fitted}");
            assert!(fitted.ends_with("? help · q quit"), "{width}: {fitted}");
        }
    }
}
