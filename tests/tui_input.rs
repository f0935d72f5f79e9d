//! Keys and mouse events become the documented Actions, by mode and pane.

use std::path::PathBuf;

use rastray::render::Algorithm;
use rastray::scene::default_scene;
use rastray::tui::input::action::Action;
use rastray::tui::input::keys::{Context, Does, KEYS, Trigger, add_hotkey};
use rastray::tui::input::{self, map};
use rastray::tui::state::app::App;
use rastray::tui::state::mode::{AddKind, Mode};
use rastray::tui::state::selection::Focus;
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

/// An editor in `context`: the mode and pane where that part of the key table works.
fn app_in(context: Context) -> App {
    let mut a = app(Focus::List);
    let setup: &[Action] = match context {
        Context::Anywhere | Context::List | Context::Mouse => &[],
        Context::Properties => &[Action::FocusNext],
        Context::Preview => &[Action::FocusNext, Action::FocusNext],
        Context::Help => &[Action::Help],
        Context::AddMenu => &[Action::AddMenu],
        Context::Dialogs => &[Action::Export],
        Context::QuitQuestion => &[Action::Add(AddKind::Light), Action::Quit],
    };
    for action in setup {
        apply(&mut a, action.clone());
    }
    assert!(
        input::contexts(a.mode(), a.focus()).contains(&context),
        "{context:?} works in {:?}",
        a.mode()
    );
    a
}

/// The terminal event a key trigger stands for.
fn event_of(trigger: &Trigger) -> Option<Event> {
    let Trigger::Key {
        code, ctrl, shift, ..
    } = *trigger
    else {
        return None;
    };
    let mut modifiers = KeyModifiers::NONE;
    if ctrl {
        modifiers |= KeyModifiers::CONTROL;
    }
    // Terminals report Shift with capitals and with Shift-Tab.
    if shift
        || matches!(code, KeyCode::BackTab)
        || matches!(code, KeyCode::Char(c) if c.is_uppercase())
    {
        modifiers |= KeyModifiers::SHIFT;
    }
    Some(key(code, modifiers))
}

/// Whether `action` is what `does` asks for (directions aside).
fn carries_out(does: &Does, action: &Action) -> bool {
    match (does, action) {
        (Does::Act(wanted), action) => wanted == action,
        (Does::Move, Action::Up | Action::Down)
        | (Does::Orbit, Action::Orbit { .. })
        | (Does::Pan, Action::Pan { .. })
        | (Does::Zoom, Action::Zoom(_))
        | (Does::Type, Action::Input(_))
        | (Does::ShowAlgorithm, Action::Algorithm(_)) => true,
        (Does::Step(n), Action::Step(m)) => m.abs() == *n,
        _ => false,
    }
}

#[test]
fn every_key_in_the_table_does_what_its_row_says() {
    let mut checked = 0;
    for row in KEYS.iter().filter(|r| r.context != Context::Mouse) {
        let a = app_in(row.context);
        for binding in row.bindings {
            for trigger in binding.triggers {
                let Some(event) = event_of(trigger) else {
                    continue;
                };
                let action = map(&a, &event, PREVIEW);
                assert!(
                    action
                        .as_ref()
                        .is_some_and(|act| carries_out(&binding.does, act)),
                    "{} `{}` in {:?}: expected {:?}, got {action:?}",
                    row.context.label(),
                    binding.label(),
                    a.mode(),
                    binding.does
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 80, "{checked} keys checked");
}

#[test]
fn no_key_is_bound_twice_where_both_would_work() {
    let modes = [
        Context::List,
        Context::Properties,
        Context::Preview,
        Context::Help,
        Context::AddMenu,
        Context::Dialogs,
        Context::QuitQuestion,
    ];
    for context in modes {
        let a = app_in(context);
        let mut seen: Vec<(String, &Does)> = Vec::new();
        for &c in input::contexts(a.mode(), a.focus()) {
            for row in KEYS.iter().filter(|r| r.context == c) {
                for binding in row.bindings {
                    for trigger in binding.triggers {
                        let Some(event) = event_of(trigger) else {
                            continue;
                        };
                        let name = format!("{event:?}");
                        if let Some((_, first)) = seen.iter().find(|(n, _)| *n == name) {
                            panic!(
                                "{name} is bound to {first:?} and {:?} in {context:?}",
                                binding.does
                            );
                        }
                        seen.push((name, &binding.does));
                    }
                }
            }
        }
    }
}

#[test]
fn capital_c_makes_the_view_the_scene_camera_in_every_pane() {
    for focus in [Focus::List, Focus::Properties, Focus::Preview] {
        let a = app(focus);
        assert_eq!(
            map(&a, &key(KeyCode::Char('C'), KeyModifiers::SHIFT), PREVIEW),
            Some(Action::SceneCameraFromView),
            "{focus:?}"
        );
        assert_eq!(map(&a, &plain('c'), PREVIEW), Some(Action::ToggleCompare));
    }
}

#[test]
fn the_add_menu_offers_the_table_hotkeys() {
    let a = app_in(Context::AddMenu);
    for kind in AddKind::ALL {
        let hotkey = add_hotkey(kind).expect("every kind has a hotkey");
        assert_eq!(map(&a, &plain(hotkey), PREVIEW), Some(Action::Add(kind)));
    }
}

#[test]
fn catch_alls_take_only_what_nothing_else_takes() {
    let dialog = app_in(Context::Dialogs);
    assert_eq!(map(&dialog, &plain('q'), PREVIEW), Some(Action::Input('q')));
    assert_eq!(
        map(
            &dialog,
            &key(KeyCode::Char('u'), KeyModifiers::CONTROL),
            PREVIEW
        ),
        Some(Action::ClearInput)
    );
    assert_eq!(
        map(
            &dialog,
            &key(KeyCode::Char('x'), KeyModifiers::CONTROL),
            PREVIEW
        ),
        None
    );
    let help = app_in(Context::Help);
    assert_eq!(map(&help, &plain('j'), PREVIEW), Some(Action::Down));
    assert_eq!(map(&help, &plain('q'), PREVIEW), Some(Action::Cancel));
}

#[test]
fn on_the_too_small_screen_only_quit_and_help_act() {
    let mut app = App::new(default_scene(), None, PathBuf::new());
    let before = app.document().generation();
    let mut acted_when_big = 0;
    for c in ('a'..='z')
        .chain('A'..='Z')
        .chain("+-[]<>/ 0123456789".chars())
    {
        let event = plain(c);
        acted_when_big += usize::from(map(&app, &event, PREVIEW).is_some());
        if let Some(action) = input::map_too_small(&app, &event) {
            assert!(
                matches!(action, Action::Quit | Action::Help),
                "{c:?} gave {action:?}"
            );
        }
    }
    for code in [KeyCode::Delete, KeyCode::Tab, KeyCode::Enter, KeyCode::Up] {
        let event = key(code, KeyModifiers::NONE);
        assert_eq!(input::map_too_small(&app, &event), None, "{code:?}");
    }
    assert!(acted_when_big > 5, "the same keys act on a full screen");
    assert_eq!(input::map_too_small(&app, &plain('q')), Some(Action::Quit));
    let help = input::map_too_small(&app, &plain('?')).expect("? opens the help");
    apply(&mut app, help);
    assert!(matches!(app.mode(), Mode::Help(_)));
    assert_eq!(app.document().generation(), before);
}
