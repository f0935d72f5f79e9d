//! tmux DCS passthrough: a sequence tmux hands to the terminal outside it unchanged, when its
//! `allow-passthrough` option is on. Every ESC inside is doubled.

/// `bytes` wrapped for tmux to pass through to the outer terminal.
pub fn tmux(bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(bytes.len() + 16);
    out.extend_from_slice(b"\x1bPtmux;");
    for &b in bytes {
        if b == 0x1b {
            out.push(0x1b);
        }
        out.push(b);
    }
    out.extend_from_slice(b"\x1b\\");
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn escapes_are_doubled_inside_one_dcs() {
        assert_eq!(
            super::tmux(b"\x1b_Ga=q\x1b\\"),
            b"\x1bPtmux;\x1b\x1b_Ga=q\x1b\x1b\\\x1b\\".to_vec()
        );
    }
}
