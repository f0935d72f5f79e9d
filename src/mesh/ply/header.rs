//! The PLY header: the format line, the elements with their properties in order, and the
//! comments rastray reads (`comment TextureFile NAME`).

use std::fmt;
use std::io::Read;

use super::error::PlyProblem;
use super::scalar::Scalar;
use crate::mesh::Place;
use crate::mesh::byte_source::ByteSource;

/// Longest header read, bytes.
pub const MAX_HEADER_BYTES: usize = 1 << 20;

/// How the body is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlyEncoding {
    Ascii,
    BinaryLittleEndian,
    BinaryBigEndian,
}

impl fmt::Display for PlyEncoding {
    /// The header's own spelling: `ascii`, `binary_little_endian`, `binary_big_endian`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            PlyEncoding::Ascii => "ascii",
            PlyEncoding::BinaryLittleEndian => "binary_little_endian",
            PlyEncoding::BinaryBigEndian => "binary_big_endian",
        })
    }
}

/// One property's type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PropertyType {
    Scalar(Scalar),
    /// A length of type `count`, then that many values of type `item`.
    List {
        count: Scalar,
        item: Scalar,
    },
}

/// One property of an element.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Property {
    pub name: String,
    pub ty: PropertyType,
}

/// One element: `count` records, each the properties in order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Element {
    pub name: String,
    pub count: u64,
    pub properties: Vec<Property>,
    /// The header line that declares it.
    pub line: usize,
}

impl Element {
    /// The fewest bytes a record can take: in binary, the scalars and list lengths (a list may
    /// be empty); in ASCII, one character and one separator a property.
    pub fn min_record_bytes(&self, encoding: PlyEncoding) -> u64 {
        self.properties
            .iter()
            .map(|p| match (encoding, p.ty) {
                (PlyEncoding::Ascii, _) => 2,
                (_, PropertyType::Scalar(s)) => s.size() as u64,
                (_, PropertyType::List { count, .. }) => count.size() as u64,
            })
            .sum()
    }

    /// Where the property called `name` is among the element's properties.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.properties.iter().position(|p| p.name == name)
    }
}

/// A parsed header.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Header {
    pub encoding: PlyEncoding,
    pub elements: Vec<Element>,
    /// The image named by `comment TextureFile NAME`, as written.
    pub texture: Option<String>,
    /// Lines the header took (the body's first line is the next).
    pub lines: usize,
}

/// Reads the header from `source`, leaving it at the body's first byte.
pub fn read_header<R: Read>(source: &mut ByteSource<R>) -> Result<Header, (Place, PlyProblem)> {
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut texture = None;
    let mut number = 0;
    loop {
        let line = next_line(source)?;
        number += 1;
        let fail = |problem| (Place::Line(number), problem);
        let text = String::from_utf8_lossy(&line);
        let text = text.trim_end_matches(['\r', '\n']);
        if number == 1 {
            if text.trim_end() != "ply" {
                return Err(fail(PlyProblem::NotPly));
            }
            continue;
        }
        let expected = |expected| {
            fail(PlyProblem::Header {
                expected,
                found: shortened(text),
            })
        };
        let mut words = text.split_whitespace();
        match words.next() {
            Some("format") => {
                let name = words.next().unwrap_or("");
                encoding = Some(match name {
                    "ascii" => PlyEncoding::Ascii,
                    "binary_little_endian" => PlyEncoding::BinaryLittleEndian,
                    "binary_big_endian" => PlyEncoding::BinaryBigEndian,
                    _ => return Err(fail(PlyProblem::UnknownFormat(shortened(name)))),
                });
                if !words.next().is_some_and(|v| v.starts_with('1')) {
                    return Err(expected("`format FORMAT 1.0`"));
                }
            }
            Some("comment") => {
                let rest = text.trim_start()["comment".len()..].trim();
                if let Some(name) = rest
                    .strip_prefix("TextureFile")
                    .or_else(|| rest.strip_prefix("texturefile"))
                    .filter(|n| n.starts_with(char::is_whitespace))
                {
                    texture = Some(name.trim().to_string());
                }
            }
            Some("obj_info") => {}
            Some("element") => {
                let (Some(name), Some(count), None) = (words.next(), words.next(), words.next())
                else {
                    return Err(expected("`element NAME COUNT`"));
                };
                let count = count
                    .parse()
                    .map_err(|_| expected("`element NAME COUNT`, COUNT a whole number"))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    properties: Vec::new(),
                    line: number,
                });
            }
            Some("property") => {
                let words: Vec<&str> = words.collect();
                let (ty, name) = match words[..] {
                    ["list", count, item, name] => {
                        let count = scalar(count).map_err(fail)?;
                        if !count.is_integer() {
                            return Err(fail(PlyProblem::ListLengthType(count.to_string())));
                        }
                        let item = scalar(item).map_err(fail)?;
                        (PropertyType::List { count, item }, name)
                    }
                    [ty, name] if ty != "list" => {
                        (PropertyType::Scalar(scalar(ty).map_err(fail)?), name)
                    }
                    _ => {
                        return Err(expected(
                            "`property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`",
                        ));
                    }
                };
                let Some(element) = elements.last_mut() else {
                    return Err(expected("`element` before its `property` lines"));
                };
                element.properties.push(Property {
                    name: name.to_string(),
                    ty,
                });
            }
            Some("end_header") => break,
            None => {}
            Some(_) => {
                return Err(expected(
                    "a header line (format, comment, element, property)",
                ));
            }
        }
    }
    let encoding = encoding.ok_or((
        Place::Line(number),
        PlyProblem::Header {
            expected: "a `format` line before `end_header`",
            found: "end_header".into(),
        },
    ))?;
    Ok(Header {
        encoding,
        elements,
        texture,
        lines: number,
    })
}

fn scalar(name: &str) -> Result<Scalar, PlyProblem> {
    Scalar::from_name(name).ok_or_else(|| PlyProblem::UnknownType(shortened(name)))
}

/// The next header line with its line feed, consumed; refused when the header runs past
/// [`MAX_HEADER_BYTES`] or the file ends first.
fn next_line<R: Read>(source: &mut ByteSource<R>) -> Result<Vec<u8>, (Place, PlyProblem)> {
    let io = |e| (Place::File, PlyProblem::Io(e));
    let mut want = 256;
    loop {
        let at_start = source.offset() == 0;
        let left = MAX_HEADER_BYTES.saturating_sub(source.offset() as usize);
        let ahead = source.ahead(want.min(left)).map_err(io)?;
        if let Some(end) = ahead.iter().take(left).position(|&b| b == b'\n') {
            let line = ahead[..=end].to_vec();
            source.consume(end + 1);
            return Ok(line);
        }
        if ahead.len() < want.min(left) || ahead.len() >= left {
            let problem = if at_start && !ahead.starts_with(b"ply") {
                PlyProblem::NotPly
            } else {
                PlyProblem::HeaderTooLong {
                    limit: MAX_HEADER_BYTES,
                }
            };
            return Err((Place::File, problem));
        }
        want *= 2;
    }
}

/// At most 60 characters of `text`, with `…` when cut.
pub fn shortened(text: &str) -> String {
    match text.char_indices().nth(60) {
        Some((at, _)) => format!("{}…", &text[..at]),
        None => text.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Header, (Place, PlyProblem)> {
        read_header(&mut ByteSource::new(text.as_bytes()))
    }

    #[test]
    fn a_header_gives_its_elements_in_order() {
        let header = parse(
            "ply\r\nformat binary_big_endian 1.0\r\ncomment TextureFile wood.png\r\n\
             element vertex 3\r\nproperty double z\r\nproperty short x\r\nproperty float32 y\r\n\
             element face 1\r\nproperty list uint8 int32 vertex_indices\r\nend_header\r\nBODY",
        )
        .unwrap();
        assert_eq!(header.encoding, PlyEncoding::BinaryBigEndian);
        assert_eq!(header.texture.as_deref(), Some("wood.png"));
        assert_eq!(header.elements.len(), 2);
        assert_eq!(header.elements[0].find("y"), Some(2));
        assert_eq!(
            header.elements[1].properties[0].ty,
            PropertyType::List {
                count: Scalar::U8,
                item: Scalar::I32
            }
        );
        assert_eq!(
            header.elements[0].min_record_bytes(PlyEncoding::BinaryBigEndian),
            14
        );
        assert_eq!(header.lines, 10);
    }

    #[test]
    fn bad_headers_say_what_and_where() {
        let at = |text: &str| {
            let (place, problem) = parse(text).unwrap_err();
            format!("{place}: {problem}")
        };
        assert_eq!(
            at("plx\n"),
            ":1: not a PLY file: the first line must be `ply`"
        );
        assert!(
            at("ply\nformat ascii 1.0\nelement vertex 1\nproperty long x\nend_header\n")
                .starts_with(":4: unknown type `long`"),
        );
        assert!(at("ply\nformat text 1.0\n").starts_with(":2: unknown format `text`"));
        assert!(at("ply\nformat ascii 1.0\n").contains("no `end_header`"));
        assert!(at("ply\nformat ascii 1.0\nproperty float x\nend_header\n").starts_with(":3:"));
        assert!(
            at("ply\nformat ascii 1.0\nelement face 1\nproperty list float int v\nend_header\n")
                .contains("whole-number type, not float")
        );
    }
}
