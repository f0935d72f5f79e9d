//! The `--up` values: which axis of a model opened on its own points up.

use rastray::scene::UpAxis;

/// Parses `x`, `y`, `z`, `-x`, `-y` or `-z` (any case) for clap.
pub fn parse_up(s: &str) -> Result<UpAxis, String> {
    UpAxis::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = UpAxis::ALL.iter().map(|a| a.name()).collect();
        format!("`{s}` is not an axis: expected one of {}", names.join(", "))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_parse_with_their_sign() {
        assert_eq!(parse_up("-z"), Ok(UpAxis::NegZ));
        assert_eq!(parse_up("Y"), Ok(UpAxis::Y));
        assert!(parse_up("up").unwrap_err().contains("x, y, z, -x, -y, -z"));
    }
}
