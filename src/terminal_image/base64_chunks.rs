//! Base64 payloads split into pieces for escape sequences with a length limit.

use base64::Engine;
use base64::engine::general_purpose::STANDARD;

/// `bytes` in standard base64 (with padding).
pub fn encode(bytes: &[u8]) -> String {
    STANDARD.encode(bytes)
}

/// `bytes` in base64, cut into pieces of at most `size` characters (the last may be shorter).
pub fn chunks(bytes: &[u8], size: usize) -> Vec<String> {
    let text = encode(bytes);
    text.as_bytes()
        .chunks(size.max(1))
        .map(|c| String::from_utf8_lossy(c).into_owned())
        .collect()
}
