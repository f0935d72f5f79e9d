//! Bytes from the terminal turned into key, mouse and paste events, and into the replies the
//! terminal gives to our queries (cursor position, device attributes, capability strings).
//!
//! crossterm's own reader keeps query replies to itself, and its blocking `read` holds the reader
//! while it waits, so the editor could not ask the terminal anything while it runs. The editor
//! needs to: a cursor-position query after each preview frame tells when the terminal has drawn
//! it (see [`super::pacer`]). This decoder reads what the editor's terminals send (xterm-style
//! CSI and SS3 keys with modifiers, SGR and X10 mouse, bracketed paste, focus) and produces
//! crossterm's event types, so the rest of the editor is unchanged.

use ratatui::crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyEventState, KeyModifiers, MouseButton, MouseEvent,
    MouseEventKind,
};

/// A reply from the terminal to a query the editor sent.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Reply {
    /// `CSI row ; column R`, 1-based: the answer to a cursor-position query (`CSI 6n`).
    CursorPosition { row: u16, column: u16 },
    /// `CSI ? p1 ; p2 … c`: primary device attributes (`CSI c`); 4 among them means sixel.
    DeviceAttributes(Vec<u16>),
    /// `CSI 6 ; height ; width t`: the cell size in pixels (`CSI 16t`).
    CellSize { width: u16, height: u16 },
    /// `CSI 4 ; height ; width t`: the text area in pixels (`CSI 14t`).
    WindowSize { width: u16, height: u16 },
    /// `APC G … ST`: a kitty graphics protocol answer, the text between `G` and `ST`.
    Kitty(String),
    /// `DCS … ST`: a capability or setting report (XTGETTCAP, DECRQSS), the text inside.
    Dcs(String),
}

/// What one decoded sequence means.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TermInput {
    /// A key, mouse, paste, focus or resize event, as crossterm describes it.
    Event(Event),
    /// A reply to a query.
    Reply(Reply),
}

/// Longest sequence kept while waiting for its end, bytes: anything longer is garbage and is
/// dropped rather than held forever (a pasted text is not bounded by this; see `paste`).
const MAX_SEQUENCE: usize = 4096;

/// Turns a stream of bytes into [`TermInput`]s. Bytes that end in the middle of a sequence are
/// kept until the next [`Decoder::feed`]; [`Decoder::flush`] reads what is left as typed keys
/// (a lone ESC is the Escape key only when nothing follows it in time).
#[derive(Debug, Default)]
pub struct Decoder {
    pending: Vec<u8>,
    /// Inside a bracketed paste: the text so far.
    paste: Option<Vec<u8>>,
}

/// How one attempt to read a sequence at the start of the buffer ended.
enum Parsed {
    /// A whole sequence of `len` bytes, with what it means (nothing for one that is ignored).
    Done(usize, Option<TermInput>),
    /// The buffer ends before the sequence does.
    Incomplete,
}

impl Decoder {
    /// A decoder with nothing pending.
    pub fn new() -> Decoder {
        Decoder::default()
    }

    /// Whether bytes are waiting for the rest of a sequence.
    pub fn has_pending(&self) -> bool {
        !self.pending.is_empty() || self.paste.is_some()
    }

    /// Decodes `bytes`, appending what they complete to `out`.
    pub fn feed(&mut self, bytes: &[u8], out: &mut Vec<TermInput>) {
        self.pending.extend_from_slice(bytes);
        self.drain(false, out);
    }

    /// Decodes everything pending as if no more bytes were coming: a trailing ESC becomes the
    /// Escape key, a cut-off sequence becomes its bytes typed as keys.
    pub fn flush(&mut self, out: &mut Vec<TermInput>) {
        self.drain(true, out);
        if let Some(text) = self.paste.take() {
            out.push(TermInput::Event(Event::Paste(
                String::from_utf8_lossy(&text).into_owned(),
            )));
        }
    }

    fn drain(&mut self, flush: bool, out: &mut Vec<TermInput>) {
        let mut start = 0;
        while start < self.pending.len() {
            let rest = &self.pending[start..];
            if let Some(text) = &mut self.paste {
                const END: &[u8] = b"\x1b[201~";
                match find(rest, END) {
                    Some(at) => {
                        text.extend_from_slice(&rest[..at]);
                        let text = String::from_utf8_lossy(text).into_owned();
                        out.push(TermInput::Event(Event::Paste(text)));
                        self.paste = None;
                        start += at + END.len();
                    }
                    None => {
                        // Keep a possible start of the end marker for the next read.
                        let keep = (1..END.len().min(rest.len() + 1))
                            .rev()
                            .find(|&n| rest.ends_with(&END[..n]))
                            .unwrap_or(0);
                        text.extend_from_slice(&rest[..rest.len() - keep]);
                        start = self.pending.len() - keep;
                        break;
                    }
                }
                continue;
            }
            match parse(rest, flush) {
                Parsed::Done(len, input) => {
                    if input == Some(TermInput::Event(Event::Paste(String::new()))) {
                        self.paste = Some(Vec::new());
                    } else if let Some(input) = input {
                        out.push(input);
                    }
                    start += len;
                }
                Parsed::Incomplete if rest.len() > MAX_SEQUENCE => start += 1,
                Parsed::Incomplete => break,
            }
        }
        self.pending.drain(..start);
    }
}

fn find(haystack: &[u8], needle: &[u8]) -> Option<usize> {
    haystack.windows(needle.len()).position(|w| w == needle)
}

fn key(code: KeyCode, modifiers: KeyModifiers) -> Option<TermInput> {
    Some(TermInput::Event(Event::Key(KeyEvent {
        code,
        modifiers,
        kind: KeyEventKind::Press,
        state: KeyEventState::NONE,
    })))
}

/// Reads one sequence at the start of `b` (not empty). With `flush`, nothing more is coming.
fn parse(b: &[u8], flush: bool) -> Parsed {
    match b[0] {
        0x1b => parse_escape(b, flush),
        _ => parse_plain(b, KeyModifiers::NONE, flush),
    }
}

/// A byte or UTF-8 character that is not the start of an escape sequence.
fn parse_plain(b: &[u8], extra: KeyModifiers, flush: bool) -> Parsed {
    let none = KeyModifiers::NONE;
    let (len, code, modifiers) = match b[0] {
        b'\r' | b'\n' => (1, KeyCode::Enter, none),
        b'\t' => (1, KeyCode::Tab, none),
        0x7f | 0x08 => (1, KeyCode::Backspace, none),
        0 => (1, KeyCode::Char(' '), KeyModifiers::CONTROL),
        c @ 0x01..=0x1a => (
            1,
            KeyCode::Char((c - 1 + b'a') as char),
            KeyModifiers::CONTROL,
        ),
        c @ 0x1c..=0x1f => (
            1,
            KeyCode::Char((c - 0x1c + b'4') as char),
            KeyModifiers::CONTROL,
        ),
        c if c < 0x80 => {
            let ch = c as char;
            let shift = if ch.is_ascii_uppercase() {
                KeyModifiers::SHIFT
            } else {
                none
            };
            (1, KeyCode::Char(ch), shift)
        }
        c => {
            let len = match c {
                0xc0..=0xdf => 2,
                0xe0..=0xef => 3,
                0xf0..=0xf7 => 4,
                _ => return Parsed::Done(1, None),
            };
            if b.len() < len {
                return if flush {
                    Parsed::Done(b.len(), None)
                } else {
                    Parsed::Incomplete
                };
            }
            match std::str::from_utf8(&b[..len])
                .ok()
                .and_then(|s| s.chars().next())
            {
                Some(ch) => (len, KeyCode::Char(ch), none),
                None => return Parsed::Done(1, None),
            }
        }
    };
    Parsed::Done(len, key(code, modifiers | extra))
}

/// A sequence starting with ESC.
fn parse_escape(b: &[u8], flush: bool) -> Parsed {
    let Some(&second) = b.get(1) else {
        return if flush {
            Parsed::Done(1, key(KeyCode::Esc, KeyModifiers::NONE))
        } else {
            Parsed::Incomplete
        };
    };
    match second {
        b'[' => parse_csi(b, flush),
        b'O' => match b.get(2) {
            None if flush => Parsed::Done(2, key(KeyCode::Char('O'), KeyModifiers::ALT)),
            None => Parsed::Incomplete,
            Some(&c) => Parsed::Done(3, ss3_key(c).and_then(|k| key(k, KeyModifiers::NONE))),
        },
        b'P' | b'_' => parse_string(b, flush),
        0x1b => Parsed::Done(1, key(KeyCode::Esc, KeyModifiers::NONE)),
        _ => match parse_plain(&b[1..], KeyModifiers::ALT, flush) {
            Parsed::Done(len, input) => Parsed::Done(len + 1, input),
            Parsed::Incomplete => Parsed::Incomplete,
        },
    }
}

/// The key an SS3 final byte stands for (`ESC O A` is the Up arrow in application mode).
fn ss3_key(c: u8) -> Option<KeyCode> {
    Some(match c {
        b'A' => KeyCode::Up,
        b'B' => KeyCode::Down,
        b'C' => KeyCode::Right,
        b'D' => KeyCode::Left,
        b'H' => KeyCode::Home,
        b'F' => KeyCode::End,
        b'M' => KeyCode::Enter,
        b'P'..=b'S' => KeyCode::F(c - b'P' + 1),
        _ => return None,
    })
}

/// `ESC P … ST` (DCS) or `ESC _ … ST` (APC), ended by `ESC \` or BEL.
fn parse_string(b: &[u8], flush: bool) -> Parsed {
    let body = &b[2..];
    let end = body.iter().enumerate().find_map(|(i, &c)| match c {
        0x07 => Some((i, 1)),
        0x1b if body.get(i + 1) == Some(&b'\\') => Some((i, 2)),
        _ => None,
    });
    let Some((at, terminator)) = end else {
        return if flush {
            Parsed::Done(b.len(), None)
        } else {
            Parsed::Incomplete
        };
    };
    let text = String::from_utf8_lossy(&body[..at]).into_owned();
    let reply = match b[1] {
        b'_' => text.strip_prefix('G').map(|t| Reply::Kitty(t.to_string())),
        _ => Some(Reply::Dcs(text)),
    };
    Parsed::Done(2 + at + terminator, reply.map(TermInput::Reply))
}

/// `ESC [ params final`.
fn parse_csi(b: &[u8], flush: bool) -> Parsed {
    // X10 mouse: ESC [ M and three bytes.
    if b.get(2) == Some(&b'M') {
        return match b.get(3..6) {
            Some(&[cb, cx, cy]) => Parsed::Done(
                6,
                mouse(
                    u16::from(cb.wrapping_sub(32)),
                    u16::from(cx.saturating_sub(32)),
                    u16::from(cy.saturating_sub(32)),
                    false,
                )
                .map(TermInput::Event),
            ),
            _ if flush => Parsed::Done(b.len(), None),
            _ => Parsed::Incomplete,
        };
    }
    let Some(end) = b[2..].iter().position(|c| (0x40..=0x7e).contains(c)) else {
        return if flush {
            Parsed::Done(b.len(), None)
        } else {
            Parsed::Incomplete
        };
    };
    let len = 2 + end + 1;
    let final_byte = b[len - 1];
    let params = &b[2..len - 1];
    let (private, params) = match params.first() {
        Some(&p @ (b'?' | b'<' | b'>' | b'=')) => (Some(p), &params[1..]),
        _ => (None, params),
    };
    let numbers: Vec<u16> = std::str::from_utf8(params)
        .unwrap_or("")
        .split([';', ':'])
        .map(|n| n.parse().unwrap_or(0))
        .collect();
    let n = |i: usize| numbers.get(i).copied().unwrap_or(0);
    let input = match (private, final_byte) {
        (Some(b'<'), b'M' | b'm') => {
            mouse(n(0), n(1), n(2), final_byte == b'm').map(TermInput::Event)
        }
        (Some(b'?'), b'c') => Some(TermInput::Reply(Reply::DeviceAttributes(numbers))),
        (None, b'R') if numbers.len() == 2 => Some(TermInput::Reply(Reply::CursorPosition {
            row: n(0),
            column: n(1),
        })),
        (None, b't') if n(0) == 6 => Some(TermInput::Reply(Reply::CellSize {
            height: n(1),
            width: n(2),
        })),
        (None, b't') if n(0) == 4 => Some(TermInput::Reply(Reply::WindowSize {
            height: n(1),
            width: n(2),
        })),
        (None, b'I') => Some(TermInput::Event(Event::FocusGained)),
        (None, b'O') => Some(TermInput::Event(Event::FocusLost)),
        (None, b'~') if n(0) == 200 => Some(TermInput::Event(Event::Paste(String::new()))),
        (None, _) => {
            csi_key(final_byte, &numbers).and_then(|(code, modifiers)| key(code, modifiers))
        }
        _ => None,
    };
    Parsed::Done(len, input)
}

/// The modifiers xterm encodes as `1 + bits` in a key sequence's second parameter.
fn modifiers(param: u16) -> KeyModifiers {
    let bits = param.saturating_sub(1);
    let mut m = KeyModifiers::NONE;
    if bits & 1 != 0 {
        m |= KeyModifiers::SHIFT;
    }
    if bits & 2 != 0 {
        m |= KeyModifiers::ALT;
    }
    if bits & 4 != 0 {
        m |= KeyModifiers::CONTROL;
    }
    m
}

/// A key from a CSI sequence: `CSI 1 ; mods A` (arrows and friends) or `CSI n ; mods ~`.
fn csi_key(final_byte: u8, numbers: &[u16]) -> Option<(KeyCode, KeyModifiers)> {
    let mods = modifiers(numbers.get(1).copied().unwrap_or(1));
    let code = match final_byte {
        b'A'..=b'D' | b'H' | b'F' | b'P'..=b'S' => ss3_key(final_byte)?,
        b'Z' => return Some((KeyCode::BackTab, KeyModifiers::SHIFT)),
        b'~' => match numbers.first().copied().unwrap_or(0) {
            1 | 7 => KeyCode::Home,
            2 => KeyCode::Insert,
            3 => KeyCode::Delete,
            4 | 8 => KeyCode::End,
            5 => KeyCode::PageUp,
            6 => KeyCode::PageDown,
            n @ 11..=15 => KeyCode::F((n - 10) as u8),
            n @ 17..=21 => KeyCode::F((n - 11) as u8),
            n @ 23..=24 => KeyCode::F((n - 12) as u8),
            _ => return None,
        },
        _ => return None,
    };
    Some((code, mods))
}

/// A mouse report: button code `cb` as xterm encodes it, 1-based cell `x`, `y`.
fn mouse(cb: u16, x: u16, y: u16, release: bool) -> Option<Event> {
    let mut modifiers = KeyModifiers::NONE;
    if cb & 4 != 0 {
        modifiers |= KeyModifiers::SHIFT;
    }
    if cb & 8 != 0 {
        modifiers |= KeyModifiers::ALT;
    }
    if cb & 16 != 0 {
        modifiers |= KeyModifiers::CONTROL;
    }
    let button = match cb & 3 {
        0 => MouseButton::Left,
        1 => MouseButton::Middle,
        2 => MouseButton::Right,
        _ => MouseButton::Left,
    };
    let kind = if cb & 64 != 0 {
        match cb & 3 {
            0 => MouseEventKind::ScrollUp,
            1 => MouseEventKind::ScrollDown,
            2 => MouseEventKind::ScrollLeft,
            _ => MouseEventKind::ScrollRight,
        }
    } else if cb & 32 != 0 {
        if cb & 3 == 3 {
            MouseEventKind::Moved
        } else {
            MouseEventKind::Drag(button)
        }
    } else if release || cb & 3 == 3 {
        MouseEventKind::Up(button)
    } else {
        MouseEventKind::Down(button)
    };
    Some(Event::Mouse(MouseEvent {
        kind,
        column: x.checked_sub(1)?,
        row: y.checked_sub(1)?,
        modifiers,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn decode(bytes: &[u8]) -> Vec<TermInput> {
        let mut decoder = Decoder::new();
        let mut out = Vec::new();
        decoder.feed(bytes, &mut out);
        decoder.flush(&mut out);
        out
    }

    fn keys(bytes: &[u8]) -> Vec<(KeyCode, KeyModifiers)> {
        decode(bytes)
            .into_iter()
            .map(|i| match i {
                TermInput::Event(Event::Key(k)) => (k.code, k.modifiers),
                other => panic!("not a key: {other:?}"),
            })
            .collect()
    }

    const NONE: KeyModifiers = KeyModifiers::NONE;

    #[test]
    fn printable_and_control_keys() {
        assert_eq!(
            keys(b"a]Q\r\t\x7f\x03"),
            vec![
                (KeyCode::Char('a'), NONE),
                (KeyCode::Char(']'), NONE),
                (KeyCode::Char('Q'), KeyModifiers::SHIFT),
                (KeyCode::Enter, NONE),
                (KeyCode::Tab, NONE),
                (KeyCode::Backspace, NONE),
                (KeyCode::Char('c'), KeyModifiers::CONTROL),
            ]
        );
        assert_eq!(
            keys("é→".as_bytes()),
            vec![(KeyCode::Char('é'), NONE), (KeyCode::Char('→'), NONE)]
        );
    }

    #[test]
    fn arrows_with_and_without_modifiers() {
        assert_eq!(
            keys(b"\x1b[A\x1bOB\x1b[1;2C\x1b[1;5D\x1b[Z\x1b[3~\x1b[5;3~"),
            vec![
                (KeyCode::Up, NONE),
                (KeyCode::Down, NONE),
                (KeyCode::Right, KeyModifiers::SHIFT),
                (KeyCode::Left, KeyModifiers::CONTROL),
                (KeyCode::BackTab, KeyModifiers::SHIFT),
                (KeyCode::Delete, NONE),
                (KeyCode::PageUp, KeyModifiers::ALT),
            ]
        );
    }

    #[test]
    fn escape_alone_only_when_nothing_follows() {
        let mut decoder = Decoder::new();
        let mut out = Vec::new();
        decoder.feed(b"\x1b", &mut out);
        assert!(
            out.is_empty() && decoder.has_pending(),
            "ESC may start a sequence"
        );
        decoder.feed(b"[B", &mut out);
        assert_eq!(out.len(), 1, "{out:?}");
        assert!(!decoder.has_pending());
        decoder.feed(b"\x1b", &mut out);
        decoder.flush(&mut out);
        assert_eq!(out[1], key(KeyCode::Esc, NONE).unwrap());
        assert_eq!(
            keys(b"\x1bx"),
            vec![(KeyCode::Char('x'), KeyModifiers::ALT)]
        );
    }

    #[test]
    fn sequences_split_across_reads_are_joined() {
        let whole = b"\x1b[1;2A\x1b[6;20;10t\x1b[<0;5;7M";
        for cut in 1..whole.len() {
            let mut decoder = Decoder::new();
            let mut out = Vec::new();
            decoder.feed(&whole[..cut], &mut out);
            decoder.feed(&whole[cut..], &mut out);
            assert_eq!(out, decode(whole), "cut at {cut}");
            assert_eq!(out.len(), 3);
        }
    }

    #[test]
    fn replies_are_told_apart_from_keys() {
        assert_eq!(
            decode(b"\x1b[12;40R\x1b[?62;4;22c\x1b[6;20;10t\x1b_Gi=31;OK\x1b\\\x1bP1+r5463\x1b\\"),
            vec![
                TermInput::Reply(Reply::CursorPosition {
                    row: 12,
                    column: 40
                }),
                TermInput::Reply(Reply::DeviceAttributes(vec![62, 4, 22])),
                TermInput::Reply(Reply::CellSize {
                    width: 10,
                    height: 20
                }),
                TermInput::Reply(Reply::Kitty("i=31;OK".into())),
                TermInput::Reply(Reply::Dcs("1+r5463".into())),
            ]
        );
        // A bare `CSI R` is F3 in the old xterm encoding.
        assert_eq!(keys(b"\x1b[R"), vec![(KeyCode::F(3), NONE)]);
    }

    #[test]
    fn sgr_mouse_press_drag_release_and_wheel() {
        let kinds: Vec<(MouseEventKind, u16, u16)> =
            decode(b"\x1b[<0;10;5M\x1b[<32;11;5M\x1b[<0;11;5m\x1b[<64;3;3M")
                .into_iter()
                .map(|i| match i {
                    TermInput::Event(Event::Mouse(m)) => (m.kind, m.column, m.row),
                    other => panic!("not a mouse event: {other:?}"),
                })
                .collect();
        assert_eq!(
            kinds,
            vec![
                (MouseEventKind::Down(MouseButton::Left), 9, 4),
                (MouseEventKind::Drag(MouseButton::Left), 10, 4),
                (MouseEventKind::Up(MouseButton::Left), 10, 4),
                (MouseEventKind::ScrollUp, 2, 2),
            ]
        );
    }

    #[test]
    fn bracketed_paste_is_one_event_even_when_split() {
        let mut decoder = Decoder::new();
        let mut out = Vec::new();
        decoder.feed(b"\x1b[200~scenes/a", &mut out);
        decoder.feed(b".toml\x1b[20", &mut out);
        assert!(out.is_empty());
        decoder.feed(b"1~q", &mut out);
        assert_eq!(
            out,
            vec![
                TermInput::Event(Event::Paste("scenes/a.toml".into())),
                key(KeyCode::Char('q'), NONE).unwrap(),
            ]
        );
    }

    #[test]
    fn garbage_never_stalls_the_stream() {
        let mut bytes = b"\x1b[".to_vec();
        bytes.extend(std::iter::repeat_n(b'1', MAX_SEQUENCE + 10));
        let mut decoder = Decoder::new();
        let mut out = Vec::new();
        decoder.feed(&bytes, &mut out);
        decoder.feed(b"q", &mut out);
        decoder.flush(&mut out);
        assert_eq!(out.last(), key(KeyCode::Char('q'), NONE).as_ref());
        assert!(!decoder.has_pending());
    }
}
