//! Drawing the editor: `impl Widget for &App` lays out the panes and overlays. Drawing reads the
//! state and changes nothing.

mod dialogs;
mod help;
mod pen;
mod picture;
mod properties;
mod scene_list;
mod status;
pub mod theme;

pub use picture::{Picture, placements};

use ratatui::buffer::Buffer;
use ratatui::layout::{Constraint, Layout, Rect};
use ratatui::text::Line;
use ratatui::widgets::{Block, BorderType, Paragraph, Widget};

use crate::render::Algorithm;
use crate::tui::state::app::App;
use crate::tui::state::mode::Mode;

/// Smallest terminal that shows the editor, columns × rows.
pub const MIN_SIZE: (u16, u16) = (20, 8);

/// Where each pane goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Areas {
    pub list: Rect,
    pub properties: Rect,
    /// The preview pane, border included.
    pub preview: Rect,
    /// Inside the preview's border: the cells the images fill.
    pub picture: Rect,
    pub status: Rect,
}

/// The panes of a terminal of size `area`, or `None` when it is too small.
pub fn layout(area: Rect, app: &App) -> Option<Areas> {
    if area.width < MIN_SIZE.0 || area.height < MIN_SIZE.1 {
        return None;
    }
    let [main, status] = Layout::vertical([Constraint::Min(3), Constraint::Length(2)]).areas(area);
    let side = (main.width / 3).clamp(10, 34);
    let [side, preview] =
        Layout::horizontal([Constraint::Length(side), Constraint::Min(1)]).areas(main);
    let list_rows = (app.items().len() as u16 + 2).min(side.height / 2).max(3);
    let [list, properties] =
        Layout::vertical([Constraint::Length(list_rows), Constraint::Min(0)]).areas(side);
    let picture = Block::bordered().inner(preview);
    Some(Areas {
        list,
        properties,
        preview,
        picture,
        status,
    })
}

/// The compare view's three panes inside `picture`: a label row and an image area each.
pub fn compare_panes(picture: Rect) -> [(Algorithm, Rect, Rect); 3] {
    let columns: [Rect; 3] = Layout::horizontal([Constraint::Ratio(1, 3); 3]).areas(picture);
    std::array::from_fn(|i| {
        let [label, image] =
            Layout::vertical([Constraint::Length(1), Constraint::Min(0)]).areas(columns[i]);
        (Algorithm::ALL[i], label, image)
    })
}

/// A bordered block titled `title`, highlighted when `focused`.
pub(super) fn pane(title: &str, focused: bool) -> Block<'_> {
    let (border, title_style, border_type) = if focused {
        (theme::ACCENT, theme::ACCENT_TITLE, BorderType::Thick)
    } else {
        (theme::DIM, theme::PLAIN, BorderType::Plain)
    };
    Block::bordered()
        .border_type(border_type)
        .border_style(border)
        .title(Line::styled(format!(" {title} "), title_style))
}

/// Milliseconds as shown next to a frame, or nothing when timings are hidden.
pub(super) fn millis(app: &App, ms: f64) -> String {
    if app.view.show_timings() {
        format!("{ms:.1} ms")
    } else {
        "– ms".into()
    }
}

impl Widget for &App {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let Some(areas) = layout(area, self) else {
            Paragraph::new(vec![
                Line::from("terminal too small"),
                Line::from(format!("need {}×{}", MIN_SIZE.0, MIN_SIZE.1)),
            ])
            .wrap(ratatui::widgets::Wrap { trim: true })
            .render(area, buf);
            return;
        };
        scene_list::SceneList(self).render(areas.list, buf);
        properties::Properties(self).render(areas.properties, buf);
        picture::PreviewPane(self).render(areas.preview, buf);
        status::StatusBar(self).render(areas.status, buf);
        match &self.mode {
            Mode::Help(scroll) => help::HelpOverlay(*scroll).render(area, buf),
            Mode::AddMenu(index) => dialogs::AddMenu(*index).render(area, buf),
            Mode::Prompt(purpose, line) => {
                dialogs::Prompt(*purpose, line, self.doc.is_dirty()).render(area, buf)
            }
            Mode::Export(form) => dialogs::ExportDialog(form).render(area, buf),
            Mode::ConfirmQuit => dialogs::ConfirmQuit.render(area, buf),
            Mode::Normal | Mode::Edit(_) => {}
        }
        if self.view.plain() {
            theme::strip_colors(buf, area, areas.picture);
        }
    }
}
