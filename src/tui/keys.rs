//! The key map, written once: the help overlay, the status hints and `docs/keys.md` show it.

/// One line of the key map.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KeyHelp {
    /// Where the keys work.
    pub context: &'static str,
    /// The keys, as a user types them.
    pub keys: &'static str,
    /// What they do.
    pub action: &'static str,
}

const fn k(context: &'static str, keys: &'static str, action: &'static str) -> KeyHelp {
    KeyHelp {
        context,
        keys,
        action,
    }
}

/// Every key of the editor.
pub const KEYS: &[KeyHelp] = &[
    k(
        "anywhere",
        "Tab / Shift-Tab",
        "next / previous pane (scene, properties, preview)",
    ),
    k(
        "anywhere",
        "1 2 3",
        "preview with Gouraud, Phong or ray tracing",
    ),
    k("anywhere", "c", "compare the three algorithms side by side"),
    k(
        "anywhere",
        "a",
        "add an icosahedron, box, prism, point light or OBJ mesh",
    ),
    k("anywhere", "d", "duplicate the selected object or light"),
    k(
        "anywhere",
        "x / Delete",
        "remove the selected object or light",
    ),
    k("anywhere", "u / Ctrl-r", "undo / redo"),
    k(
        "anywhere",
        "s / S",
        "save (asks for a path the first time) / save as",
    ),
    k("anywhere", "o", "open another scene file"),
    k(
        "anywhere",
        "e",
        "export a PNG (size, algorithm, samples); Esc cancels it",
    ),
    k(
        "anywhere",
        "[ ] { }",
        "orbit the camera left, right, up, down",
    ),
    k("anywhere", "+ / -", "zoom in / out"),
    k(
        "anywhere",
        "r / Home",
        "reset the view to the scene's camera",
    ),
    k(
        "anywhere",
        "C",
        "set the scene's camera from the view (an undoable edit)",
    ),
    k("anywhere", "?", "this help"),
    k(
        "anywhere",
        "q / Ctrl-c",
        "quit (asks when there are unsaved edits)",
    ),
    k("scene list", "↑ ↓ / k j", "select an item"),
    k("scene list", "Enter / →", "go to its properties"),
    k("properties", "↑ ↓ / k j", "choose a property"),
    k(
        "properties",
        "← → / h l",
        "step the value down / up (toggle yes/no)",
    ),
    k("properties", "Shift-← → / H L", "step ten times"),
    k(
        "properties",
        "Enter",
        "type an exact value (Enter accepts, Esc cancels)",
    ),
    k("preview", "← → ↑ ↓ / h l k j", "orbit the camera"),
    k("preview", "Shift-arrows / H L K J", "pan the camera"),
    k("mouse", "drag on the preview", "orbit the camera"),
    k("mouse", "wheel on the preview", "zoom"),
    k(
        "help",
        "↑ ↓ / k j",
        "scroll this help; any other key closes it",
    ),
    k("dialogs", "Enter / Esc", "accept / cancel"),
    k(
        "dialogs",
        "↑ ↓ / Tab",
        "move between export fields; ← → pick the algorithm",
    ),
    k(
        "dialogs",
        "Ctrl-u / Backspace",
        "clear the line / delete a character",
    ),
];

/// The key map as a Markdown table.
pub fn markdown() -> String {
    let mut s = String::from("| Where | Keys | Action |\n|---|---|---|\n");
    for key in KEYS {
        s.push_str(&format!(
            "| {} | `{}` | {} |\n",
            key.context, key.keys, key.action
        ));
    }
    s
}
