//! Keys and mouse events become [`Action`]s, depending on the mode and the focused pane.
//! Nothing else happens here.

use ratatui::crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use ratatui::layout::{Position, Rect};

use super::action::Action;
use super::app::App;
use super::mode::{AddKind, Mode};
use super::selection::Focus;
use crate::render::Algorithm;

/// Degrees per orbit key press.
const ORBIT_STEP: f32 = 5.0;
/// Fraction of the viewing distance per pan key press.
const PAN_STEP: f32 = 0.05;
/// Distance factor per zoom step.
const ZOOM_STEP: f32 = 0.9;

/// The action for a terminal event; `preview` is the preview pane, for the mouse.
pub fn map(app: &App, event: &Event, preview: Rect) -> Option<Action> {
    match event {
        Event::Key(key) if key.kind != KeyEventKind::Release => key_action(app, key),
        Event::Mouse(mouse) => mouse_action(app, mouse, preview),
        _ => None,
    }
}

fn key_action(app: &App, key: &KeyEvent) -> Option<Action> {
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    match &app.mode {
        Mode::Normal => normal_key(app, key, ctrl),
        Mode::Edit(_) | Mode::Prompt(..) | Mode::Export(_) => typing_key(key, ctrl),
        Mode::AddMenu(_) => match key.code {
            KeyCode::Up | KeyCode::Char('k') => Some(Action::Up),
            KeyCode::Down | KeyCode::Char('j') => Some(Action::Down),
            KeyCode::Enter => Some(Action::Submit),
            KeyCode::Esc | KeyCode::Char('q') | KeyCode::Char('a') => Some(Action::Cancel),
            KeyCode::Char(c) => AddKind::ALL
                .into_iter()
                .find(|k| k.hotkey() == c)
                .map(Action::Add),
            _ => None,
        },
        Mode::Help(_) => match key.code {
            KeyCode::Up | KeyCode::Char('k') => Some(Action::Up),
            KeyCode::Down | KeyCode::Char('j') => Some(Action::Down),
            _ => Some(Action::Cancel),
        },
        Mode::ConfirmQuit => match key.code {
            KeyCode::Char('y') | KeyCode::Char('Y') => Some(Action::QuitNow),
            KeyCode::Char('s') | KeyCode::Char('S') => Some(Action::SaveAndQuit),
            KeyCode::Char('n') | KeyCode::Char('N') | KeyCode::Esc => Some(Action::Cancel),
            _ => None,
        },
    }
}

fn typing_key(key: &KeyEvent, ctrl: bool) -> Option<Action> {
    let shift = key.modifiers.contains(KeyModifiers::SHIFT);
    let times = if shift { 10 } else { 1 };
    match key.code {
        KeyCode::Enter => Some(Action::Submit),
        KeyCode::Esc => Some(Action::Cancel),
        KeyCode::Backspace => Some(Action::Backspace),
        KeyCode::Char('u') if ctrl => Some(Action::ClearInput),
        KeyCode::Char('c') if ctrl => Some(Action::Cancel),
        KeyCode::Up => Some(Action::Up),
        KeyCode::Down => Some(Action::Down),
        KeyCode::Tab => Some(Action::FocusNext),
        KeyCode::BackTab => Some(Action::FocusPrev),
        KeyCode::Left => Some(Action::Step(-times)),
        KeyCode::Right => Some(Action::Step(times)),
        KeyCode::Char(c) if !ctrl => Some(Action::Input(c)),
        _ => None,
    }
}

fn normal_key(app: &App, key: &KeyEvent, ctrl: bool) -> Option<Action> {
    let shift = key.modifiers.contains(KeyModifiers::SHIFT);
    if ctrl {
        return match key.code {
            KeyCode::Char('r') => Some(Action::Redo),
            KeyCode::Char('c') => Some(Action::Quit),
            _ => None,
        };
    }
    // Direction keys: hjkl and arrows; Shift (or HJKL) is the big or sideways variant.
    let direction = match key.code {
        KeyCode::Left | KeyCode::Char('h') => Some((-1, 0, shift)),
        KeyCode::Right | KeyCode::Char('l') => Some((1, 0, shift)),
        KeyCode::Up | KeyCode::Char('k') => Some((0, -1, shift)),
        KeyCode::Down | KeyCode::Char('j') => Some((0, 1, shift)),
        KeyCode::Char('H') => Some((-1, 0, true)),
        KeyCode::Char('L') => Some((1, 0, true)),
        KeyCode::Char('K') => Some((0, -1, true)),
        KeyCode::Char('J') => Some((0, 1, true)),
        _ => None,
    };
    if let Some((dx, dy, big)) = direction {
        return Some(match app.focus() {
            Focus::Preview if big => Action::Pan {
                right: -dx as f32 * PAN_STEP,
                up: dy as f32 * PAN_STEP,
            },
            Focus::Preview => Action::Orbit {
                yaw: -dx as f32 * ORBIT_STEP,
                pitch: -dy as f32 * ORBIT_STEP,
            },
            Focus::Properties if dx != 0 => Action::Step(dx * if big { 10 } else { 1 }),
            Focus::List if dx > 0 => Action::Edit,
            _ if dy < 0 => Action::Up,
            _ if dy > 0 => Action::Down,
            _ => return None,
        });
    }
    Some(match key.code {
        KeyCode::Char('q') => Action::Quit,
        KeyCode::Tab => Action::FocusNext,
        KeyCode::BackTab => Action::FocusPrev,
        KeyCode::Enter => Action::Edit,
        KeyCode::Esc => Action::Cancel,
        KeyCode::Char('?') => Action::Help,
        KeyCode::Char('1') => Action::Algorithm(Algorithm::Gouraud),
        KeyCode::Char('2') => Action::Algorithm(Algorithm::Phong),
        KeyCode::Char('3') => Action::Algorithm(Algorithm::Ray),
        KeyCode::Char('c') => Action::ToggleCompare,
        KeyCode::Char('a') => Action::AddMenu,
        KeyCode::Char('d') => Action::Duplicate,
        KeyCode::Char('x') | KeyCode::Delete => Action::Remove,
        KeyCode::Char('u') => Action::Undo,
        KeyCode::Char('s') => Action::Save,
        KeyCode::Char('S') => Action::SaveAs,
        KeyCode::Char('o') => Action::Open,
        KeyCode::Char('e') => Action::Export,
        KeyCode::Char('r') | KeyCode::Home => Action::ResetView,
        KeyCode::Char('C') => Action::SceneCameraFromView,
        KeyCode::Char('[') => Action::Orbit {
            yaw: ORBIT_STEP,
            pitch: 0.0,
        },
        KeyCode::Char(']') => Action::Orbit {
            yaw: -ORBIT_STEP,
            pitch: 0.0,
        },
        KeyCode::Char('{') => Action::Orbit {
            yaw: 0.0,
            pitch: ORBIT_STEP,
        },
        KeyCode::Char('}') => Action::Orbit {
            yaw: 0.0,
            pitch: -ORBIT_STEP,
        },
        KeyCode::Char('+') | KeyCode::Char('=') => Action::Zoom(ZOOM_STEP),
        KeyCode::Char('-') | KeyCode::Char('_') => Action::Zoom(1.0 / ZOOM_STEP),
        _ => return None,
    })
}

fn mouse_action(app: &App, mouse: &MouseEvent, preview: Rect) -> Option<Action> {
    if app.mode != Mode::Normal {
        return None;
    }
    let (column, row) = (mouse.column, mouse.row);
    let inside = preview.contains(Position::new(column, row));
    match mouse.kind {
        MouseEventKind::Down(MouseButton::Left) if inside => {
            Some(Action::DragStart { column, row })
        }
        MouseEventKind::Drag(MouseButton::Left) if app.drag.is_some() => {
            Some(Action::DragTo { column, row })
        }
        MouseEventKind::Up(_) if app.drag.is_some() => Some(Action::DragEnd),
        MouseEventKind::ScrollUp if inside => Some(Action::Zoom(ZOOM_STEP)),
        MouseEventKind::ScrollDown if inside => Some(Action::Zoom(1.0 / ZOOM_STEP)),
        _ => None,
    }
}
