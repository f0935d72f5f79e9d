//! Experiment 3's heat map: one panel per way of counting the BVH build, image sizes down,
//! face counts across, each cell coloured by the fastest algorithm and labelled with its time,
//! and a black line where the ray tracer stops or starts winning (the crossover).

use std::path::Path;

use plotters::prelude::*;

use super::crossover::{BvhCount, Cell};
use super::error::BenchError;
use super::plot::{FONT, color, register_bundled_font, save_png, tick};
use crate::render::{Algorithm, Size};

/// File name of the heat map.
pub const CROSSOVER_PLOT: &str = "who-wins-where.png";
/// Width and height of the heat map, pixels.
const PLOT_SIZE: (u32, u32) = (1600, 760);
/// Room around each panel's grid, pixels: left (row labels), top (title), bottom (column labels).
const LEFT: i32 = 120;
const TOP: i32 = 80;
const BOTTOM: i32 = 110;

/// The sizes and face counts of `cells`, each once, in the order first met (the sweep's order).
fn axes(cells: &[Cell]) -> (Vec<Size>, Vec<usize>) {
    let mut sizes: Vec<Size> = Vec::new();
    let mut faces: Vec<usize> = Vec::new();
    for c in cells {
        if !sizes.contains(&c.size) {
            sizes.push(c.size);
        }
        if !faces.contains(&c.faces) {
            faces.push(c.faces);
        }
    }
    (sizes, faces)
}

/// The cell at `size` and `faces`, if measured.
fn at(cells: &[Cell], size: Size, faces: usize) -> Option<&Cell> {
    cells.iter().find(|c| c.size == size && c.faces == faces)
}

/// A paler version of `c`, for cell backgrounds that keep black text readable.
fn pale(c: RGBColor) -> RGBColor {
    let mix = |v: u8| (v as u16 + 2 * 255).div_euclid(3) as u8;
    RGBColor(mix(c.0), mix(c.1), mix(c.2))
}

/// Draws the heat map of `cells` into `dir`.
pub fn write(dir: &Path, cells: &[Cell]) -> Result<(), BenchError> {
    register_bundled_font();
    let path = dir.join(CROSSOVER_PLOT);
    let plot_error = |e: &dyn std::fmt::Display| BenchError::Plot {
        path: path.clone(),
        message: e.to_string(),
    };
    let (w, h) = PLOT_SIZE;
    let mut buffer = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, PLOT_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(&e))?;
        let panels = root.split_evenly((1, BvhCount::ALL.len()));
        for (panel, bvh) in panels.iter().zip(BvhCount::ALL) {
            draw_panel(panel, cells, bvh).map_err(|e| plot_error(&e))?;
        }
        // The legend, across the bottom.
        let y = h as i32 - 36;
        let mut x = LEFT;
        for algorithm in Algorithm::ALL {
            root.draw(&Rectangle::new(
                [(x, y - 12), (x + 28, y + 12)],
                pale(color(algorithm)).filled(),
            ))
            .map_err(|e| plot_error(&e))?;
            root.draw(&Text::new(
                format!("{} fastest", algorithm.name()),
                (x + 36, y - 10),
                (FONT, 20),
            ))
            .map_err(|e| plot_error(&e))?;
            x += 230;
        }
        root.draw(&PathElement::new(
            vec![(x, y), (x + 40, y)],
            BLACK.stroke_width(5),
        ))
        .map_err(|e| plot_error(&e))?;
        root.draw(&Text::new(
            "crossover: the ray tracer wins on one side",
            (x + 50, y - 10),
            (FONT, 20),
        ))
        .map_err(|e| plot_error(&e))?;
        root.present().map_err(|e| plot_error(&e))?;
    }
    save_png(&path, w, h, buffer)
}

/// One panel: the grid of `cells` with winners as `bvh` counts the build.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    cells: &[Cell],
    bvh: BvhCount,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (sizes, faces) = axes(cells);
    let (pw, ph) = area.dim_in_pixel();
    let grid_w = pw as i32 - LEFT - 30;
    let grid_h = ph as i32 - TOP - BOTTOM;
    let (cols, rows) = (faces.len().max(1) as i32, sizes.len().max(1) as i32);
    let (cw, rh) = (grid_w / cols, grid_h / rows);
    // Largest size on top, as a y axis grows upward.
    let cell_rect = |col: i32, row: i32| {
        let x0 = LEFT + col * cw;
        let y0 = TOP + (rows - 1 - row) * rh;
        (x0, y0, x0 + cw, y0 + rh)
    };
    area.draw(&Text::new(bvh.title(), (LEFT, 24), (FONT, 26)))?;
    for (row, &size) in sizes.iter().enumerate() {
        let (_, y0, _, y1) = cell_rect(0, row as i32);
        area.draw(&Text::new(
            size.to_string(),
            (8, (y0 + y1) / 2 - 10),
            (FONT, 18),
        ))?;
        for (col, &n) in faces.iter().enumerate() {
            let Some(cell) = at(cells, size, n) else {
                continue;
            };
            let winner = cell.winner(bvh);
            let (x0, y0, x1, y1) = cell_rect(col as i32, row as i32);
            area.draw(&Rectangle::new(
                [(x0, y0), (x1, y1)],
                pale(color(winner)).filled(),
            ))?;
            area.draw(&Rectangle::new([(x0, y0), (x1, y1)], WHITE.stroke_width(1)))?;
            let time = cell.time_ms(winner, bvh);
            area.draw(&Text::new(winner.name(), (x0 + 8, y0 + 8), (FONT, 18)))?;
            area.draw(&Text::new(
                format!("{} ms", tick(&round_ms(time))),
                (x0 + 8, y0 + 32),
                (FONT, 16),
            ))?;
        }
    }
    for (col, &n) in faces.iter().enumerate() {
        let (x0, _, x1, y1) = cell_rect(col as i32, 0);
        let label = tick(&(n as f64));
        let half_width = 5 * label.len() as i32;
        area.draw(&Text::new(
            label,
            ((x0 + x1) / 2 - half_width, y1 + 10),
            (FONT, 18),
        ))?;
    }
    let (x_mid, y_axis) = (LEFT + grid_w / 2 - 40, TOP + grid_h + 40);
    area.draw(&Text::new("faces", (x_mid, y_axis), (FONT, 20)))?;
    area.draw(&Text::new("image", (8, TOP - 30), (FONT, 20)))?;
    // The crossover: every edge between a cell the ray tracer wins and one it does not.
    let ray_wins = |col: usize, row: usize| {
        at(cells, sizes[row], faces[col]).map(|c| c.winner(bvh) == Algorithm::Ray)
    };
    let line = BLACK.stroke_width(5);
    for row in 0..sizes.len() {
        for col in 0..faces.len() {
            let here = ray_wins(col, row);
            let (x0, y0, x1, y1) = cell_rect(col as i32, row as i32);
            if col + 1 < faces.len() && differ(here, ray_wins(col + 1, row)) {
                area.draw(&PathElement::new(vec![(x1, y0), (x1, y1)], line))?;
            }
            // The row above on screen is the next size up.
            if row + 1 < sizes.len() && differ(here, ray_wins(col, row + 1)) {
                area.draw(&PathElement::new(vec![(x0, y0), (x1, y0)], line))?;
            }
        }
    }
    Ok(())
}

/// Whether two measured neighbours fall on different sides of the crossover.
fn differ(a: Option<bool>, b: Option<bool>) -> bool {
    matches!((a, b), (Some(x), Some(y)) if x != y)
}

/// `ms` to two significant digits below 10 and whole numbers above, for cell labels.
fn round_ms(ms: f64) -> f64 {
    if ms < 10.0 {
        (ms * 10.0).round() / 10.0
    } else {
        ms.round()
    }
}
