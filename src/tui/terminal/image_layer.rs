//! The pictures drawn over the cells in real pixels (kitty, sixel, iTerm2), and what is on the
//! screen now, so that a picture is sent only when it changed and a kitty image is deleted when
//! its place goes back to cells.
//!
//! The cells under a picture are blank in ratatui's buffer (see `view::picture`), so ratatui
//! leaves them alone from frame to frame and the picture stays. Anything that rewrites those
//! cells (an overlay, a motion frame in half blocks, a resize) takes the picture off this layer
//! first, and it is sent again when it comes back.
//!
//! Inside tmux, in kitty 0.28 or later, kitty pictures are Unicode placeholders instead: each
//! slot's image keeps one id ([`placeholder_id`]), is sent with a virtual placement, and the view
//! writes the placeholder cells (see `view::picture`), which tmux keeps with the pane.

use ratatui::layout::Rect;

use super::graphics::Graphics;
use crate::terminal_image::preview::PreviewImage;
use crate::terminal_image::{CellArea, Protocol, kitty, kitty_placeholder, passthrough};

/// Focus reporting on and off (DEC private mode 1004): the terminal, or tmux, sends `CSI I` when
/// the pane gains the focus and `CSI O` when it loses it.
const FOCUS_REPORTS_ON: &[u8] = b"\x1b[?1004h";
const FOCUS_REPORTS_OFF: &[u8] = b"\x1b[?1004l";

/// Slots a picture can take: the main preview and the three compare panes.
const SLOTS: usize = 4;

/// The 256-colour index that gives `slot`'s placeholder cells their image: the slot plus one.
pub fn placeholder_colour(slot: usize) -> u8 {
    slot as u8 + 1
}

/// The kitty image id of `slot`'s picture drawn with Unicode placeholders whose most significant
/// id byte is `high`.
pub fn placeholder_id(slot: usize, high: u8) -> u32 {
    kitty_placeholder::id(placeholder_colour(slot), high)
}

/// One picture to show: its slot (0 the main preview, 1..=3 the compare panes), its cells, its
/// image.
#[derive(Debug, Clone, Copy)]
pub struct Placement<'a> {
    pub slot: usize,
    pub area: Rect,
    pub image: &'a PreviewImage,
}

/// A picture on the screen.
#[derive(Debug, Clone)]
struct Placed {
    slot: usize,
    area: Rect,
    image: PreviewImage,
    /// The kitty image id.
    id: u32,
}

/// The pictures on the screen and how to draw more.
#[derive(Debug, Clone, Default)]
pub struct ImageLayer {
    graphics: Graphics,
    placed: Vec<Placed>,
    next_id: u32,
    /// Deletions of pictures forgotten by [`ImageLayer::invalidate`], sent with the next frame.
    deletes: Vec<u8>,
}

impl ImageLayer {
    /// A layer drawing with `graphics` (nothing at all for half blocks).
    pub fn new(graphics: Graphics) -> ImageLayer {
        ImageLayer {
            graphics,
            placed: Vec::new(),
            next_id: 1,
            deletes: Vec::new(),
        }
    }

    /// The bytes that make the screen show `wanted` after a frame of cells: new or changed
    /// pictures are sent, kitty images no longer wanted are deleted; pictures already shown
    /// cost nothing. A picture that cannot be encoded is left out.
    pub fn frame(&mut self, wanted: &[Placement]) -> Vec<u8> {
        let Some(protocol) = self.graphics.protocol else {
            return Vec::new();
        };
        let mut out = std::mem::take(&mut self.deletes);
        let mut kept = Vec::with_capacity(wanted.len());
        for p in wanted {
            let same = self
                .placed
                .iter()
                .position(|q| q.slot == p.slot && q.area == p.area && q.image == *p.image);
            if let Some(i) = same {
                kept.push(self.placed.swap_remove(i));
                continue;
            }
            let id = match self.graphics.placeholders {
                Some(high) => placeholder_id(p.slot, high),
                None => {
                    let id = self.next_id;
                    self.next_id = self.next_id.wrapping_add(1).max(1);
                    id
                }
            };
            if let Ok(bytes) = self.place(protocol, p, id) {
                out.extend_from_slice(&bytes);
                kept.push(Placed {
                    slot: p.slot,
                    area: p.area,
                    image: p.image.clone(),
                    id,
                });
            }
        }
        // What is left was replaced or is no longer wanted; a placeholder picture replaced in
        // its slot kept its id, and sending it again replaced the image.
        if protocol == Protocol::Kitty {
            for gone in &self.placed {
                if !kept.iter().any(|k| k.id == gone.id) {
                    out.extend_from_slice(&self.wrap(&kitty::delete(gone.id)));
                }
            }
        }
        self.placed = kept;
        out
    }

    /// Forgets what is on the screen (the terminal was cleared or resized): every picture is
    /// sent again with the next frame, and kitty images are deleted first.
    pub fn invalidate(&mut self) {
        let placed = std::mem::take(&mut self.placed);
        if self.graphics.protocol == Some(Protocol::Kitty) {
            for p in placed {
                let delete = self.wrap(&kitty::delete(p.id));
                self.deletes.extend_from_slice(&delete);
            }
        }
    }

    /// The bytes that start what the layer needs from the terminal: focus reports where
    /// pictures leave with the focus ([`Graphics::hides_unfocused`]), else nothing.
    pub fn enter(&self) -> Vec<u8> {
        match self.graphics.hides_unfocused {
            true => FOCUS_REPORTS_ON.to_vec(),
            false => Vec::new(),
        }
    }

    /// The pane lost the focus, perhaps to another tmux window, where tmux passes nothing on:
    /// where pictures leave with the focus, the bytes that delete those on the screen, for the
    /// outer terminal itself (not wrapped for tmux), and the layer forgets them so that they are
    /// sent again when wanted; else nothing.
    pub fn hide(&mut self) -> Vec<u8> {
        if !self.graphics.hides_unfocused {
            return Vec::new();
        }
        let placed = std::mem::take(&mut self.placed);
        placed.iter().flat_map(|p| kitty::delete(p.id)).collect()
    }

    /// The bytes that take every picture off the screen before the editor leaves: kitty images
    /// are deleted (those of placeholders by id, as deleting all leaves virtual placements);
    /// sixel and iTerm2 pictures are cells, cleared with the screen.
    pub fn cleanup(&self) -> Vec<u8> {
        match self.graphics.protocol {
            Some(Protocol::Kitty) => match self.graphics.placeholders {
                Some(high) => {
                    let deletes: Vec<u8> = (0..SLOTS)
                        .flat_map(|slot| kitty::delete(placeholder_id(slot, high)))
                        .collect();
                    self.wrap(&deletes)
                }
                None if self.graphics.hides_unfocused => {
                    [&self.wrap(kitty::DELETE_ALL), FOCUS_REPORTS_OFF].concat()
                }
                None => self.wrap(kitty::DELETE_ALL),
            },
            Some(_) => b"\x1b[2J".to_vec(),
            None => Vec::new(),
        }
    }

    /// The bytes that draw `p` with `protocol` as kitty image `id`: the cursor moved to the
    /// area's top-left cell, then the picture; or, with placeholders, the image and its virtual
    /// placement alone (at most [`kitty_placeholder::MAX_CELLS`] a side).
    fn place(
        &self,
        protocol: Protocol,
        p: &Placement,
        id: u32,
    ) -> Result<Vec<u8>, image::ImageError> {
        let cells = CellArea {
            cols: u32::from(p.area.width.max(1)),
            rows: u32::from(p.area.height.max(1)),
        };
        if self.graphics.placeholders.is_some() {
            let most = u32::from(kitty_placeholder::MAX_CELLS);
            let cells = CellArea {
                cols: cells.cols.min(most),
                rows: cells.rows.min(most),
            };
            return Ok(self.wrap(&kitty::encode_virtual(p.image, cells, id)?));
        }
        // Kitty and iTerm2 stretch the picture over the cells; sixel draws it at its own size,
        // centred in them when the pixel budget made it smaller.
        let (at_x, at_y) = match protocol {
            Protocol::Sixel => {
                let cell = self.graphics.cell;
                let spare = |cells: u16, size: u32, pixels: u32| {
                    ((u32::from(cells) * size).saturating_sub(pixels) / 2 / size.max(1)) as u16
                };
                (
                    p.area.x + spare(p.area.width, cell.width, p.image.width),
                    p.area.y + spare(p.area.height, cell.height, p.image.height),
                )
            }
            _ => (p.area.x, p.area.y),
        };
        let pieces = match protocol {
            Protocol::Kitty => kitty::encode_pieces(p.image, cells, Some(id))?,
            other => vec![other.encode(p.image, cells)?],
        };
        let mut out = Vec::new();
        match self.graphics.tmux_pane {
            None => {
                out.extend_from_slice(format!("\x1b[{};{}H", at_y + 1, at_x + 1).as_bytes());
                pieces.iter().for_each(|piece| out.extend_from_slice(piece));
            }
            // Passthrough reaches the outer terminal, whose cursor tmux puts back where it
            // wants after each passthrough sequence: the cursor move (in the outer terminal's
            // cells), the picture and the cursor's return travel in one.
            Some((left, top)) => {
                let mut inner =
                    format!("\x1b7\x1b[{};{}H", top + at_y + 1, left + at_x + 1).into_bytes();
                pieces
                    .iter()
                    .for_each(|piece| inner.extend_from_slice(piece));
                inner.extend_from_slice(b"\x1b8");
                out.extend_from_slice(&passthrough::tmux(&inner));
            }
        }
        Ok(out)
    }

    /// `bytes` as the terminal must receive them: through tmux when inside it.
    fn wrap(&self, bytes: &[u8]) -> Vec<u8> {
        match self.graphics.tmux_pane {
            Some(_) => passthrough::tmux(bytes),
            None => bytes.to_vec(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::terminal_image::CellSize;

    fn kitty_layer() -> ImageLayer {
        ImageLayer::new(Graphics {
            protocol: Some(Protocol::Kitty),
            cells: crate::terminal_image::GlyphSet::HalfBlock,
            cell: CellSize::default(),
            ..Graphics::default()
        })
    }

    fn image(v: u8) -> PreviewImage {
        PreviewImage {
            width: 2,
            height: 2,
            pixels: vec![[v; 3]; 4],
        }
    }

    #[test]
    fn a_picture_is_sent_once_replaced_when_it_changes_and_deleted_when_gone() {
        let mut layer = kitty_layer();
        let area = Rect::new(3, 2, 10, 5);
        let (a, b) = (image(10), image(200));
        let first = String::from_utf8(layer.frame(&[Placement {
            slot: 0,
            area,
            image: &a,
        }]))
        .unwrap();
        assert!(
            first.starts_with("\x1b[3;4H\x1b_Ga=T,f=100,q=2,i=1,C=1,c=10,r=5,"),
            "{first:?}"
        );
        let again = layer.frame(&[Placement {
            slot: 0,
            area,
            image: &a,
        }]);
        assert!(again.is_empty(), "an unchanged picture costs nothing");
        let changed = String::from_utf8(layer.frame(&[Placement {
            slot: 0,
            area,
            image: &b,
        }]))
        .unwrap();
        assert!(changed.contains("i=2,") && changed.ends_with("\x1b_Ga=d,d=I,i=1,q=2\x1b\\"));
        let gone = layer.frame(&[]);
        assert_eq!(gone, kitty::delete(2));
        assert_eq!(layer.cleanup(), kitty::DELETE_ALL);
    }

    #[test]
    fn inside_tmux_everything_passes_through_at_the_pane_offset() {
        let mut layer = ImageLayer::new(Graphics {
            tmux_pane: Some((40, 1)),
            ..kitty_layer().graphics
        });
        let a = image(10);
        let bytes = layer.frame(&[Placement {
            slot: 0,
            area: Rect::new(3, 2, 10, 5),
            image: &a,
        }]);
        let text = String::from_utf8(bytes).unwrap();
        // One passthrough: the cursor move, the picture and the cursor's return together.
        assert!(
            text.starts_with("\x1bPtmux;\x1b\x1b7\x1b\x1b[4;44H\x1b\x1b_Ga=T"),
            "{text:?}"
        );
        assert!(text.ends_with("\x1b\x1b8\x1b\\"), "{text:?}");
        assert_eq!(text.matches("\x1bPtmux;").count(), 1, "{text:?}");
    }

    #[test]
    fn placeholders_send_a_virtual_placement_under_one_id_a_slot_and_delete_by_id() {
        let mut layer = ImageLayer::new(Graphics {
            tmux_pane: Some((40, 1)),
            placeholders: Some(7),
            ..kitty_layer().graphics
        });
        let id = placeholder_id(0, 7);
        assert_eq!(id, (7 << 24) | 1);
        let area = Rect::new(3, 2, 10, 5);
        let (a, b) = (image(10), image(200));
        let first = layer.frame(&[Placement {
            slot: 0,
            area,
            image: &a,
        }]);
        let text = String::from_utf8(first).unwrap();
        let head = format!("\x1bPtmux;\x1b\x1b_Ga=T,U=1,f=100,q=2,i={id},c=10,r=5,");
        assert!(text.starts_with(&head), "{text:?}");
        assert!(
            !text.contains("\x1b\x1b[") && !text.contains("\x1b\x1b7"),
            "{text:?}"
        );
        // Another picture in the same slot replaces the image under the same id: no delete.
        let changed = String::from_utf8(layer.frame(&[Placement {
            slot: 0,
            area,
            image: &b,
        }]))
        .unwrap();
        assert!(changed.contains(&format!("i={id},")) && !changed.contains("a=d"));
        let gone = layer.frame(&[]);
        assert_eq!(gone, passthrough::tmux(&kitty::delete(id)));
        // On quit every slot's id is deleted; `d=A` would leave virtual placements.
        let cleanup = String::from_utf8(layer.cleanup()).unwrap();
        for slot in 0..SLOTS {
            assert!(cleanup.contains(&format!("d=I,i={},", placeholder_id(slot, 7))));
        }
        assert!(!cleanup.contains("d=A"), "{cleanup:?}");
    }

    #[test]
    fn where_pictures_leave_with_the_focus_hiding_deletes_them_for_the_outer_terminal() {
        let mut layer = ImageLayer::new(Graphics {
            tmux_pane: Some((0, 0)),
            hides_unfocused: true,
            ..kitty_layer().graphics
        });
        assert_eq!(layer.enter(), b"\x1b[?1004h");
        let a = image(10);
        let wanted = [Placement {
            slot: 0,
            area: Rect::new(3, 2, 10, 5),
            image: &a,
        }];
        assert!(!layer.frame(&wanted).is_empty());
        // Not wrapped: written to tmux's client terminal, past tmux.
        assert_eq!(layer.hide(), kitty::delete(1));
        assert!(layer.hide().is_empty(), "forgotten once deleted");
        assert!(
            layer.frame(&wanted).starts_with(b"\x1bPtmux;"),
            "sent again"
        );
        assert!(layer.cleanup().ends_with(b"\x1b[?1004l"));
        // Elsewhere nothing changes: no focus reports, nothing to hide.
        let mut plain = kitty_layer();
        assert!(plain.enter().is_empty());
        assert!(!plain.frame(&wanted).is_empty());
        assert!(plain.hide().is_empty());
        assert_eq!(plain.cleanup(), kitty::DELETE_ALL);
    }

    #[test]
    fn a_sixel_smaller_than_its_cells_is_centred_in_them() {
        let mut layer = ImageLayer::new(Graphics {
            protocol: Some(Protocol::Sixel),
            ..kitty_layer().graphics
        });
        // 10×5 cells of 10×20 pixels are 100×100 pixels; the picture is 50×60.
        let small = PreviewImage {
            width: 50,
            height: 60,
            pixels: vec![[9; 3]; 3000],
        };
        let bytes = layer.frame(&[Placement {
            slot: 0,
            area: Rect::new(4, 3, 10, 5),
            image: &small,
        }]);
        // 25 pixels spare on the left are 2 whole cells; 20 above are 1.
        assert!(bytes.starts_with(b"\x1b[5;7H\x1bP"), "{:?}", &bytes[..12]);
        assert_eq!(layer.cleanup(), b"\x1b[2J");
    }

    #[test]
    fn half_blocks_draw_no_picture() {
        let mut layer = ImageLayer::new(Graphics::default());
        let a = image(1);
        let wanted = [Placement {
            slot: 0,
            area: Rect::new(0, 0, 2, 1),
            image: &a,
        }];
        assert!(layer.frame(&wanted).is_empty());
        assert!(layer.cleanup().is_empty());
    }
}
