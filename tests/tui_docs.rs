//! The key map in `docs/keys.md` is the one the help overlay shows.

#[test]
fn docs_key_map_matches_the_help_overlay() {
    let docs = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/keys.md"))
        .expect("docs/keys.md exists");
    let table = rastray::tui::keys::markdown();
    assert!(
        docs.contains(&table),
        "docs/keys.md is out of date; its table should be:\n{table}"
    );
}
