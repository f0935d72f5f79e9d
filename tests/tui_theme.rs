//! The editor's colours live in `src/tui/theme.rs`: no widget writes a colour or style of its own.

use std::path::{Path, PathBuf};

/// Every `.rs` file below `dir`.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).expect("the folder exists") {
        let path = entry.expect("a readable entry").path();
        if path.is_dir() {
            files.extend(sources(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            files.push(path);
        }
    }
    files
}

#[test]
fn colours_and_styles_are_written_only_in_the_theme() {
    let tui = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/tui");
    let files = sources(&tui);
    assert!(files.len() > 10, "the editor's sources are found");
    // A preview pixel's own colour is data, not a theme choice: its two encodings are allowed.
    let pixel_encodings = ["Color::Rgb(", "Color::Indexed("];
    let mut offenders = Vec::new();
    for file in files.iter().filter(|f| !f.ends_with("theme.rs")) {
        let text = std::fs::read_to_string(file).expect("a readable source file");
        for (n, line) in text.lines().enumerate() {
            let mut rest = line.to_string();
            for allowed in pixel_encodings {
                rest = rest.replace(allowed, "");
            }
            if ["Color::", "Style::", "Modifier::"]
                .iter()
                .any(|literal| rest.contains(literal))
            {
                offenders.push(format!("{}:{}: {}", file.display(), n + 1, line.trim()));
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "colours written outside src/tui/theme.rs:\n{}",
        offenders.join("\n")
    );
}
