//! The body of a binary PLY, either byte order: each element's records in turn, read from
//! the buffer of a [`ByteSource`] without copying, one record at a time.

use std::io::Read;

use super::collect::Collector;
use super::error::PlyProblem;
use super::header::{Element, PropertyType};
use super::plan::{FaceLists, Plan, SLOTS, Target};
use crate::mesh::Place;
use crate::mesh::byte_source::ByteSource;

/// What a record lacks: it needs at least this many bytes from its start.
struct Short(usize);

/// A record's list with a negative length.
struct NegativeLength;

/// What an element's records feed.
pub enum Role {
    Vertex,
    Face,
    Skip,
}

/// Reads the records of `element` from `source` by `plan`, from record `first` (counting from
/// 0: the records before it are read already) to the last, feeding `collector` as `role`
/// says; `size` is the file's size in bytes. Big-endian when `BIG`.
pub fn read_element<R: Read, const BIG: bool>(
    source: &mut ByteSource<R>,
    size: u64,
    (element, first): (&Element, u64),
    plan: &Plan,
    role: Role,
    collector: &mut Collector,
) -> Result<(), (Place, PlyProblem)> {
    if element.properties.is_empty() {
        return Ok(());
    }
    let io = |e| (Place::File, PlyProblem::Io(e));
    let mut values = [0f64; SLOTS];
    let mut lists = FaceLists::default();
    let mut index = first;
    let mut need = 1;
    while index < element.count {
        let start = source.offset();
        let block = source.ahead(need).map_err(io)?;
        let mut at = 0;
        need = loop {
            match record::<BIG>(&plan.properties, &block[at..], &mut values, &mut lists) {
                Ok(length) => {
                    let fed = match role {
                        Role::Vertex => collector.vertex(&values),
                        Role::Face => collector.face(&lists, false),
                        Role::Skip => Ok(()),
                    };
                    fed.map_err(|problem| (Place::Byte(start + at as u64), problem))?;
                    at += length;
                    index += 1;
                    if index == element.count {
                        break 0;
                    }
                }
                Err(Ok(Short(length))) => break length,
                Err(Err(NegativeLength)) => {
                    return Err((
                        Place::Byte(start + at as u64),
                        PlyProblem::BadListLength {
                            element: element.name.clone(),
                            index: index + 1,
                        },
                    ));
                }
            }
        };
        source.consume(at);
        if need > 0 && source.offset() + need as u64 > size {
            return Err((
                Place::Byte(size),
                PlyProblem::Truncated {
                    element: element.name.clone(),
                    index: index + 1,
                    count: element.count,
                },
            ));
        }
        if need > 0 && at == 0 && source.ahead(need).map_err(io)?.len() < need {
            // The file shrank while it was read.
            return Err((
                Place::Byte(source.offset()),
                PlyProblem::Truncated {
                    element: element.name.clone(),
                    index: index + 1,
                    count: element.count,
                },
            ));
        }
    }
    Ok(())
}

/// Reads one record from the start of `bytes` by `properties`: scalar values into their
/// `values` slot, the face's lists into `lists`. The record's length, or the bytes it
/// needs when `bytes` is too short for it.
#[inline(always)]
fn record<const BIG: bool>(
    properties: &[(PropertyType, Target)],
    bytes: &[u8],
    values: &mut [f64; SLOTS],
    lists: &mut FaceLists,
) -> Result<usize, Result<Short, NegativeLength>> {
    let mut at = 0;
    for &(ty, target) in properties {
        match ty {
            PropertyType::Scalar(s) => {
                let end = at + s.size();
                let Some(field) = bytes.get(at..end) else {
                    return Err(Ok(Short(end)));
                };
                if let Target::Slot(k) = target {
                    values[k] = s.read::<BIG>(field);
                }
                at = end;
            }
            PropertyType::List { count, item } => {
                let end = at + count.size();
                let Some(field) = bytes.get(at..end) else {
                    return Err(Ok(Short(end)));
                };
                let n = count.read::<BIG>(field);
                if n < 0.0 {
                    return Err(Err(NegativeLength));
                }
                let start = end;
                let end = start + n as usize * item.size();
                let Some(items) = bytes.get(start..end) else {
                    return Err(Ok(Short(end)));
                };
                if let Some(list) = lists.of(target) {
                    list.clear();
                    list.extend(items.chunks_exact(item.size()).map(|b| item.read::<BIG>(b)));
                }
                at = end;
            }
        }
    }
    Ok(at)
}
