//! Text that came from a file, made safe to print on a terminal: every control character is
//! written as an escape, in the style of Rust's `escape_debug` (`\u{1b}`, `\u{7}`, `\n`), so a
//! name or path cannot retitle the window, move the cursor or write the clipboard.
//!
//! The command line prints names, paths and error messages through [`escape_controls`]; the
//! editor drops control characters instead (`tui::text`).

use std::borrow::Cow;
use std::fmt;

/// `text` with each control character (C0, DEL and C1) escaped as `escape_debug` writes it;
/// everything else, quotes and backslashes included, unchanged. Borrows when nothing changes.
pub fn escape_controls(text: &str) -> Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// Displays its text through [`escape_controls`]: `format!("{}", Escaped(name))`.
pub struct Escaped<'a>(pub &'a str);

impl fmt::Display for Escaped<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.pad(&escape_controls(self.0))
    }
}

#[cfg(test)]
mod tests {
    use super::escape_controls;

    #[test]
    fn controls_are_escaped_and_the_rest_is_kept() {
        assert_eq!(
            escape_controls("\u{1b}]0;pwned\u{7}"),
            "\\u{1b}]0;pwned\\u{7}"
        );
        assert_eq!(escape_controls("a\r\nb\tc\0"), "a\\r\\nb\\tc\\0");
        assert_eq!(escape_controls("\u{7f}\u{9b}31m"), "\\u{7f}\\u{9b}31m");
        assert_eq!(
            escape_controls("plain \"name\" \\ été ✓"),
            "plain \"name\" \\ été ✓"
        );
        assert!(matches!(
            escape_controls("no controls"),
            std::borrow::Cow::Borrowed(_)
        ));
    }

    #[test]
    fn padding_applies_to_the_escaped_text() {
        assert_eq!(format!("{:<8}|", super::Escaped("a\u{7}")), "a\\u{7}  |");
    }
}
