//! The key map, written once: [`crate::tui::input`] looks every key and mouse gesture up in [`KEYS`],
//! and the help overlay, the README and `docs/keys.md` show the same table.

use ratatui::crossterm::event::KeyCode;

use super::action::Action;
use crate::render::OverlayKind;
use crate::tui::state::mode::AddKind;
use Context::*;

/// Where a binding works.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Context {
    /// Browsing, whichever pane has the focus.
    Anywhere,
    /// Browsing with the scene list focused.
    List,
    /// Browsing with the properties focused.
    Properties,
    /// Browsing with the preview focused.
    Preview,
    /// The mouse on the preview, while browsing.
    Mouse,
    /// The help overlay.
    Help,
    /// The add menu.
    AddMenu,
    /// Typing a value or a path, and the export dialog.
    Dialogs,
    /// The question asked before quitting with unsaved edits.
    QuitQuestion,
}

impl Context {
    /// The name shown in the help's first column.
    pub fn label(self) -> &'static str {
        match self {
            Context::Anywhere => "anywhere",
            Context::List => "scene list",
            Context::Properties => "properties",
            Context::Preview => "preview",
            Context::Mouse => "mouse",
            Context::Help => "help",
            Context::AddMenu => "add menu",
            Context::Dialogs => "dialogs",
            Context::QuitQuestion => "quit?",
        }
    }
}

/// The way a key or gesture points, for commands that go somewhere.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    Left,
    Right,
    Up,
    Down,
}

/// What a binding reacts to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trigger {
    /// A key. Shift counts only for keys that are not characters (a character carries its case).
    Key {
        code: KeyCode,
        ctrl: bool,
        shift: bool,
        dir: Option<Dir>,
    },
    /// Any character typed without Ctrl that nothing else takes.
    AnyChar,
    /// Any key that nothing else takes.
    AnyKey,
    /// Dragging with the left button on the preview.
    Drag,
    /// The wheel on the preview (up is [`Dir::Up`]).
    Wheel,
}

/// What a binding does: an action, or one the key completes with its direction or character.
#[derive(Debug, Clone, PartialEq)]
pub enum Does {
    /// This action, whatever the key.
    Act(Action),
    /// Up or down the list, menu, form or help, as the key points.
    Move,
    /// Step the chosen value this many steps, down (left) or up (right).
    Step(i32),
    /// Type the key's character.
    Type,
    /// Preview with the algorithm the digit names (1 Gouraud, 2 Phong, 3 ray tracing).
    ShowAlgorithm,
    /// Turn the view around its target, as the key points.
    Orbit,
    /// Move the view sideways, as the key points.
    Pan,
    /// Move the view closer (up) or away (down).
    Zoom,
}

/// Keys that do one thing.
#[derive(Debug, Clone, PartialEq)]
pub struct Binding {
    pub triggers: &'static [Trigger],
    pub does: Does,
}

/// One line of the key map: the keys of each binding, then what they do.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub context: Context,
    pub bindings: &'static [Binding],
    /// What the bindings do, in their order ("undo / redo").
    pub what: &'static str,
}

/// A key without modifiers; arrows and h j k l (either case) point where they do in vi.
const fn key(code: KeyCode) -> Trigger {
    let dir = match code {
        KeyCode::Left | KeyCode::Char('h' | 'H') => Some(Dir::Left),
        KeyCode::Right | KeyCode::Char('l' | 'L') => Some(Dir::Right),
        KeyCode::Up | KeyCode::Char('k' | 'K') => Some(Dir::Up),
        KeyCode::Down | KeyCode::Char('j' | 'J') => Some(Dir::Down),
        _ => None,
    };
    Trigger::Key {
        code,
        ctrl: false,
        shift: false,
        dir,
    }
}

/// A character key.
const fn ch(c: char) -> Trigger {
    key(KeyCode::Char(c))
}

/// A character key that points `dir`.
const fn toward(c: char, dir: Dir) -> Trigger {
    Trigger::Key {
        code: KeyCode::Char(c),
        ctrl: false,
        shift: false,
        dir: Some(dir),
    }
}

/// Ctrl and a character.
const fn ctrl(c: char) -> Trigger {
    Trigger::Key {
        code: KeyCode::Char(c),
        ctrl: true,
        shift: false,
        dir: None,
    }
}

/// Shift and a key that is not a character.
const fn shift(code: KeyCode) -> Trigger {
    match key(code) {
        Trigger::Key { dir, .. } => Trigger::Key {
            code,
            ctrl: false,
            shift: true,
            dir,
        },
        other => other,
    }
}

const fn does(triggers: &'static [Trigger], does: Does) -> Binding {
    Binding { triggers, does }
}

const fn act(triggers: &'static [Trigger], action: Action) -> Binding {
    does(triggers, Does::Act(action))
}

const UP_DOWN: &[Trigger] = &[key(KeyCode::Up), key(KeyCode::Down)];
const K_J: &[Trigger] = &[ch('k'), ch('j')];
const LEFT_RIGHT: &[Trigger] = &[key(KeyCode::Left), key(KeyCode::Right)];
const ARROWS: &[Trigger] = &[
    key(KeyCode::Left),
    key(KeyCode::Right),
    key(KeyCode::Up),
    key(KeyCode::Down),
];
const HLKJ: &[Trigger] = &[ch('h'), ch('l'), ch('k'), ch('j')];

/// Every key and mouse gesture of the editor. In browsing, the focused pane's rows come before
/// the "anywhere" ones; in other modes only that mode's rows count.
pub const KEYS: &[Row] = &[
    Row {
        context: Anywhere,
        bindings: &[
            act(&[key(KeyCode::Tab)], Action::FocusNext),
            act(&[key(KeyCode::BackTab)], Action::FocusPrev),
        ],
        what: "next / previous pane (scene, properties, preview)",
    },
    Row {
        context: Anywhere,
        bindings: &[does(&[ch('1'), ch('2'), ch('3')], Does::ShowAlgorithm)],
        what: "preview with Gouraud, Phong or ray tracing",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('c')], Action::ToggleCompare)],
        what: "compare the three algorithms side by side",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('m')], Action::CycleMode(1)),
            act(&[ch('M')], Action::CycleMode(-1)),
        ],
        what: "next / previous display mode (shaded, wire, normals…)",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('g')], Action::ToggleOverlay(OverlayKind::Grid)),
            act(&[ch('G')], Action::ToggleOverlay(OverlayKind::Axes)),
        ],
        what: "ground grid / axis gizmo, on or off",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('b')], Action::ToggleOverlay(OverlayKind::Bbox)),
            act(&[ch('O')], Action::ToggleOverlay(OverlayKind::Outline)),
        ],
        what: "bounding box / outline of the selection, on or off",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('a')], Action::AddMenu)],
        what: "add a shape, light or mesh (OBJ, STL, PLY, glTF)",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('d')], Action::Duplicate)],
        what: "duplicate the selected object or light",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('x')], Action::Remove),
            act(&[key(KeyCode::Delete)], Action::Remove),
        ],
        what: "remove the selected object or light",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('u')], Action::Undo),
            act(&[ctrl('r')], Action::Redo),
        ],
        what: "undo / redo",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('s')], Action::Save),
            act(&[ch('S')], Action::SaveAs),
        ],
        what: "save (asks for a path the first time) / save as",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('o')], Action::Open)],
        what: "open another scene file",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('e')], Action::Export),
            act(&[key(KeyCode::Esc)], Action::Cancel),
        ],
        what: "export a PNG (size, algorithm, samples) / cancel it",
    },
    Row {
        context: Anywhere,
        bindings: &[does(
            &[
                toward('[', Dir::Left),
                toward(']', Dir::Right),
                toward('{', Dir::Up),
                toward('}', Dir::Down),
            ],
            Does::Orbit,
        )],
        what: "orbit the view left, right, up, down",
    },
    Row {
        context: Anywhere,
        bindings: &[
            does(&[toward('+', Dir::Up), toward('=', Dir::Up)], Does::Zoom),
            does(
                &[toward('-', Dir::Down), toward('_', Dir::Down)],
                Does::Zoom,
            ),
        ],
        what: "zoom in / out",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('r')], Action::ResetView),
            act(&[key(KeyCode::Home)], Action::ResetView),
        ],
        what: "put the view back at the scene's camera",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('v')], Action::StepPresetView(1)),
            act(&[ch('V')], Action::StepPresetView(-1)),
        ],
        what: "next / previous preset view: front, sides, top, iso…",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('f')], Action::FitAll)],
        what: "fit the whole scene in the view",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('p')], Action::ToggleProjection)],
        what: "perspective / orthographic view, keeping the framing",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('t')], Action::ToggleSpin)],
        what: "turn the view slowly about its target (auto-spin) / stop",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('C')], Action::SceneCameraFromView)],
        what: "make the view the scene's camera (saved, undoable)",
    },
    Row {
        context: Anywhere,
        bindings: &[act(&[ch('?')], Action::Help)],
        what: "this help",
    },
    Row {
        context: Anywhere,
        bindings: &[
            act(&[ch('q')], Action::Quit),
            act(&[ctrl('c')], Action::Quit),
        ],
        what: "quit (asks when there are unsaved edits)",
    },
    Row {
        context: List,
        bindings: &[does(UP_DOWN, Does::Move), does(K_J, Does::Move)],
        what: "select an item",
    },
    Row {
        context: List,
        bindings: &[
            act(&[key(KeyCode::Enter)], Action::Edit),
            act(&[key(KeyCode::Right)], Action::Edit),
            act(&[ch('l')], Action::Edit),
        ],
        what: "go to its properties",
    },
    Row {
        context: Properties,
        bindings: &[does(UP_DOWN, Does::Move), does(K_J, Does::Move)],
        what: "choose a property",
    },
    Row {
        context: Properties,
        bindings: &[
            does(LEFT_RIGHT, Does::Step(1)),
            does(&[ch('h'), ch('l')], Does::Step(1)),
        ],
        what: "step the value down / up (toggle yes/no)",
    },
    Row {
        context: Properties,
        bindings: &[
            does(
                &[shift(KeyCode::Left), shift(KeyCode::Right)],
                Does::Step(10),
            ),
            does(&[ch('H'), ch('L')], Does::Step(10)),
        ],
        what: "step ten times",
    },
    Row {
        context: Properties,
        bindings: &[act(&[key(KeyCode::Enter)], Action::Edit)],
        what: "type an exact value (Enter accepts, Esc cancels)",
    },
    Row {
        context: Preview,
        bindings: &[does(ARROWS, Does::Orbit), does(HLKJ, Does::Orbit)],
        what: "orbit the view (the scene's camera stays)",
    },
    Row {
        context: Preview,
        bindings: &[
            does(
                &[
                    shift(KeyCode::Left),
                    shift(KeyCode::Right),
                    shift(KeyCode::Up),
                    shift(KeyCode::Down),
                ],
                Does::Pan,
            ),
            does(&[ch('H'), ch('L'), ch('K'), ch('J')], Does::Pan),
        ],
        what: "pan the view",
    },
    Row {
        context: Mouse,
        bindings: &[does(&[Trigger::Drag], Does::Orbit)],
        what: "orbit the view",
    },
    Row {
        context: Mouse,
        bindings: &[does(&[Trigger::Wheel], Does::Zoom)],
        what: "zoom",
    },
    Row {
        context: Help,
        bindings: &[does(UP_DOWN, Does::Move), does(K_J, Does::Move)],
        what: "scroll this help",
    },
    Row {
        context: Help,
        bindings: &[act(&[Trigger::AnyKey], Action::Cancel)],
        what: "close this help",
    },
    Row {
        context: AddMenu,
        bindings: &[
            does(UP_DOWN, Does::Move),
            does(K_J, Does::Move),
            act(&[key(KeyCode::Enter)], Action::Submit),
        ],
        what: "choose a kind / add it",
    },
    Row {
        context: AddMenu,
        bindings: &[
            act(&[ch('i')], Action::Add(AddKind::Icosahedron)),
            act(&[ch('b')], Action::Add(AddKind::Box)),
            act(&[ch('p')], Action::Add(AddKind::Prism)),
            act(&[ch('l')], Action::Add(AddKind::Light)),
            act(&[ch('m')], Action::Add(AddKind::Mesh)),
        ],
        what: "add that kind at once",
    },
    Row {
        context: AddMenu,
        bindings: &[
            act(&[key(KeyCode::Esc)], Action::Cancel),
            act(&[ch('q')], Action::Cancel),
            act(&[ch('a')], Action::Cancel),
        ],
        what: "close the menu",
    },
    Row {
        context: Dialogs,
        bindings: &[
            act(&[key(KeyCode::Enter)], Action::Submit),
            act(&[key(KeyCode::Esc), ctrl('c')], Action::Cancel),
        ],
        what: "accept / cancel",
    },
    Row {
        context: Dialogs,
        bindings: &[
            does(UP_DOWN, Does::Move),
            act(&[key(KeyCode::Tab)], Action::FocusNext),
            act(&[key(KeyCode::BackTab)], Action::FocusPrev),
        ],
        what: "move between export fields",
    },
    Row {
        context: Dialogs,
        bindings: &[does(LEFT_RIGHT, Does::Step(1))],
        what: "pick the export's algorithm (or type 1 2 3)",
    },
    Row {
        context: Dialogs,
        bindings: &[
            act(&[ctrl('u')], Action::ClearInput),
            act(&[key(KeyCode::Backspace)], Action::Backspace),
        ],
        what: "clear the line / delete a character",
    },
    Row {
        context: Dialogs,
        bindings: &[does(&[Trigger::AnyChar], Does::Type)],
        what: "type (the first character replaces the shown value)",
    },
    Row {
        context: QuitQuestion,
        bindings: &[
            act(&[ch('y'), ch('Y')], Action::QuitNow),
            act(&[ch('s'), ch('S')], Action::SaveAndQuit),
            act(&[ch('n'), ch('N'), key(KeyCode::Esc)], Action::Cancel),
        ],
        what: "quit without saving / save and quit / stay",
    },
];

impl Trigger {
    /// The modifier written before the key, such as `Ctrl-`.
    fn prefix(&self) -> &'static str {
        match self {
            Trigger::Key { ctrl: true, .. } => "Ctrl-",
            Trigger::Key { shift: true, .. } => "Shift-",
            _ => "",
        }
    }

    /// The key or gesture without its modifier, as the help writes it.
    fn name(&self) -> String {
        let code = match self {
            Trigger::Key { code, .. } => code,
            Trigger::AnyChar => return "any character".into(),
            Trigger::AnyKey => return "any other key".into(),
            Trigger::Drag => return "drag on the preview".into(),
            Trigger::Wheel => return "wheel on the preview".into(),
        };
        let name = match code {
            KeyCode::Char(c) => return c.to_string(),
            KeyCode::Left => "←",
            KeyCode::Right => "→",
            KeyCode::Up => "↑",
            KeyCode::Down => "↓",
            KeyCode::Tab => "Tab",
            KeyCode::BackTab => "Shift-Tab",
            KeyCode::Enter => "Enter",
            KeyCode::Esc => "Esc",
            KeyCode::Backspace => "Backspace",
            KeyCode::Delete => "Delete",
            KeyCode::Home => "Home",
            _ => "?",
        };
        name.into()
    }

    /// Whether the trigger takes `key`, pressed with Ctrl (`ctrl`) and Shift (`shift`).
    pub fn takes(&self, key: KeyCode, ctrl: bool, shift: bool) -> bool {
        match *self {
            Trigger::Key {
                code,
                ctrl: c,
                shift: s,
                ..
            } => {
                // A character carries its case, and Shift-Tab is a key of its own.
                let shift_counts = !matches!(code, KeyCode::Char(_) | KeyCode::BackTab);
                code == key && c == ctrl && (!shift_counts || s == shift)
            }
            Trigger::AnyChar => matches!(key, KeyCode::Char(_)) && !ctrl,
            Trigger::AnyKey => true,
            Trigger::Drag | Trigger::Wheel => false,
        }
    }

    /// Whether the trigger takes keys no other binding takes.
    pub fn is_fallback(&self) -> bool {
        matches!(self, Trigger::AnyChar | Trigger::AnyKey)
    }

    /// Where the key points, for commands that go somewhere.
    pub fn dir(&self) -> Option<Dir> {
        match self {
            Trigger::Key { dir, .. } => *dir,
            _ => None,
        }
    }
}

impl Binding {
    /// The keys as the help writes them: `↑ ↓`, `Ctrl-r`, `Shift-← →` (a modifier shared by all
    /// the keys is written once).
    pub fn label(&self) -> String {
        let first = self.triggers.first().map_or("", Trigger::prefix);
        let shared = self.triggers.len() > 1 && self.triggers.iter().all(|t| t.prefix() == first);
        let names: Vec<String> = self
            .triggers
            .iter()
            .map(|t| {
                if shared {
                    t.name()
                } else {
                    format!("{}{}", t.prefix(), t.name())
                }
            })
            .collect();
        let prefix = if shared { first } else { "" };
        format!("{prefix}{}", names.join(" "))
    }
}

impl Row {
    /// The keys of every binding, as the help writes them: `u / Ctrl-r`.
    pub fn keys(&self) -> String {
        self.bindings
            .iter()
            .map(Binding::label)
            .collect::<Vec<_>>()
            .join(" / ")
    }
}

/// The rows that work in `context`.
pub fn rows_of(context: Context) -> impl Iterator<Item = &'static Row> {
    KEYS.iter().filter(move |r| r.context == context)
}

/// The character that adds `kind` in the add menu.
pub fn add_hotkey(kind: AddKind) -> Option<char> {
    rows_of(AddMenu)
        .flat_map(|r| r.bindings)
        .filter(|b| b.does == Does::Act(Action::Add(kind)))
        .flat_map(|b| b.triggers)
        .find_map(|t| match t {
            Trigger::Key {
                code: KeyCode::Char(c),
                ..
            } => Some(*c),
            _ => None,
        })
}

/// The key map as a Markdown table.
pub fn markdown() -> String {
    let mut s = String::from("| Where | Keys | Action |\n|---|---|---|\n");
    for row in KEYS {
        s.push_str(&format!(
            "| {} | `{}` | {} |\n",
            row.context.label(),
            row.keys(),
            row.what
        ));
    }
    s
}
