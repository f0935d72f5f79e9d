//! The body of an ASCII PLY: one record a line, values separated by blanks. Blank lines are
//! passed over.

use std::io::BufRead;

use super::binary::Role;
use super::collect::Collector;
use super::error::PlyProblem;
use super::header::{Element, PropertyType, shortened};
use super::plan::{FaceLists, Plan, SLOTS, Target};
use super::scalar::Scalar;
use crate::mesh::Place;

/// Lines of an ASCII body, counted from the header's.
pub struct Lines<B> {
    reader: B,
    line: Vec<u8>,
    /// 1-based number of the line last read.
    pub number: usize,
}

impl<B: BufRead> Lines<B> {
    /// The lines of `reader`, the first numbered `after + 1`.
    pub fn new(reader: B, after: usize) -> Lines<B> {
        Lines {
            reader,
            line: Vec::new(),
            number: after,
        }
    }

    /// The next line that is not blank; `None` at the end.
    fn next(&mut self) -> std::io::Result<Option<String>> {
        loop {
            self.line.clear();
            if self.reader.read_until(b'\n', &mut self.line)? == 0 {
                return Ok(None);
            }
            self.number += 1;
            let text = String::from_utf8_lossy(&self.line);
            if !text.trim().is_empty() {
                return Ok(Some(text.into_owned()));
            }
        }
    }
}

/// Reads the records of `element` by `plan`, feeding `collector` as `role` says.
pub fn read_element<B: BufRead>(
    lines: &mut Lines<B>,
    element: &Element,
    plan: &Plan,
    role: Role,
    collector: &mut Collector,
) -> Result<(), (Place, PlyProblem)> {
    if element.properties.is_empty() {
        return Ok(());
    }
    let mut values = [0f64; SLOTS];
    let mut lists = FaceLists::default();
    for index in 1..=element.count {
        let Some(line) = lines.next().map_err(|e| (Place::File, PlyProblem::Io(e)))? else {
            return Err((
                Place::Line(lines.number),
                PlyProblem::Truncated {
                    element: element.name.clone(),
                    index,
                    count: element.count,
                },
            ));
        };
        let fail = |problem| (Place::Line(lines.number), problem);
        let mut tokens = line.split_whitespace();
        let mut next = |ty: Scalar| -> Result<f64, PlyProblem> {
            let token = tokens.next().ok_or_else(|| PlyProblem::TooFewValues {
                element: element.name.clone(),
                index,
            })?;
            number(token, ty)
        };
        for &(ty, target) in &plan.properties {
            match ty {
                PropertyType::Scalar(s) => {
                    let value = next(s).map_err(fail)?;
                    if let Target::Slot(k) = target {
                        values[k] = value;
                    }
                }
                PropertyType::List { count, item } => {
                    let n = next(count).map_err(fail)?;
                    if n < 0.0 {
                        return Err(fail(PlyProblem::BadListLength {
                            element: element.name.clone(),
                            index,
                        }));
                    }
                    if let Some(list) = lists.of(target) {
                        list.clear();
                    }
                    for _ in 0..n as u64 {
                        let value = next(item).map_err(fail)?;
                        if let Some(list) = lists.of(target) {
                            list.push(value);
                        }
                    }
                }
            }
        }
        if tokens.next().is_some() {
            return Err(fail(PlyProblem::TooManyValues {
                element: element.name.clone(),
                index,
            }));
        }
        match role {
            Role::Vertex => collector.vertex(&values),
            Role::Face => collector.face(&lists, true),
            Role::Skip => Ok(()),
        }
        .map_err(fail)?;
    }
    Ok(())
}

/// `token` as a value of type `ty`: whole numbers within the type's range for the integer
/// types, any number for the floating-point ones.
fn number(token: &str, ty: Scalar) -> Result<f64, PlyProblem> {
    let bad = || PlyProblem::BadNumber {
        token: shortened(token),
        ty: ty.to_string(),
    };
    if ty.is_integer() {
        let value: i64 = token.parse().map_err(|_| bad())?;
        let (lo, hi) = match ty {
            Scalar::I8 => (i8::MIN as i64, i8::MAX as i64),
            Scalar::U8 => (0, u8::MAX as i64),
            Scalar::I16 => (i16::MIN as i64, i16::MAX as i64),
            Scalar::U16 => (0, u16::MAX as i64),
            Scalar::I32 => (i32::MIN as i64, i32::MAX as i64),
            _ => (0, u32::MAX as i64),
        };
        if (lo..=hi).contains(&value) {
            Ok(value as f64)
        } else {
            Err(bad())
        }
    } else {
        token.parse().map_err(|_| bad())
    }
}
