//! Keys and mouse events become the documented Actions, by mode and pane.

use std::path::PathBuf;

use rastray::render::Algorithm;
use rastray::scene::default_scene;
use rastray::tui::action::Action;
use rastray::tui::app::App;
use rastray::tui::input::map;
use rastray::tui::mode::Mode;
use rastray::tui::selection::Focus;
use rastray::tui::update::apply;
use ratatui::crossterm::event::{
    Event, KeyCode, KeyEvent, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use ratatui::layout::Rect;

const PREVIEW: Rect = Rect::new(40, 0, 80, 38);

fn key(code: KeyCode, modifiers: KeyModifiers) -> Event {
    Event::Key(KeyEvent::new(code, modifiers))
}

fn plain(c: char) -> Event {
    key(KeyCode::Char(c), KeyModifiers::NONE)
}

fn app(focus: Focus) -> App {
    let mut app = App::new(default_scene(), None, PathBuf::from("."));
    while app.focus() != focus {
        apply(&mut app, Action::FocusNext);
    }
    app
}

#[test]
fn global_keys() {
    let a = app(Focus::List);
    let m = |e: Event| map(&a, &e, PREVIEW);
    assert_eq!(m(plain('q')), Some(Action::Quit));
    assert_eq!(m(plain('?')), Some(Action::Help));
    assert_eq!(m(plain('3')), Some(Action::Algorithm(Algorithm::Ray)));
    assert_eq!(m(plain('c')), Some(Action::ToggleCompare));
    assert_eq!(m(plain('u')), Some(Action::Undo));
    assert_eq!(
        m(key(KeyCode::Char('r'), KeyModifiers::CONTROL)),
        Some(Action::Redo)
    );
    assert_eq!(
        m(key(KeyCode::Delete, KeyModifiers::NONE)),
        Some(Action::Remove)
    );
    assert_eq!(
        m(key(KeyCode::Home, KeyModifiers::NONE)),
        Some(Action::ResetView)
    );
    assert_eq!(
        m(key(KeyCode::BackTab, KeyModifiers::SHIFT)),
        Some(Action::FocusPrev)
    );
    assert_eq!(m(plain('j')), Some(Action::Down));
}

#[test]
fn arrows_depend_on_the_pane() {
    let props = app(Focus::Properties);
    assert_eq!(map(&props, &plain('l'), PREVIEW), Some(Action::Step(1)));
    assert_eq!(map(&props, &plain('H'), PREVIEW), Some(Action::Step(-10)));
    assert_eq!(
        map(&props, &key(KeyCode::Right, KeyModifiers::SHIFT), PREVIEW),
        Some(Action::Step(10))
    );
    let preview = app(Focus::Preview);
    assert!(matches!(
        map(&preview, &plain('h'), PREVIEW),
        Some(Action::Orbit { .. })
    ));
    assert!(matches!(
        map(&preview, &key(KeyCode::Up, KeyModifiers::SHIFT), PREVIEW),
        Some(Action::Pan { .. })
    ));
}

#[test]
fn typing_mode_sends_characters() {
    let mut a = app(Focus::Properties);
    apply(&mut a, Action::Edit);
    assert!(matches!(a.mode(), Mode::Edit(_)));
    assert_eq!(map(&a, &plain('q'), PREVIEW), Some(Action::Input('q')));
    assert_eq!(
        map(&a, &key(KeyCode::Esc, KeyModifiers::NONE), PREVIEW),
        Some(Action::Cancel)
    );
}

#[test]
fn mouse_drags_and_wheel_on_the_preview_only() {
    let mut a = app(Focus::List);
    let mouse = |kind, column, row| {
        Event::Mouse(MouseEvent {
            kind,
            column,
            row,
            modifiers: KeyModifiers::NONE,
        })
    };
    assert!(matches!(
        map(&a, &mouse(MouseEventKind::ScrollUp, 50, 10), PREVIEW),
        Some(Action::Zoom(f)) if f < 1.0
    ));
    assert_eq!(
        map(&a, &mouse(MouseEventKind::ScrollUp, 5, 10), PREVIEW),
        None
    );
    assert_eq!(
        map(
            &a,
            &mouse(MouseEventKind::Down(MouseButton::Left), 50, 10),
            PREVIEW
        ),
        Some(Action::DragStart {
            column: 50,
            row: 10
        })
    );
    let before = a.view().camera();
    for action in [
        Action::DragStart {
            column: 50,
            row: 10,
        },
        Action::DragTo {
            column: 60,
            row: 10,
        },
        Action::DragEnd,
    ] {
        apply(&mut a, action);
    }
    assert_ne!(
        a.view().camera().position,
        before.position,
        "dragging orbits"
    );
    assert_eq!(a.view().camera().target, before.target);
    assert_eq!(
        a.document().scene().camera,
        before,
        "the scene's camera stays"
    );
}
