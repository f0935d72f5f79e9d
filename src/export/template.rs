//! Output templates: one `-o` for many files. `out/{stem}.png` names each input's image,
//! `frames/{frame:04}.png` each frame of a turntable. The fields are `{stem}` (the input's
//! file name without its extension), `{name}` (with it), `{index}` (the input's position, from
//! 0), `{view}`, `{algo}` and `{frame}` (from 0); a number field takes zero padding to any
//! width, `{frame:04}`. `{{` and `}}` are literal braces.

use std::fmt::Write;
use std::path::{Path, PathBuf};

/// A field of an output template.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Field {
    /// The input's file name without its extension.
    Stem,
    /// The input's file name.
    Name,
    /// The input's position in the sorted list of inputs, from 0.
    Index,
    /// The name of the view (`front`, `iso`, …).
    View,
    /// The algorithm: `gouraud`, `phong` or `ray`.
    Algo,
    /// The turntable frame, from 0.
    Frame,
}

impl Field {
    /// Every field, in the order the help lists them.
    pub const ALL: [Field; 6] = [
        Field::Stem,
        Field::Name,
        Field::Index,
        Field::View,
        Field::Algo,
        Field::Frame,
    ];

    /// The name written between the braces.
    pub fn name(self) -> &'static str {
        match self {
            Field::Stem => "stem",
            Field::Name => "name",
            Field::Index => "index",
            Field::View => "view",
            Field::Algo => "algo",
            Field::Frame => "frame",
        }
    }

    /// Whether the field is a number, which may be zero-padded.
    fn is_number(self) -> bool {
        matches!(self, Field::Index | Field::Frame)
    }
}

/// One piece of a template.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Part {
    Text(String),
    /// A field, zero-padded to `width` digits (0: as wide as the number).
    Field {
        field: Field,
        width: usize,
    },
}

/// A parsed output template.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputTemplate {
    parts: Vec<Part>,
}

/// What one output's fields stand for.
#[derive(Debug, Clone, Copy)]
pub struct FieldValues<'a> {
    /// The input file (`-` for standard input).
    pub input: &'a Path,
    /// The input's position among all inputs, from 0.
    pub index: usize,
    pub view: Option<&'a str>,
    pub algo: &'a str,
    pub frame: Option<u32>,
}

/// A template that cannot be read; each names the template and the byte where it went wrong.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum TemplateError {
    #[error(
        "output template `{template}`: the `{{` at byte {at} is not closed (write `{{{{` for a brace)"
    )]
    Unclosed { template: String, at: usize },
    #[error(
        "output template `{template}`: the `}}` at byte {at} closes nothing (write `}}}}` for a brace)"
    )]
    Unopened { template: String, at: usize },
    #[error(
        "output template `{template}`: `{{{field}}}` at byte {at} is no field; the fields are {{stem}}, {{name}}, {{index}}, {{view}}, {{algo}} and {{frame}} (padded as {{frame:04}})"
    )]
    Unknown {
        template: String,
        field: String,
        at: usize,
    },
    #[error(
        "output template `{template}`: `{{{field}}}` at byte {at}: only {{index}} and {{frame}} take a padding, written `:0` and a width up to 9, as {{frame:04}}"
    )]
    Padding {
        template: String,
        field: String,
        at: usize,
    },
}

/// Widest zero padding, digits.
const MAX_WIDTH: usize = 9;

impl OutputTemplate {
    /// Reads `template`; a path with no braces is a template of plain text.
    pub fn parse(template: &str) -> Result<OutputTemplate, TemplateError> {
        let mut parts = Vec::new();
        let mut text = String::new();
        let mut rest = template.char_indices().peekable();
        while let Some((at, c)) = rest.next() {
            match c {
                '{' if rest.peek().map(|&(_, c)| c) == Some('{') => {
                    rest.next();
                    text.push('{');
                }
                '}' if rest.peek().map(|&(_, c)| c) == Some('}') => {
                    rest.next();
                    text.push('}');
                }
                '}' => {
                    return Err(TemplateError::Unopened {
                        template: template.to_string(),
                        at,
                    });
                }
                '{' => {
                    let inner_start = at + 1;
                    let Some(close) = template[inner_start..].find('}') else {
                        return Err(TemplateError::Unclosed {
                            template: template.to_string(),
                            at,
                        });
                    };
                    let inner = &template[inner_start..inner_start + close];
                    while rest.peek().is_some_and(|&(i, _)| i <= inner_start + close) {
                        rest.next();
                    }
                    if !text.is_empty() {
                        parts.push(Part::Text(std::mem::take(&mut text)));
                    }
                    parts.push(field_part(template, inner, at)?);
                }
                c => text.push(c),
            }
        }
        if !text.is_empty() {
            parts.push(Part::Text(text));
        }
        Ok(OutputTemplate { parts })
    }

    /// Whether the template holds `field`.
    pub fn has(&self, field: Field) -> bool {
        self.parts
            .iter()
            .any(|p| matches!(p, Part::Field { field: f, .. } if *f == field))
    }

    /// Whether the template has any field at all.
    pub fn has_fields(&self) -> bool {
        self.parts.iter().any(|p| matches!(p, Part::Field { .. }))
    }

    /// Whether two inputs get two names: the template holds `{stem}`, `{name}` or `{index}`.
    pub fn tells_inputs_apart(&self) -> bool {
        self.has(Field::Stem) || self.has(Field::Name) || self.has(Field::Index)
    }

    /// The path of one output. A field with no value (`{view}` without views, `{frame}` of a
    /// still) is left out.
    pub fn fill(&self, values: &FieldValues) -> PathBuf {
        let file_name = values
            .input
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "stdin".to_string());
        let stem = Path::new(&file_name)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mut out = String::new();
        for part in &self.parts {
            match part {
                Part::Text(text) => out.push_str(text),
                Part::Field { field, width } => {
                    let number = |n: u64| {
                        let mut s = String::new();
                        let _ = write!(s, "{n:0width$}");
                        s
                    };
                    let value = match field {
                        Field::Stem => stem.clone(),
                        Field::Name => file_name.clone(),
                        Field::Index => number(values.index as u64),
                        Field::View => values.view.unwrap_or_default().to_string(),
                        Field::Algo => values.algo.to_string(),
                        Field::Frame => values.frame.map(|k| number(k.into())).unwrap_or_default(),
                    };
                    out.push_str(&value);
                }
            }
        }
        PathBuf::from(out)
    }
}

/// The field written `{inner}` at byte `at` of `template`.
fn field_part(template: &str, inner: &str, at: usize) -> Result<Part, TemplateError> {
    let (name, padding) = match inner.split_once(':') {
        Some((name, padding)) => (name, Some(padding)),
        None => (inner, None),
    };
    let Some(field) = Field::ALL.into_iter().find(|f| f.name() == name) else {
        return Err(TemplateError::Unknown {
            template: template.to_string(),
            field: inner.to_string(),
            at,
        });
    };
    let bad_padding = || TemplateError::Padding {
        template: template.to_string(),
        field: inner.to_string(),
        at,
    };
    let width = match padding {
        None => 0,
        Some(_) if !field.is_number() => return Err(bad_padding()),
        Some(padding) => {
            let digits = padding.strip_prefix('0').ok_or_else(bad_padding)?;
            match digits.parse::<usize>() {
                Ok(width) if (1..=MAX_WIDTH).contains(&width) => width,
                _ => return Err(bad_padding()),
            }
        }
    };
    Ok(Part::Field { field, width })
}

#[cfg(test)]
mod tests {
    use std::path::{Path, PathBuf};

    use super::{Field, FieldValues, OutputTemplate, TemplateError};

    fn values(input: &str) -> FieldValues<'_> {
        FieldValues {
            input: Path::new(input),
            index: 7,
            view: Some("iso"),
            algo: "phong",
            frame: Some(42),
        }
    }

    fn fill(template: &str, input: &str) -> PathBuf {
        OutputTemplate::parse(template)
            .unwrap()
            .fill(&values(input))
    }

    #[test]
    fn every_field_is_filled() {
        assert_eq!(
            fill("out/{stem}.png", "models/bunny.obj"),
            Path::new("out/bunny.png")
        );
        assert_eq!(
            fill("{name}-{index}-{view}-{algo}-{frame}.png", "a/b.c.glb"),
            Path::new("b.c.glb-7-iso-phong-42.png")
        );
        assert_eq!(
            fill("f/{frame:04}_{index:02}.png", "x.obj"),
            Path::new("f/0042_07.png")
        );
        assert_eq!(
            fill("{{literal}}{stem}.png", "x.obj"),
            Path::new("{literal}x.png")
        );
        assert_eq!(fill("plain.png", "x.obj"), Path::new("plain.png"));
        // A number wider than its padding is written whole.
        assert_eq!(fill("{frame:01}.png", "x.obj"), Path::new("42.png"));
    }

    #[test]
    fn a_template_says_which_fields_it_has() {
        let t = OutputTemplate::parse("out/{stem}.png").unwrap();
        assert!(t.has(Field::Stem) && !t.has(Field::Frame));
        assert!(t.tells_inputs_apart() && t.has_fields());
        let t = OutputTemplate::parse("frames/{frame:04}.png").unwrap();
        assert!(t.has(Field::Frame) && !t.tells_inputs_apart());
        let t = OutputTemplate::parse("out.png").unwrap();
        assert!(!t.has_fields() && !t.tells_inputs_apart());
        assert!(
            OutputTemplate::parse("{index}.png")
                .unwrap()
                .tells_inputs_apart()
        );
    }

    #[test]
    fn bad_templates_are_refused_with_the_byte() {
        let err = |t: &str| OutputTemplate::parse(t).unwrap_err();
        assert!(matches!(
            err("out/{stem.png"),
            TemplateError::Unclosed { at: 4, .. }
        ));
        assert!(matches!(
            err("out}.png"),
            TemplateError::Unopened { at: 3, .. }
        ));
        let unknown = err("{stme}.png");
        assert!(matches!(unknown, TemplateError::Unknown { at: 0, .. }));
        assert!(unknown.to_string().contains("{stme}"), "{unknown}");
        assert!(unknown.to_string().contains("{stem}"), "{unknown}");
        for padded in [
            "{stem:04}",
            "{frame:4}",
            "{frame:0}",
            "{frame:0x}",
            "{frame:010}",
        ] {
            assert!(
                matches!(err(padded), TemplateError::Padding { .. }),
                "{padded}"
            );
        }
    }
}
