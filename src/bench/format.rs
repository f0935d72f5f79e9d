//! How measured numbers are written, in the report and on the terminal alike.

/// A non-negative measurement (milliseconds, rates) with about three significant digits;
/// values under 0.01 in scientific notation.
pub fn number(value: f64) -> String {
    let decimals = if value >= 100.0 {
        0
    } else if value >= 10.0 {
        1
    } else if value >= 1.0 {
        2
    } else if value >= 0.01 || value == 0.0 {
        3
    } else {
        return format!("{value:.2e}");
    };
    format!("{value:.decimals$}")
}
