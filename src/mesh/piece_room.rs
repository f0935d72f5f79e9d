//! Where one piece of a text file writes what it reads: its own part of the file's array, made
//! before the pieces are read and as long as a quick count of the piece says ([`Room`]), so that
//! the values land where they stay. Values past that part (the count was a lower bound, as a
//! polygon gives more triangles than its one face) go to a vector of the piece's own, and
//! [`join_rooms`] moves them in after the pieces are read. No piece keeps a second copy of its
//! vertices and triangles to be copied in after: on a virtual machine each fresh page costs
//! about 2 µs to fault in, and those copies were a third of the pages an OBJ's load touched.

/// A piece's part of the file's array, filled from its start, and what did not fit.
#[derive(Debug, Default)]
pub struct Room<'a, T> {
    slots: &'a mut [T],
    /// Slots written, from the first.
    filled: usize,
    /// Values pushed once every slot was written.
    extra: Vec<T>,
}

impl<'a, T: Copy> Room<'a, T> {
    /// An empty room over `slots`.
    pub fn new(slots: &'a mut [T]) -> Room<'a, T> {
        Room {
            slots,
            filled: 0,
            extra: Vec::new(),
        }
    }

    /// Adds `value` after those pushed so far.
    #[inline]
    pub fn push(&mut self, value: T) {
        match self.slots.get_mut(self.filled) {
            Some(slot) => {
                *slot = value;
                self.filled += 1;
            }
            None => self.extra.push(value),
        }
    }

    /// `values` cut into one room a piece, one after another, each as long as `lengths` says,
    /// as far as `values` goes (the rooms past its end are empty).
    pub fn cut(mut values: &'a mut [T], lengths: impl Iterator<Item = usize>) -> Vec<Room<'a, T>> {
        lengths
            .map(|length| {
                let length = length.min(values.len());
                let (slots, rest) = std::mem::take(&mut values).split_at_mut(length);
                values = rest;
                Room::new(slots)
            })
            .collect()
    }

    /// Values pushed so far.
    #[inline]
    pub fn len(&self) -> usize {
        self.filled + self.extra.len()
    }

    /// What [`join_rooms`] needs once the room's slots are no longer borrowed.
    pub fn into_filled(self) -> Filled<T> {
        Filled {
            room: self.slots.len(),
            filled: self.filled,
            extra: self.extra,
        }
    }
}

/// A room as its piece left it: slots made, slots written and the values past them.
#[derive(Debug)]
pub struct Filled<T> {
    room: usize,
    filled: usize,
    extra: Vec<T>,
}

/// Joins the pieces' values in `values[start..]`, where the `rooms` lie one after another as
/// they were made, into one run in piece order, and leaves `values` ending with it. Nothing
/// moves when every piece filled its room exactly (as when every face of a file is a triangle).
/// When each piece filled its room and some pushed more, the rooms move up in place, the last
/// first; a piece that filled less than its room (a face of fewer than three corners) has its
/// values gathered anew.
pub fn join_rooms<T: Copy + Default>(values: &mut Vec<T>, start: usize, rooms: &[Filled<T>]) {
    let made: usize = rooms.iter().map(|r| r.room).sum();
    debug_assert_eq!(values.len(), start + made);
    if rooms
        .iter()
        .all(|r| r.filled == r.room && r.extra.is_empty())
    {
        return;
    }
    let total: usize = rooms.iter().map(|r| r.filled + r.extra.len()).sum();
    if rooms.iter().any(|r| r.filled < r.room) {
        let mut joined = Vec::with_capacity(total);
        let mut at = start;
        for r in rooms {
            joined.extend_from_slice(&values[at..at + r.filled]);
            joined.extend_from_slice(&r.extra);
            at += r.room;
        }
        values.truncate(start);
        values.extend_from_slice(&joined);
        return;
    }
    // Every room is full, so each piece's values start at or after its room: moving the last
    // piece first, nothing is overwritten before it has moved.
    values.resize(start + total, T::default());
    let (mut room_end, mut end) = (start + made, start + total);
    for r in rooms.iter().rev() {
        let room_start = room_end - r.room;
        let begin = end - r.filled - r.extra.len();
        values[begin + r.filled..end].copy_from_slice(&r.extra);
        values.copy_within(room_start..room_start + r.filled, begin);
        (room_end, end) = (room_start, begin);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_draws::draws;

    #[test]
    fn values_fill_the_room_then_go_past_it_in_order() {
        let mut slots = [0u32; 3];
        let mut room = Room::new(&mut slots);
        assert_eq!(room.len(), 0);
        for v in 1..=5 {
            room.push(v);
        }
        assert_eq!(room.len(), 5);
        let filled = room.into_filled();
        assert_eq!(
            (filled.room, filled.filled, filled.extra),
            (3, 3, vec![4, 5])
        );
        assert_eq!(slots, [1, 2, 3]);
    }

    #[test]
    fn joined_rooms_hold_every_piece_in_order() {
        let mut draw = draws(11);
        for case in 0..400 {
            let pieces = 1 + (draw() % 6) as usize;
            let start = (draw() % 4) as usize;
            let mut values: Vec<u32> = (0..start as u32).map(|v| 1000 + v).collect();
            // Each piece: its room, and how many values it pushes (fewer, as many or more).
            let plan: Vec<(usize, usize)> = (0..pieces)
                .map(|_| {
                    let room = (draw() % 5) as usize;
                    let pushed = match draw() % 3 {
                        0 if case % 2 == 0 => room.saturating_sub(1 + (draw() % 2) as usize),
                        1 => room + (draw() % 4) as usize,
                        _ => room,
                    };
                    (room, pushed)
                })
                .collect();
            let made: usize = plan.iter().map(|p| p.0).sum();
            values.resize(start + made, 0);
            let mut expected: Vec<u32> = values[..start].to_vec();
            let mut next = 0;
            let rooms = Room::cut(&mut values[start..], plan.iter().map(|p| p.0));
            let filled: Vec<Filled<u32>> = rooms
                .into_iter()
                .zip(&plan)
                .map(|(mut room, &(_, pushed))| {
                    for _ in 0..pushed {
                        next += 1;
                        room.push(next);
                        expected.push(next);
                    }
                    room.into_filled()
                })
                .collect();
            join_rooms(&mut values, start, &filled);
            assert_eq!(values, expected, "{plan:?}");
        }
    }
}
