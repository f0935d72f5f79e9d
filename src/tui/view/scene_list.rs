//! The scene list: camera and settings, lights, objects.

use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::text::{Line, Span};
use ratatui::widgets::{List, ListItem, ListState, StatefulWidget, Widget};

use super::pane;
use crate::tui::state::app::App;
use crate::tui::state::selection::{Focus, Item};
use crate::tui::text::clean;
use crate::tui::view::theme;

/// The list of items, the selected one highlighted.
pub struct SceneList<'a>(pub &'a App);

impl Widget for SceneList<'_> {
    fn render(self, area: Rect, buf: &mut Buffer) {
        let app = self.0;
        let focused = app.focus() == Focus::List;
        let scene = app.doc.scene();
        let items: Vec<ListItem> = app
            .items()
            .into_iter()
            .map(|item| {
                let (tag, name, tag_style) = match item {
                    Item::Settings => ("cam", "camera & scene".to_string(), theme::TAG_SETTINGS),
                    Item::Light(i) => {
                        let l = &scene.lights[i];
                        let name = l.name.clone().unwrap_or_else(|| format!("light {}", i + 1));
                        ("lit", name, theme::TAG_LIGHT)
                    }
                    Item::Object(i) => {
                        let o = &scene.objects[i];
                        let tag = match o.shape.kind() {
                            crate::scene::ShapeKind::Icosahedron => "ico",
                            crate::scene::ShapeKind::Box => "box",
                            crate::scene::ShapeKind::Prism => "prm",
                            crate::scene::ShapeKind::Mesh => "obj",
                        };
                        (tag, o.label().to_string(), theme::TAG_OBJECT)
                    }
                };
                ListItem::new(Line::from(vec![
                    Span::styled(format!("{tag} "), tag_style),
                    Span::raw(clean(&name)),
                ]))
            })
            .collect();
        let highlight = if focused {
            theme::SELECTED
        } else {
            theme::SELECTED_UNFOCUSED
        };
        let list = List::new(items)
            .block(pane("Scene", focused))
            .highlight_style(highlight)
            .highlight_symbol("▶");
        let mut state = ListState::default().with_selected(Some(app.selection.item()));
        StatefulWidget::render(list, area, buf, &mut state);
    }
}
