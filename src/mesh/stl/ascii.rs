//! The text of an ASCII STL: one or more `solid … endsolid` blocks of facets,
//!
//! ```text
//! solid name
//!   facet normal nx ny nz
//!     outer loop
//!       vertex x y z      (three or more; a polygon is fanned into triangles)
//!     endloop
//!   endfacet
//! endsolid name
//! ```
//!
//! Keywords are matched in any case; the facet normals are not read. A last `endsolid` that
//! is missing is forgiven (the file ends between facets); a missing `endloop` or `endfacet` is
//! not.

use std::io::BufRead;

use super::error::{StlProblem, coordinate_problem};
use crate::mesh::Place;
use crate::mesh::weld::{Indexed, coordinate_bits};

/// Where the reader is in the grammar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    /// Before a `solid` line (or at the end of the file).
    Outside,
    /// Inside a solid, between facets.
    Solid,
    /// After `facet`, before `outer loop`.
    Facet,
    /// Inside a loop: vertices, then `endloop`.
    Loop,
    /// After `endloop`, before `endfacet`.
    Closed,
}

/// Reads every solid of the text `reader` gives: the corners' coordinate bits (as
/// [`coordinate_bits`] gives them), one a `vertex` line, and the triangles as indices into
/// them, at most `limit` triangles.
pub fn read_solids(
    reader: &mut impl BufRead,
    limit: u64,
) -> Result<Indexed<[u32; 3]>, (Place, StlProblem)> {
    let mut keys = Vec::new();
    let mut triangles = Vec::new();
    let mut state = State::Outside;
    let mut number = 0;
    let mut facet_line = 0;
    let mut corners: Vec<u32> = Vec::with_capacity(3);
    let mut bytes = Vec::new();
    loop {
        bytes.clear();
        let read = reader
            .read_until(b'\n', &mut bytes)
            .map_err(|e| (Place::File, StlProblem::Io(e)))?;
        if read == 0 {
            break;
        }
        number += 1;
        let fail = |problem| (Place::Line(number), problem);
        let line = String::from_utf8_lossy(&bytes);
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let is = |word: &str| keyword.eq_ignore_ascii_case(word);
        let expected = |expected| {
            fail(StlProblem::Expected {
                expected,
                found: shortened(line.trim()),
            })
        };
        state = match state {
            State::Outside if is("solid") => State::Solid,
            State::Outside => return Err(expected("`solid`")),
            State::Solid if is("facet") => {
                facet_line = number;
                corners.clear();
                State::Facet
            }
            State::Solid if is("endsolid") => State::Outside,
            State::Solid => return Err(expected("`facet` or `endsolid`")),
            State::Facet
                if is("outer") && words.next().is_some_and(|w| w.eq_ignore_ascii_case("loop")) =>
            {
                State::Loop
            }
            State::Facet => return Err(expected("`outer loop`")),
            State::Loop if is("vertex") => {
                let mut key = [0u32; 3];
                for bits in &mut key {
                    let value: f32 = words
                        .next()
                        .and_then(|w| w.parse().ok())
                        .ok_or_else(|| fail(StlProblem::BadVertex))?;
                    let triangle = triangles.len() as u64 + 1;
                    if let Some(problem) = coordinate_problem(value, triangle) {
                        return Err(fail(problem));
                    }
                    *bits = coordinate_bits(value);
                }
                if words.next().is_some() {
                    return Err(fail(StlProblem::BadVertex));
                }
                corners.push(keys.len() as u32);
                keys.push(key);
                State::Loop
            }
            State::Loop if is("endloop") => {
                if corners.len() < 3 {
                    return Err(fail(StlProblem::ShortLoop(corners.len())));
                }
                if triangles.len() as u64 + corners.len() as u64 - 2 > limit {
                    return Err(fail(StlProblem::TooManyTriangles { limit }));
                }
                let first = corners[0];
                triangles.extend(corners[1..].windows(2).map(|w| [first, w[0], w[1]]));
                State::Closed
            }
            State::Loop => return Err(expected("`vertex` or `endloop`")),
            State::Closed if is("endfacet") => State::Solid,
            State::Closed => return Err(expected("`endfacet`")),
        };
    }
    let missing = match state {
        State::Outside | State::Solid => return Ok((keys, triangles)),
        State::Facet => "`outer loop`",
        State::Loop => "`endloop`",
        State::Closed => "`endfacet`",
    };
    Err((
        Place::Line(number),
        StlProblem::Unfinished {
            expected: missing,
            facet_line,
        },
    ))
}

/// At most 60 characters of `text`, with `…` when cut.
fn shortened(text: &str) -> String {
    match text.char_indices().nth(60) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_string(),
    }
}
