//! How many terminal cells a picture covers and how many pixels that is.

/// Size of one terminal cell in screen pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellSize {
    /// Width in pixels, at least 1.
    pub width: u32,
    /// Height in pixels, at least 1.
    pub height: u32,
}

impl Default for CellSize {
    /// 10×20 pixels: the usual cell when the terminal does not say.
    fn default() -> CellSize {
        CellSize {
            width: 10,
            height: 20,
        }
    }
}

/// Most pixels a pixel protocol renders, whatever the cell area: 4 M pixels (2560×1600).
pub const PIXEL_BUDGET: u64 = 4_000_000;

/// A rectangle of terminal cells a picture fills.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellArea {
    /// Columns, at least 1.
    pub cols: u32,
    /// Rows, at least 1.
    pub rows: u32,
}

impl CellArea {
    /// The area `cols` wide whose rows make a picture of `aspect` (width / height) on cells of
    /// `cell` pixels.
    pub fn for_aspect(cols: u32, aspect: f32, cell: CellSize) -> CellArea {
        let cols = cols.max(1);
        let picture_height = cols as f32 * cell.width as f32 / aspect.max(f32::EPSILON);
        let rows = (picture_height / cell.height as f32).round().max(1.0) as u32;
        CellArea { cols, rows }
    }

    /// Pixel size for a pixel protocol: the area at `cell` pixels per cell, scaled down to at
    /// most [`PIXEL_BUDGET`] pixels.
    pub fn pixels(self, cell: CellSize) -> (u32, u32) {
        self.pixels_within(cell, PIXEL_BUDGET)
    }

    /// Pixel size for a pixel protocol: the area at `cell` pixels per cell, scaled down with
    /// its aspect kept to at most `budget` pixels.
    pub fn pixels_within(self, cell: CellSize, budget: u64) -> (u32, u32) {
        let (w, h) = (
            u64::from(self.cols) * u64::from(cell.width.max(1)),
            u64::from(self.rows) * u64::from(cell.height.max(1)),
        );
        if w * h <= budget {
            return (w as u32, h as u32);
        }
        let scale = (budget as f64 / (w * h) as f64).sqrt();
        let fit = |v: u64| ((v as f64 * scale).floor() as u32).max(1);
        (fit(w), fit(h))
    }

    /// Pixel size for half blocks: one pixel per column, two per row.
    pub fn half_block_pixels(self) -> (u32, u32) {
        (self.cols, self.rows * 2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_follow_the_aspect_on_two_to_one_cells() {
        let area = CellArea::for_aspect(80, 16.0 / 9.0, CellSize::default());
        // 80 cells × 10 px = 800 px wide → 450 px high → 22.5 cells of 20 px.
        assert_eq!(area, CellArea { cols: 80, rows: 23 });
        assert_eq!(area.pixels(CellSize::default()), (800, 460));
        assert_eq!(area.half_block_pixels(), (80, 46));
    }

    #[test]
    fn pixel_size_stays_within_the_budget() {
        let area = CellArea {
            cols: 1000,
            rows: 500,
        };
        let (w, h) = area.pixels(CellSize::default());
        assert!(u64::from(w) * u64::from(h) <= PIXEL_BUDGET);
        assert!((w as f32 / h as f32 - 1.0).abs() < 0.01, "{w}x{h}");
    }
}
