//! Text from scene files made safe to show: control characters removed.

/// `s` without control characters (escape sequences in a name cannot reach the terminal).
pub fn clean(s: &str) -> String {
    s.chars().filter(|c| !c.is_control()).collect()
}
