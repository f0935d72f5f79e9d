//! The two line plots of the report, drawn with plotters into a pixel buffer and saved as PNG.
//! The font is DejaVu Sans, bundled in the binary, so no system font is needed.

use std::path::Path;

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;

use super::analysis::series;
use super::error::BenchError;
use super::experiments::Experiment;
use super::measurement::Measurement;
use crate::atomic_file::write_atomically;
use crate::render::{Algorithm, Size};

/// File name of the time-against-area plot.
pub const AREA_PLOT: &str = "time-vs-area.png";
/// File name of the time-against-faces plot.
pub const FACES_PLOT: &str = "time-vs-faces.png";
/// Width and height of both plots, pixels.
pub const PLOT_SIZE: (u32, u32) = (1200, 800);

pub(super) use crate::bundled_font::{FONT, register_bundled_font};
/// The study's crossover areas, Mpx, drawn as vertical guides on the area plot.
const STUDY_MARKS: [(f64, &str); 2] = [
    (3.28, "study: ray overtakes Z-buffer"),
    (3.68, "study: Phong overtakes Gouraud"),
];

/// Line colour of each algorithm.
pub(super) fn color(algorithm: Algorithm) -> RGBColor {
    match algorithm {
        Algorithm::Gouraud => RGBColor(31, 119, 180),
        Algorithm::Phong => RGBColor(255, 127, 14),
        Algorithm::Ray => RGBColor(44, 160, 44),
    }
}

/// Draws both plots of `results` (measured at `size`) into `dir`.
pub fn write(dir: &Path, results: &[Measurement], size: Size) -> Result<(), BenchError> {
    register_bundled_font();
    let lines = |e| -> Vec<(Algorithm, Vec<(f64, f64)>)> {
        Algorithm::ALL
            .into_iter()
            .map(|a| (a, series(results, e, a, size)))
            .collect()
    };
    let area = lines(Experiment::Area);
    let faces = lines(Experiment::Faces);
    let (x_hi, y_hi) = extent(&area);
    draw(
        &dir.join(AREA_PLOT),
        &format!("Time against total face area ({size}, few faces)"),
        "total face area (Mpx at 1920×1080)",
        0.0..x_hi.max(STUDY_MARKS[1].0) * 1.05,
        0.0..y_hi * 1.1,
        &area,
        &STUDY_MARKS,
    )?;
    let (f_lo, f_hi, t_lo, t_hi) = log_extent(&faces);
    draw(
        &dir.join(FACES_PLOT),
        &format!("Time against face count ({size}, constant area)"),
        "faces (log scale)",
        (decade_below(f_lo)..f_hi * 1.25).log_scale(),
        (decade_below(t_lo)..t_hi * 1.25).log_scale(),
        &faces,
        &[],
    )
}

/// The power of ten at or below `v` (> 0): log axes that start on one get labels all along.
fn decade_below(v: f64) -> f64 {
    10f64.powf(v.log10().floor())
}

/// An axis label: 1.5, 20, 300, 40k, 1M.
pub(super) fn tick(value: &f64) -> String {
    let v = *value;
    let trimmed = |x: f64, suffix: &str| {
        let text = format!("{x:.1}");
        format!("{}{suffix}", text.trim_end_matches(".0"))
    };
    if v.abs() >= 1e6 {
        trimmed(v / 1e6, "M")
    } else if v.abs() >= 1e4 {
        trimmed(v / 1e3, "k")
    } else {
        trimmed(v, "")
    }
}

/// Largest x and y over all lines (1 when there are none).
fn extent(lines: &[(Algorithm, Vec<(f64, f64)>)]) -> (f64, f64) {
    let points = lines.iter().flat_map(|l| l.1.iter());
    let x = points.clone().map(|p| p.0).fold(0.0, f64::max);
    let y = points.map(|p| p.1).fold(0.0, f64::max);
    (if x > 0.0 { x } else { 1.0 }, if y > 0.0 { y } else { 1.0 })
}

/// Smallest and largest positive x and y over all lines, for log axes.
fn log_extent(lines: &[(Algorithm, Vec<(f64, f64)>)]) -> (f64, f64, f64, f64) {
    let points: Vec<(f64, f64)> = lines
        .iter()
        .flat_map(|l| l.1.iter().copied())
        .filter(|p| p.0 > 0.0 && p.1 > 0.0)
        .collect();
    if points.is_empty() {
        return (1.0, 10.0, 1.0, 10.0);
    }
    let lo = |f: fn(&(f64, f64)) -> f64| points.iter().map(f).fold(f64::INFINITY, f64::min);
    let hi = |f: fn(&(f64, f64)) -> f64| points.iter().map(f).fold(0.0, f64::max);
    (lo(|p| p.0), hi(|p| p.0), lo(|p| p.1), hi(|p| p.1))
}

/// Draws one plot of median time (ms) against `x` with one line per algorithm and vertical guides
/// at `marks`, and saves it as a PNG of [`PLOT_SIZE`].
fn draw<X, Y>(
    path: &Path,
    title: &str,
    x_label: &str,
    x_range: X,
    y_range: Y,
    lines: &[(Algorithm, Vec<(f64, f64)>)],
    marks: &[(f64, &str)],
) -> Result<(), BenchError>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let plot_error = |e: &dyn std::fmt::Display| BenchError::Plot {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    let (w, h) = PLOT_SIZE;
    let mut buffer = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut buffer, PLOT_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_error(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FONT, 30))
            .margin(20)
            .x_label_area_size(60)
            .y_label_area_size(80)
            .build_cartesian_2d(x_range, y_range)
            .map_err(|e| plot_error(&e))?;
        chart
            .configure_mesh()
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .y_labels(12)
            .x_desc(x_label)
            .y_desc("median render time (ms)")
            .label_style((FONT, 18))
            .axis_desc_style((FONT, 20))
            .draw()
            .map_err(|e| plot_error(&e))?;
        for &(algorithm, ref points) in lines {
            let style = color(algorithm).stroke_width(3);
            chart
                .draw_series(LineSeries::new(points.iter().copied(), style))
                .map_err(|e| plot_error(&e))?
                .label(algorithm.name())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], color(algorithm).stroke_width(3))
                });
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|&p| Circle::new(p, 5, color(algorithm).filled())),
                )
                .map_err(|e| plot_error(&e))?;
        }
        let y_bounds = chart.y_range();
        for (i, &(x, label)) in marks.iter().enumerate() {
            let grey = RGBColor(120 + 60 * i as u8, 120, 120).stroke_width(2);
            chart
                .draw_series(LineSeries::new(
                    [(x, y_bounds.start), (x, y_bounds.end)],
                    grey,
                ))
                .map_err(|e| plot_error(&e))?
                .label(format!("{label} ({x} Mpx)"))
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], grey));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .label_font((FONT, 18))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| plot_error(&e))?;
        root.present().map_err(|e| plot_error(&e))?;
    }
    save_png(path, w, h, buffer)
}

/// Encodes `buffer` (`w`×`h` RGB pixels) as PNG and writes it to `path` atomically.
pub(super) fn save_png(path: &Path, w: u32, h: u32, buffer: Vec<u8>) -> Result<(), BenchError> {
    let image = image::RgbImage::from_raw(w, h, buffer).expect("the buffer holds w·h RGB pixels");
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| BenchError::Plot {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
    write_atomically(path, &png).map_err(|source| BenchError::Write {
        path: path.to_path_buf(),
        source,
    })
}
