//! The key map in `docs/keys.md` and in the README is the one the help overlay shows.

#[test]
fn docs_key_map_matches_the_help_overlay() {
    let table = rastray::tui::input::keys::markdown();
    for file in ["docs/keys.md", "README.md"] {
        let path = format!("{}/{file}", env!("CARGO_MANIFEST_DIR"));
        let docs = std::fs::read_to_string(&path).expect("the file exists");
        assert!(
            docs.contains(&table),
            "the key map in {file} is out of date; it should be:\n{table}"
        );
    }
}
