//! What the editor holds: the [`app::App`] and its parts by owner: the [`document::Document`]
//! (the scene, its file and undo history), the [`view_state::ViewState`] (where the preview
//! looks from and how it draws, moved by [`orbit`]), the [`selection::Selection`], the current
//! [`mode::Mode`], and the editable [`fields`] of the selected item. Only
//! [`crate::tui::update`] changes it.

pub mod app;
pub mod document;
pub mod fields;
pub mod mode;
pub mod orbit;
pub mod selection;
pub mod view_state;
