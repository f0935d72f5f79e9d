//! A mistyped command: `rastray veiw` would open the editor on a new scene named `veiw`, and
//! `rastray rendr x.png` would be a parser error about `x.png`. A first argument that is a bare
//! word (no extension, no folder), names no file, and is close to a command is caught before
//! parsing: `did you mean 'view'?`.

use std::path::Path;

/// The command `word` is likely a typo of, among `commands`: the closest within an edit
/// distance of 1 (2 for words of six letters or more), swapped neighbours counting one.
/// `None` for a word that is a command, names a file, or has an extension or a folder.
pub fn suggestion<'a>(word: &str, commands: &[&'a str]) -> Option<&'a str> {
    if word.starts_with('-')
        || word.contains('/')
        || word.contains('.')
        || commands.contains(&word)
        || Path::new(word).exists()
    {
        return None;
    }
    let limit = if word.chars().count() >= 6 { 2 } else { 1 };
    commands
        .iter()
        .map(|c| (distance(&word.to_ascii_lowercase(), c), *c))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

/// The optimal-string-alignment distance: insertions, deletions, substitutions and swaps of
/// neighbours, each 1.
fn distance(a: &str, b: &str) -> usize {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let mut rows = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in rows.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in rows[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (rows[i - 1][j] + 1)
                .min(rows[i][j - 1] + 1)
                .min(rows[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(rows[i - 2][j - 2] + 1);
            }
            rows[i][j] = best;
        }
    }
    rows[a.len()][b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    const COMMANDS: [&str; 5] = ["render", "view", "info", "bench", "join"];

    #[test]
    fn near_misses_are_caught_and_files_are_not() {
        assert_eq!(suggestion("veiw", &COMMANDS), Some("view"));
        assert_eq!(suggestion("rendr", &COMMANDS), Some("render"));
        assert_eq!(suggestion("Render", &COMMANDS), Some("render"));
        assert_eq!(suggestion("rnedre", &COMMANDS), Some("render"));
        assert_eq!(suggestion("render", &COMMANDS), None);
        assert_eq!(suggestion("veiw.toml", &COMMANDS), None);
        assert_eq!(suggestion("teapot", &COMMANDS), None);
        assert_eq!(suggestion("dir/veiw", &COMMANDS), None);
        assert_eq!(suggestion("--vew", &COMMANDS), None);
        assert_eq!(distance("kitten", "sitting"), 3);
    }
}
