//! One piece of an OBJ file (whole lines) read on its own, so that the pieces of a file can be
//! read on several cores and joined in order ([`super::obj`] joins them). What a statement
//! means can depend on what came before it: a negative index counts back from the vertices
//! read so far, and a texture coordinate or normal index must name one read so far. A piece
//! is therefore read knowing how many of each statement the pieces before it hold
//! ([`Counts`], from [`count_statements`], a quick pass over the lines), and gives indices
//! and line numbers for the whole file. Materials are named, not numbered, since their
//! numbers depend on the names met before.
//!
//! Lines are read as bytes. In an ASCII piece (nearly every file) a plain statement (`v`, `vn`,
//! `vt` or `f` of plain numbers) is read in place, straight from the piece's text up to its
//! `\n`, the text never cut into lines; any other line is cut out and split into words without
//! decoding it. A piece with other bytes is read line by line, a line that is not ASCII decoded
//! as UTF-8 (invalid bytes replaced), as every line once was, so a comment in another encoding
//! is no obstacle and a number in one is no number.

use glam::{Vec2, Vec3};

use super::normals::unit_or_zero;
use super::obj_error::ObjProblem;
use super::obj_number::{decimal_at, index_at, parse_f32, parse_index};
use super::piece_room::Room;
use super::srgb::srgb_to_linear;
use crate::scene::limits::COORDINATE;

/// How many lines and statements of each kind came before a piece, or lie in one.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Counts {
    pub lines: usize,
    pub positions: usize,
    pub uvs: usize,
    pub normals: usize,
    /// Triangles: known before a piece only when it is read again to find where the file
    /// passed the triangle limit (0 otherwise: each piece then checks only its own).
    pub triangles: usize,
    /// `f` statements: what a piece reserves room for (a face is one triangle or more).
    pub faces: usize,
}

impl Counts {
    /// These counts followed by `more`'s (a piece's lines and statements after these).
    pub fn then(self, more: Counts) -> Counts {
        Counts {
            lines: self.lines + more.lines,
            positions: self.positions + more.positions,
            uvs: self.uvs + more.uvs,
            normals: self.normals + more.normals,
            triangles: self.triangles + more.triangles,
            faces: self.faces + more.faces,
        }
    }
}

/// What one piece of the file holds, with indices and lines for the whole file. Its positions
/// and triangles are written into its rooms in the file's arrays.
#[derive(Debug, Default)]
pub struct Piece<'a> {
    pub positions: Room<'a, Vec3>,
    /// Unit normals (zero for a zero normal), as `vn` statements give them.
    pub normals: Vec<Vec3>,
    /// The linear colour of each vertex, while every vertex of the piece so far has one.
    pub colors: Vec<Vec3>,
    /// Whether some vertex of the piece has no colour.
    pub vertex_without_color: bool,
    pub triangles: Room<'a, [u32; 3]>,
    /// The normal index of each triangle corner, while every corner so far has one.
    pub normal_corners: Vec<[u32; 3]>,
    /// Whether some face corner of the piece has no normal.
    pub corner_without_normal: bool,
    /// Texture coordinates (u, v) as `vt` statements give them (OBJ's origin: bottom-left).
    pub uvs: Vec<Vec2>,
    /// The texture coordinate index of each triangle corner, while every corner so far has one.
    pub uv_corners: Vec<[u32; 3]>,
    /// Whether some face corner of the piece has no texture coordinate.
    pub corner_without_uv: bool,
    /// Each `usemtl`: the piece's triangles before it, and the name (empty: none).
    pub material_uses: Vec<(usize, String)>,
    /// Each `mtllib`: its line in the file and the rest of the line.
    pub libraries: Vec<(usize, String)>,
    /// Whether a face named a vertex before the first (index 0, or negative too far back).
    pub missing_vertex: bool,
}

/// An index that names nothing.
pub const NONE: u32 = u32::MAX;

/// One corner of a face: vertex, texture coordinate and normal indices, from 0.
#[derive(Debug, Clone, Copy)]
struct Corner {
    vertex: u32,
    uv: Option<u32>,
    normal: Option<u32>,
}

/// What a malformed face corner should have been.
const CORNER_FORMS: &str = "a face corner is `v`, `v/vt`, `v//vn` or `v/vt/vn`";

/// What a face that goes on after a `\` at the end of its line gets: a line continued with a
/// backslash, as the OBJ specification allows and exporters almost never write, is not read
/// (neither tobj nor rapidobj reads it either).
const CONTINUED_LINE: &str =
    "a face continues on the next line after `\\`, which rastray does not read: join the lines";

/// Whether `b` is white space as `char::is_whitespace` has it among ASCII characters.
#[inline]
fn is_space(b: u8) -> bool {
    b == b' ' || (b'\t'..=b'\r').contains(&b)
}

/// Whether `b` is white space within a line: [`is_space`] but for `\n`, which ends the line.
#[inline]
fn is_line_space(b: u8) -> bool {
    is_space(b) && b != b'\n'
}

/// The lines of `text`, each without its `\n` (a last line without one counts).
fn lines(text: &[u8]) -> impl Iterator<Item = &[u8]> {
    line_ranges(text).map(|line| &text[line])
}

/// Where the lines of `text` lie, each without its `\n` (a last line without one counts):
/// found with `memchr`, many bytes a step.
fn line_ranges(text: &[u8]) -> impl Iterator<Item = std::ops::Range<usize>> + '_ {
    let body = text.strip_suffix(b"\n").unwrap_or(text);
    let ends = memchr::memchr_iter(b'\n', body).chain(std::iter::once(body.len()));
    let mut from = 0;
    ends.filter(|_| !text.is_empty()).map(move |end| {
        let line = from..end;
        from = end + 1;
        line
    })
}

/// The lines and the `v`, `vt` and `vn` statements of `text` (whole lines): what a piece
/// after it needs to know.
pub fn count_statements(text: &[u8]) -> Counts {
    let mut counts = Counts::default();
    for line in lines(text) {
        counts.lines += 1;
        let start = line
            .iter()
            .position(|&b| !is_space(b))
            .unwrap_or(line.len());
        let word = &line[start..];
        let end = word.iter().position(|&b| is_space(b)).unwrap_or(word.len());
        match &word[..end] {
            b"v" => counts.positions += 1,
            b"vt" => counts.uvs += 1,
            b"vn" => counts.normals += 1,
            b"f" => counts.faces += 1,
            // A line not ASCII may begin with other white space or spell a keyword with
            // invalid bytes around it: it is decoded as the reader decodes it.
            _ if !line.is_ascii() => {
                let text = String::from_utf8_lossy(line);
                match text.split_whitespace().next() {
                    Some("v") => counts.positions += 1,
                    Some("vt") => counts.uvs += 1,
                    Some("vn") => counts.normals += 1,
                    Some("f") => counts.faces += 1,
                    _ => {}
                }
            }
            _ => {}
        }
    }
    counts
}

/// Reads `text` (whole lines), the part of the file after what `before` counts, with room
/// made at once for what `holds` counts in it (its [`count_statements`]): its positions go
/// into the room `positions` and its triangles into `triangles`. An error gives its line in
/// the file.
pub fn read_piece<'a>(
    text: &[u8],
    before: Counts,
    holds: Counts,
    positions: Room<'a, Vec3>,
    triangles: Room<'a, [u32; 3]>,
) -> Result<Piece<'a>, (usize, ObjProblem)> {
    let corners = |indexed: usize| match indexed {
        0 => 0,
        _ => holds.faces,
    };
    let piece = Piece {
        positions,
        normals: Vec::with_capacity(holds.normals),
        uvs: Vec::with_capacity(holds.uvs),
        triangles,
        normal_corners: Vec::with_capacity(corners(before.normals + holds.normals)),
        uv_corners: Vec::with_capacity(corners(before.uvs + holds.uvs)),
        ..Piece::default()
    };
    let mut reader = PieceReader {
        piece,
        before,
        corners: Vec::new(),
        limit: crate::memory_budget::triangle_cap(),
    };
    // ASCII (as nearly every file is): every byte a character, so lines and words split at
    // bytes are whole characters, and the text is checked once, not line by line. Plain
    // statements are read in place, the text never cut into lines; any other line is cut out
    // and read by words.
    if text.is_ascii() {
        let ascii = std::str::from_utf8(text).unwrap_or_default();
        let (mut at, mut number) = (0, before.lines);
        while at < text.len() {
            number += 1;
            let end = match reader.plain_statement(text, at) {
                Ok(Some(end)) => end,
                Ok(None) => {
                    let end = memchr::memchr(b'\n', &text[at..]).map_or(text.len(), |e| at + e);
                    let line = ascii.get(at..end).unwrap_or_default();
                    reader
                        .statement_by_words(number, line, AsciiWords(line))
                        .map_err(|problem| (number, problem))?;
                    end
                }
                Err(problem) => return Err((number, problem)),
            };
            at = end + 1;
        }
        return Ok(reader.piece);
    }
    for (n, line) in lines(text).enumerate() {
        let number = before.lines + n + 1;
        let result = if line.is_ascii() {
            let line = std::str::from_utf8(line).unwrap_or_default();
            // A plain statement read in place, else by words (naming what is wrong).
            match reader.plain_statement(line.as_bytes(), 0) {
                Ok(Some(_)) => Ok(()),
                Ok(None) => reader.statement_by_words(number, line, AsciiWords(line)),
                Err(problem) => Err(problem),
            }
        } else {
            let line = String::from_utf8_lossy(line);
            reader.statement_by_words(number, &line, line.split_whitespace())
        };
        result.map_err(|problem| (number, problem))?;
    }
    Ok(reader.piece)
}

/// The words of an ASCII line, split at white space as `str::split_whitespace` splits them.
#[derive(Clone)]
struct AsciiWords<'a>(&'a str);

impl<'a> Iterator for AsciiWords<'a> {
    type Item = &'a str;

    #[inline]
    fn next(&mut self) -> Option<&'a str> {
        let bytes = self.0.as_bytes();
        let start = bytes.iter().position(|&b| !is_space(b))?;
        let end = bytes[start..]
            .iter()
            .position(|&b| is_space(b))
            .map_or(bytes.len(), |e| start + e);
        let word = self.0.get(start..end)?;
        self.0 = self.0.get(end..).unwrap_or_default();
        Some(word)
    }
}

/// A piece being read.
struct PieceReader<'a> {
    piece: Piece<'a>,
    before: Counts,
    /// The corners of the face being read.
    corners: Vec<Corner>,
    /// Most triangles the file may hold (the bound in force's cap), read once a piece.
    limit: u64,
}

impl PieceReader<'_> {
    /// Reads line `number` of the file (`line`, split into `words`) by its words: a line
    /// [`PieceReader::plain_statement`] did not read, or one that is not ASCII.
    fn statement_by_words<'a>(
        &mut self,
        number: usize,
        line: &'a str,
        mut words: impl Iterator<Item = &'a str>,
    ) -> Result<(), ObjProblem> {
        let piece = &mut self.piece;
        match words.next() {
            Some("v") => {
                let p = three_numbers(&mut words).ok_or(ObjProblem::Malformed(
                    "a vertex is `v x y z`, three numbers",
                ))?;
                let color = vertex_color(&mut words);
                self.vertex(p, color)?;
            }
            Some("vn") => {
                let n = three_numbers(&mut words).ok_or(ObjProblem::Malformed(
                    "a normal is `vn x y z`, three numbers",
                ))?;
                piece.normals.push(unit_or_zero(Vec3::from_array(n)));
            }
            Some("vt") => {
                let u = words.next().and_then(parse_f32);
                // `vt u [v [w]]`: v defaults to 0.
                let v = match words.next() {
                    None => Some(0.0),
                    Some(w) => parse_f32(w),
                };
                match (u, v) {
                    (Some(u), Some(v)) if u.is_finite() && v.is_finite() => {
                        piece.uvs.push(Vec2::new(u, v));
                    }
                    _ => {
                        return Err(ObjProblem::Malformed(
                            "a texture coordinate is `vt u [v [w]]`, finite numbers",
                        ));
                    }
                }
            }
            Some("f") => self.face(words)?,
            Some(keyword @ ("usemtl" | "mtllib")) => {
                // The name is the rest of the line: it may hold spaces.
                let rest = line.trim_start()[keyword.len()..].trim();
                if keyword == "mtllib" {
                    if !rest.is_empty() {
                        piece.libraries.push((number, rest.to_string()));
                    }
                } else {
                    let start = piece.triangles.len();
                    piece.material_uses.push((start, rest.to_string()));
                }
            }
            // Groups, smoothing groups, points and lines: not drawn.
            _ => {}
        }
        Ok(())
    }

    /// Adds the vertex at `p` with its colour, if the statement gives one.
    fn vertex(&mut self, p: [f32; 3], color: Option<Vec3>) -> Result<(), ObjProblem> {
        let piece = &mut self.piece;
        let vertex = self.before.positions + piece.positions.len() + 1;
        if let Some(&value) = p.iter().find(|&&x| !COORDINATE.accepts(x)) {
            return Err(if value.is_finite() {
                ObjProblem::VertexOutOfRange { vertex, value }
            } else {
                ObjProblem::NonFiniteVertex { vertex }
            });
        }
        piece.positions.push(Vec3::from_array(p));
        match (color, piece.vertex_without_color) {
            (_, true) => {}
            (Some(color), false) => piece.colors.push(color),
            (None, false) => {
                piece.vertex_without_color = true;
                piece.colors = Vec::new();
            }
        }
        Ok(())
    }

    /// Reads the corners of an `f` statement and fans them into triangles.
    fn face<'a>(&mut self, words: impl Iterator<Item = &'a str>) -> Result<(), ObjProblem> {
        self.corners.clear();
        let piece = &mut self.piece;
        let uvs = self.before.uvs + piece.uvs.len();
        let normals = self.before.normals + piece.normals.len();
        let positions = self.before.positions + piece.positions.len();
        for word in words {
            let (vertex, rest) = split_slash(word);
            // Which message, worked out only for a corner that is refused.
            let refused = || {
                ObjProblem::Malformed(match word {
                    "\\" => CONTINUED_LINE,
                    _ => CORNER_FORMS,
                })
            };
            let vertex = parse_index(vertex).ok_or_else(refused)?;
            let (uv, rest) = rest.map_or(("", None), split_slash);
            let (normal, _) = rest.map_or(("", None), split_slash);
            // An index as written, resolved; `None` when absent, `Some(NONE)` when it names
            // nothing read so far.
            let index = |word: &str, count: usize| match word {
                "" => Ok(None),
                n => parse_index(n)
                    .map(|n| {
                        Some(resolve(n, count)).map(|i| if i as usize >= count { NONE } else { i })
                    })
                    .ok_or(ObjProblem::Malformed(CORNER_FORMS)),
            };
            // A texture coordinate the file lacks leaves the model without coordinates, as
            // before rastray read them: such files loaded then and still do.
            let uv = index(uv, uvs)?.filter(|&t| t != NONE);
            let normal = index(normal, normals)?;
            if normal == Some(NONE) {
                return Err(ObjProblem::Malformed(
                    "a face names a normal the file lacks",
                ));
            }
            let vertex = resolve(vertex, positions);
            piece.missing_vertex |= vertex == NONE;
            self.corners.push(Corner { vertex, uv, normal });
        }
        self.fan()
    }

    /// Reads the plain statement at `text[at..]`, a line's start, in place: a `v` of three
    /// plain decimals, a `vn` of three, a `vt` of two, or an `f` of plain corners (see
    /// [`plain_corners`]). `Some(end)` when done, `end` the line's end (its `\n` or the text's
    /// end); `None` leaves the piece as it was, for [`PieceReader::statement_by_words`] to read the line
    /// by words (and name what is wrong). A vertex out of range is an error, as read by words.
    fn plain_statement(&mut self, text: &[u8], at: usize) -> Result<Option<usize>, ObjProblem> {
        let mut end = at;
        match (text.get(at), text.get(at + 1)) {
            (Some(b'f'), _) => Ok(self.plain_face(text, &mut end).then_some(end)),
            (Some(b'v'), Some(b't')) => {
                Ok(plain_numbers::<2>(text, &mut end, b"vt").map(|[u, v]| {
                    self.piece.uvs.push(Vec2::new(u, v));
                    end
                }))
            }
            (Some(b'v'), Some(b'n')) => Ok(plain_numbers::<3>(text, &mut end, b"vn").map(|n| {
                self.piece.normals.push(unit_or_zero(Vec3::from_array(n)));
                end
            })),
            (Some(b'v'), _) => match plain_numbers::<3>(text, &mut end, b"v") {
                Some(p) => self.vertex(p, None).map(|()| Some(end)),
                None => Ok(None),
            },
            _ => Ok(None),
        }
    }

    /// Reads the `f` statement at `text[*at..]` in place when every corner is plain (`v`,
    /// `v/vt`, `v//vn`, `v/vt/vn` with indices of at most 18 digits, each naming something
    /// read so far or, for a vertex, anything) and fans it, `*at` moved to the line's end:
    /// true when done. False leaves the piece as it was, for [`PieceReader::face`] to read the
    /// line (and name what is wrong).
    fn plain_face(&mut self, text: &[u8], at: &mut usize) -> bool {
        let piece = &self.piece;
        let counts = [
            self.before.positions + piece.positions.len(),
            self.before.uvs + piece.uvs.len(),
            self.before.normals + piece.normals.len(),
        ];
        self.corners.clear();
        let Some(corners) = plain_corners(text, at, counts, &mut self.corners) else {
            return false;
        };
        self.piece.missing_vertex |= corners;
        self.fan().is_ok()
    }

    /// Fans the corners read of a face into triangles.
    fn fan(&mut self) -> Result<(), ObjProblem> {
        let piece = &mut self.piece;
        // A point or a line: not drawn.
        if self.corners.len() < 3 {
            return Ok(());
        }
        // Refused as soon as it shows: a model file of nothing but tiny faces must not fill
        // memory before the world counts its triangles.
        let limit = self.limit;
        if (self.before.triangles + piece.triangles.len() + self.corners.len() - 2) as u64 > limit {
            return Err(ObjProblem::TooManyTriangles { limit });
        }
        let first = self.corners[0];
        for pair in self.corners[1..].windows(2) {
            let [b, c] = [pair[0], pair[1]];
            piece.triangles.push([first.vertex, b.vertex, c.vertex]);
            match (first.normal, b.normal, c.normal) {
                (Some(na), Some(nb), Some(nc)) if !piece.corner_without_normal => {
                    piece.normal_corners.push([na, nb, nc]);
                }
                _ => {
                    piece.corner_without_normal = true;
                    piece.normal_corners = Vec::new();
                }
            }
            match (first.uv, b.uv, c.uv) {
                (Some(ta), Some(tb), Some(tc)) if !piece.corner_without_uv => {
                    piece.uv_corners.push([ta, tb, tc]);
                }
                _ => {
                    piece.corner_without_uv = true;
                    piece.uv_corners = Vec::new();
                }
            }
        }
        Ok(())
    }
}

/// The corners of the `f` statement at `text[*at..]` into `corners`, read in place up to the
/// line's end (its `\n` or the text's end, where `*at` is left), with `counts` the positions,
/// texture coordinates and normals read so far: whether a vertex names nothing read so far.
/// `None`, with `corners` part filled, for anything but plain corners naming what exists (see
/// [`PieceReader::plain_face`]).
fn plain_corners(
    text: &[u8],
    at: &mut usize,
    counts: [usize; 3],
    corners: &mut Vec<Corner>,
) -> Option<bool> {
    skip_space(text, at);
    if text.get(*at..*at + 2)? != b"f " {
        return None;
    }
    *at += 2;
    let mut missing = false;
    loop {
        skip_space(text, at);
        if text.get(*at).is_none_or(|&b| b == b'\n') {
            return Some(missing);
        }
        let vertex = resolve(index_at(text, at)?, counts[0]);
        missing |= vertex == NONE;
        let mut uv = None;
        let mut normal = None;
        if text.get(*at) == Some(&b'/') {
            *at += 1;
            if text.get(*at) != Some(&b'/') {
                uv = Some(existing(index_at(text, at)?, counts[1])?);
            }
            if text.get(*at) == Some(&b'/') {
                *at += 1;
                normal = Some(existing(index_at(text, at)?, counts[2])?);
            }
        }
        if text.get(*at).is_some_and(|&b| !is_space(b)) {
            return None;
        }
        corners.push(Corner { vertex, uv, normal });
    }
}

/// The numbers of the statement at `text[*at..]` read in place when it is plain: `keyword`
/// and `N` plain decimals (see [`decimal_at`]) apart by white space, and nothing more (a `v`
/// with a colour is not plain), `*at` moved to the line's end (its `\n` or the text's end).
/// `None` for any other line, which is read by words as it would be without this path: on the
/// 1.31M-triangle icosphere this reads its vertices in about half the time.
fn plain_numbers<const N: usize>(text: &[u8], at: &mut usize, keyword: &[u8]) -> Option<[f32; N]> {
    skip_space(text, at);
    if text.get(*at..*at + keyword.len())? != keyword
        || !text
            .get(*at + keyword.len())
            .is_some_and(|&b| is_line_space(b))
    {
        return None;
    }
    *at += keyword.len();
    let mut numbers = [0.0; N];
    for x in &mut numbers {
        skip_space(text, at);
        *x = decimal_at(text, at)?;
        if text.get(*at).is_some_and(|&b| !is_space(b)) {
            return None;
        }
    }
    skip_space(text, at);
    text.get(*at).is_none_or(|&b| b == b'\n').then_some(numbers)
}

/// Moves `*at` past the white space at `text[*at..]` within its line.
#[inline]
fn skip_space(text: &[u8], at: &mut usize) {
    while text.get(*at).is_some_and(|&b| is_line_space(b)) {
        *at += 1;
    }
}

/// Index `i` as written, resolved against `count`, when it names one of them.
#[inline]
fn existing(i: i64, count: usize) -> Option<u32> {
    Some(resolve(i, count)).filter(|&r| (r as usize) < count)
}

/// `word` up to its first `/`, and the rest after that `/` when there is one.
#[inline]
fn split_slash(word: &str) -> (&str, Option<&str>) {
    match word.as_bytes().iter().position(|&b| b == b'/') {
        Some(at) => (&word[..at], Some(&word[at + 1..])),
        None => (word, None),
    }
}

/// Index `i` as written (from 1, or negative back from the `count` read so far) as an index
/// from 0; [`NONE`] when it names nothing before the end of what was read. A positive index may
/// name a vertex the file gives later; it is checked at the end.
pub fn resolve(i: i64, count: usize) -> u32 {
    let resolved = if i < 0 { count as i64 + i } else { i - 1 };
    u32::try_from(resolved)
        .ok()
        .filter(|&r| r != NONE)
        .unwrap_or(NONE)
}

/// The vertex colour that ends a `v` statement, `r g b` after the position: exactly three
/// finite numbers, read as sRGB in 0..1 (clamped) and decoded to linear. `None` otherwise.
fn vertex_color<'a>(words: &mut impl Iterator<Item = &'a str>) -> Option<Vec3> {
    let rgb = three_numbers(words)?;
    if words.next().is_some() || !rgb.iter().all(|c| c.is_finite()) {
        return None;
    }
    Some(Vec3::from_array(rgb.map(srgb_to_linear)))
}

/// The next three words as numbers; `None` when they are fewer or not numbers.
#[inline]
fn three_numbers<'a>(words: &mut impl Iterator<Item = &'a str>) -> Option<[f32; 3]> {
    let mut xyz = [0.0; 3];
    for x in &mut xyz {
        *x = parse_f32(words.next()?)?;
    }
    Some(xyz)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The corners `face` reads from `line` (an `f` statement), or `None` when it refuses it.
    fn read_by_words(line: &str, before: Counts) -> Option<String> {
        let mut reader = PieceReader {
            piece: Piece::default(),
            before,
            corners: Vec::new(),
            limit: u64::MAX,
        };
        let mut words = AsciiWords(line);
        assert_eq!(words.next(), Some("f"));
        reader.face(words).ok()?;
        let missing = reader.piece.missing_vertex;
        Some(format!("{:?} {missing}", reader.corners))
    }

    /// Pseudo-random numbers below its argument, from `seed`.
    fn below(seed: u64) -> impl FnMut(usize) -> usize {
        let mut below = crate::test_draws::below(seed);
        move |n| below(n as u64) as usize
    }

    #[test]
    fn plain_vertices_read_byte_by_byte_as_words_read_them() {
        let numbers = [
            "0",
            "-0",
            "1",
            "-1.5",
            "+2.25",
            "0.5257311",
            "-0.8506508",
            ".5",
            "1.",
            "1e3",
            "inf",
            "nan",
            "x",
            "-",
            "1.2.3",
            "16777217",
            "0.00000000001",
            "1234567890123456789",
        ];
        let spaces = [" ", "  ", "\t", " \r", "\x0b"];
        let mut next = below(99);
        let mut plain = 0;
        for _ in 0..20_000 {
            let mut line = String::from(["v ", " v ", "v\t", "vn ", "v"][next(5)]);
            // Mostly three plain decimals, so that whole vertices read.
            let count = if next(4) > 0 { 3 } else { next(7) };
            for _ in 0..count {
                line += numbers[if next(6) > 0 {
                    next(7)
                } else {
                    next(numbers.len())
                }];
                line += spaces[next(spaces.len())];
            }
            let mut words = AsciiWords(&line);
            let by_words = (words.next() == Some("v"))
                .then(|| three_numbers(&mut words))
                .flatten()
                .filter(|_| vertex_color(&mut words.clone()).is_none());
            // Read as a line alone, and in place in a file's text with more lines after it.
            let in_text = format!("{line}\nv 12345678 1 2\n");
            let mut end = 0;
            let read_in_text = plain_numbers::<3>(in_text.as_bytes(), &mut end, b"v");
            let bits = |p: Option<[f32; 3]>| p.map(|p| p.map(f32::to_bits));
            let read = plain_numbers::<3>(line.as_bytes(), &mut 0, b"v");
            assert_eq!(bits(read_in_text), bits(read), "{line:?}");
            if let Some(p) = read {
                assert_eq!(end, line.len(), "{line:?}");
                plain += 1;
                let bits = |p: [f32; 3]| p.map(f32::to_bits);
                assert_eq!(Some(bits(p)), by_words.map(bits), "{line:?}");
                // Nothing follows the position: no colour.
                assert_eq!(words.next(), None, "{line:?}");
            }
        }
        assert!(plain > 1_000, "{plain} plain vertices of 20000");
    }

    #[test]
    fn text_read_in_place_reads_as_its_lines_one_by_one() {
        let lines = [
            "v 1 2 3",
            "v 0.5 -1.25 2",
            "v 0.12345678 1 2",
            "  v 1 1 1",
            "v 1 2 3 0.5 0.25 1",
            "v 1 2",
            "vt 0.5 0.25",
            "vt 0.1 0.2 0",
            "vn 0 0 1",
            "vn 0 0",
            "f 1 2 3",
            "f 1 2 3 4",
            "f 1/1/1 2/2/1 3/3/1",
            "f 1//1 2//1 3//1",
            "f -1 -2 -3",
            "f 1 2",
            "f 1 2 x",
            "# a comment",
            "",
            "usemtl red",
            "g group",
            "v 1e40 0 0",
            "v\t1 2 3",
            "f\t1 2 3",
            "vn\t0 1 0",
            "vt\t0 1",
            "vx 1 2 3",
            "\tf 1 2 3",
        ];
        let mut next = below(7);
        for _ in 0..300 {
            let mut text = String::new();
            for _ in 0..next(40) {
                text += lines[next(lines.len())];
                text += ["\n", "\r\n", " \n"][next(3)];
            }
            if next(2) == 0 {
                text += lines[next(lines.len())];
            }
            let read = |text: &str| {
                let bytes = text.as_bytes();
                format!(
                    "{:?}",
                    read_piece(
                        bytes,
                        Counts::default(),
                        count_statements(bytes),
                        Room::default(),
                        Room::default()
                    )
                )
            };
            // A comment that is not ASCII sends the whole text through the line-by-line path.
            let by_lines = read(&format!("{text}\n# é"));
            assert_eq!(read(&text), by_lines, "{text:?}");
            // The statements counted are those whose first word names them.
            let mut by_words = Counts::default();
            for line in text.lines() {
                by_words.lines += 1;
                match line.split_whitespace().next() {
                    Some("v") => by_words.positions += 1,
                    Some("vt") => by_words.uvs += 1,
                    Some("vn") => by_words.normals += 1,
                    Some("f") => by_words.faces += 1,
                    _ => {}
                }
            }
            assert_eq!(count_statements(text.as_bytes()), by_words, "{text:?}");
        }
    }

    #[test]
    fn plain_faces_read_byte_by_byte_as_words_read_them() {
        let before = Counts {
            positions: 4,
            uvs: 2,
            normals: 2,
            ..Counts::default()
        };
        let counts = [4, 2, 2];
        // Corners of every form, in range and not, signed, empty and malformed.
        let forms = [
            "1",
            "-1",
            "+2",
            "4",
            "5",
            "-5",
            "0",
            "1/1",
            "2/-2",
            "3/3",
            "1//2",
            "2//3",
            "1/2/1",
            "3/1/-1",
            "1/",
            "1//",
            "1/2/",
            "1/2/1/1",
            "x",
            "1x",
            "1/x",
            "-",
            "+",
            "/1",
            "12345678901234567890",
            "000000000000000000001",
        ];
        let mut next = below(12345);
        let mut plain = 0;
        for _ in 0..20_000 {
            let spaces = [" ", "  ", "\t", " \r"];
            let mut line = String::from(["f ", " f ", "f\t"][next(3)]);
            for _ in 0..next(6) {
                // Mostly forms that read, so that whole faces do.
                line += forms[if next(3) > 0 {
                    next(14)
                } else {
                    next(forms.len())
                }];
                line += spaces[next(spaces.len())];
            }
            let mut corners = Vec::new();
            // Read in place in a file's text, with more lines after it, and as a line alone.
            let in_text = format!("{line}\nf 12345678 2 3\n");
            let mut end = 0;
            let read_in_text = plain_corners(in_text.as_bytes(), &mut end, counts, &mut corners)
                .map(|missing| format!("{corners:?} {missing}"));
            corners.clear();
            if let Some(missing) = plain_corners(line.as_bytes(), &mut 0, counts, &mut corners) {
                assert_eq!(end, line.len(), "{line:?}");
                assert_eq!(
                    read_in_text,
                    Some(format!("{corners:?} {missing}")),
                    "{line:?}"
                );
                plain += 1;
                let bytes = Some(format!("{corners:?} {missing}"));
                assert_eq!(bytes, read_by_words(&line, before), "{line:?}");
            }
        }
        assert!(plain > 5_000, "{plain} plain faces of 20000");
    }
}
