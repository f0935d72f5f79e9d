//! Keys and mouse events become [`Action`]s, as the key table [`keys::KEYS`] says for the current
//! mode and focused pane. Nothing else happens here.

pub mod action;
pub mod keys;

use ratatui::crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};
use ratatui::layout::{Position, Rect};

use crate::render::Algorithm;
use crate::tui::state::app::App;
use crate::tui::state::mode::Mode;
use crate::tui::state::selection::Focus;
use action::Action;
use keys::{Context, Dir, Does, Trigger};

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
        Event::FocusGained => Some(Action::TerminalFocus(true)),
        Event::FocusLost => Some(Action::TerminalFocus(false)),
        _ => None,
    }
}

/// The action for a terminal event while the terminal is too small to show the editor: only
/// quitting and the help (and the answers inside them) work, since nothing else can be seen.
pub fn map_too_small(app: &App, event: &Event) -> Option<Action> {
    let Event::Key(key) = event else {
        return None;
    };
    let action = map(app, event, Rect::default())?;
    let seen = matches!(app.mode, Mode::Help(_) | Mode::ConfirmQuit);
    let allowed = matches!(
        action,
        Action::Quit | Action::QuitNow | Action::SaveAndQuit | Action::Help
    );
    (key.kind != KeyEventKind::Release && (seen || allowed)).then_some(action)
}

/// The parts of the key table that work now, the first taking precedence.
pub fn contexts(mode: &Mode, focus: Focus) -> &'static [Context] {
    match mode {
        Mode::Normal => match focus {
            Focus::List => &[Context::List, Context::Anywhere],
            Focus::Properties => &[Context::Properties, Context::Anywhere],
            Focus::Preview => &[Context::Preview, Context::Anywhere],
        },
        Mode::Edit(_) | Mode::Prompt(..) | Mode::Export(_) => &[Context::Dialogs],
        Mode::AddMenu(_) => &[Context::AddMenu],
        Mode::Help(_) => &[Context::Help],
        Mode::ConfirmQuit => &[Context::QuitQuestion],
    }
}

fn key_action(app: &App, key: &KeyEvent) -> Option<Action> {
    let ctrl = key.modifiers.contains(KeyModifiers::CONTROL);
    let shift = key.modifiers.contains(KeyModifiers::SHIFT);
    let bound = || {
        contexts(&app.mode, app.focus())
            .iter()
            .flat_map(|&c| keys::rows_of(c))
            .flat_map(|row| row.bindings)
            .flat_map(|b| b.triggers.iter().map(move |t| (&b.does, t)))
    };
    // Keys the table names win over its catch-alls ("any character", "any other key").
    let (does, trigger) = bound()
        .find(|(_, t)| !t.is_fallback() && t.takes(key.code, ctrl, shift))
        .or_else(|| bound().find(|(_, t)| t.is_fallback() && t.takes(key.code, ctrl, shift)))?;
    let typed = match key.code {
        KeyCode::Char(c) => Some(c),
        _ => None,
    };
    action(does, trigger.dir(), typed)
}

/// The action `does` asks for, pointing `dir`, with the character `typed` on the key.
fn action(does: &Does, dir: Option<Dir>, typed: Option<char>) -> Option<Action> {
    Some(match does {
        Does::Act(action) => action.clone(),
        Does::Move => match dir? {
            Dir::Up => Action::Up,
            Dir::Down => Action::Down,
            Dir::Left | Dir::Right => return None,
        },
        Does::Step(n) => match dir? {
            Dir::Left => Action::Step(-n),
            Dir::Right => Action::Step(*n),
            Dir::Up | Dir::Down => return None,
        },
        Does::Type => Action::Input(typed?),
        Does::ShowAlgorithm => {
            let digit = typed?.to_digit(10)? as usize;
            Action::Algorithm(*Algorithm::ALL.get(digit.checked_sub(1)?)?)
        }
        Does::Orbit => {
            let (yaw, pitch) = match dir? {
                Dir::Left => (ORBIT_STEP, 0.0),
                Dir::Right => (-ORBIT_STEP, 0.0),
                Dir::Up => (0.0, ORBIT_STEP),
                Dir::Down => (0.0, -ORBIT_STEP),
            };
            Action::Orbit { yaw, pitch }
        }
        Does::Pan => {
            let (right, up) = match dir? {
                Dir::Left => (PAN_STEP, 0.0),
                Dir::Right => (-PAN_STEP, 0.0),
                Dir::Up => (0.0, -PAN_STEP),
                Dir::Down => (0.0, PAN_STEP),
            };
            Action::Pan { right, up }
        }
        Does::Zoom => match dir? {
            Dir::Up => Action::Zoom(ZOOM_STEP),
            Dir::Down => Action::Zoom(1.0 / ZOOM_STEP),
            Dir::Left | Dir::Right => return None,
        },
    })
}

fn mouse_action(app: &App, mouse: &MouseEvent, preview: Rect) -> Option<Action> {
    if app.mode != Mode::Normal {
        return None;
    }
    let (column, row) = (mouse.column, mouse.row);
    let inside = preview.contains(Position::new(column, row));
    let dragging = app.drag.is_some();
    let (trigger, dir) = match mouse.kind {
        MouseEventKind::Down(MouseButton::Left) if inside => (Trigger::Drag, None),
        MouseEventKind::Drag(MouseButton::Left) | MouseEventKind::Up(_) if dragging => {
            (Trigger::Drag, None)
        }
        MouseEventKind::ScrollUp if inside => (Trigger::Wheel, Some(Dir::Up)),
        MouseEventKind::ScrollDown if inside => (Trigger::Wheel, Some(Dir::Down)),
        _ => return None,
    };
    let does = &keys::rows_of(Context::Mouse)
        .flat_map(|r| r.bindings)
        .find(|b| b.triggers.contains(&trigger))?
        .does;
    match (trigger, does) {
        // Dragging orbits in steps as the pointer moves: the gesture's three phases.
        (Trigger::Drag, Does::Orbit) => Some(match mouse.kind {
            MouseEventKind::Down(_) => Action::DragStart { column, row },
            MouseEventKind::Drag(_) => Action::DragTo { column, row },
            _ => Action::DragEnd,
        }),
        (Trigger::Drag, _) => None,
        _ => action(does, dir, None),
    }
}
