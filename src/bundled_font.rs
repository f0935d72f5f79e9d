//! The one font rastray draws text with (plots, contact sheet titles): DejaVu Sans, bundled in
//! the binary through the `dejavu` crate, so no system font is needed.

use std::sync::Once;

use plotters::style::{FontStyle, register_font};

/// The family name the bundled font is registered under.
pub const FONT: &str = "sans-serif";

/// Registers the bundled font with plotters, once per process.
pub fn register_bundled_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        register_font(FONT, FontStyle::Normal, dejavu::sans::regular())
            .unwrap_or_else(|_| panic!("the bundled DejaVu Sans font is a valid TrueType font"));
    });
}
