//! The written results: one CSV row per measurement and a Markdown report with the tables, the
//! crossovers and the study's claims beside ours.

use std::fmt::Write as _;
use std::path::Path;

use super::analysis::{AGREEMENT_FACTOR, claims, compare, series};
use super::crossover::Cell;
use super::crossover_report;
use super::error::BenchError;
use super::experiments::Experiment;
use super::format::number;
use super::measurement::{BenchConfig, Measurement};
use super::plot::{AREA_PLOT, FACES_PLOT};
use crate::atomic_file::write_atomically;
use crate::render::Algorithm;

/// File name of the CSV results.
pub const CSV_FILE: &str = "results.csv";
/// File name of the Markdown report.
pub const REPORT_FILE: &str = "report.md";
/// The CSV header, in column order.
pub const CSV_HEADER: &str = "experiment,algorithm,faces,total_area_px,median_ms,min_ms,max_ms";

/// The CSV text of `results`: [`CSV_HEADER`] then one row per measurement.
pub fn csv(results: &[Measurement]) -> String {
    let mut out = format!("{CSV_HEADER}\n");
    for m in results {
        let _ = writeln!(
            out,
            "{},{},{},{:.0},{:.4},{:.4},{:.4}",
            m.experiment,
            m.algorithm.name().to_lowercase(),
            m.faces,
            m.area_px,
            m.median_ms,
            m.min_ms,
            m.max_ms
        );
    }
    out
}

/// The Markdown report of `results` and of experiment 3's `cells` (none: no such section)
/// measured with `config`; `machine` describes where.
pub fn markdown(
    results: &[Measurement],
    cells: &[Cell],
    config: &BenchConfig,
    machine: &str,
) -> String {
    let size = config.size;
    let mut md = String::from("# rastray benchmark\n\n");
    let _ = writeln!(
        md,
        "Image {size}, timed renders per point: {} (median shown, min–max in brackets){}. \
         Measured on: {machine}\n",
        config.reps,
        if config.quick { ", quick mode" } else { "" }
    );
    md.push_str(
        "Only the render call is timed, each algorithm rendering into its own frame kept from \
         render to render: the vertex stage, rasterization and shading for the Z-buffer; BVH \
         construction and tracing for the ray tracer. Tessellating the scene is not timed. Total \
         face area is the sum over all faces, back faces included (the Z-buffer draws \
         them), of the projected area clipped to the image.\n\n",
    );
    for experiment in Experiment::ALL {
        let _ = writeln!(md, "## {}\n", experiment.title());
        let _ = writeln!(md, "![{}]({})\n", experiment.title(), plot_file(experiment));
        md.push_str(&table(results, experiment));
        md.push('\n');
    }
    md.push_str("## Crossovers\n\n");
    let area_note = if size.width as f64 * size.height as f64 == super::REFERENCE_PIXELS {
        String::new()
    } else {
        " (areas scaled to a 1920×1080 image)".to_string()
    };
    let pairs = [
        (Algorithm::Ray, Algorithm::Gouraud),
        (Algorithm::Ray, Algorithm::Phong),
        (Algorithm::Phong, Algorithm::Gouraud),
    ];
    for experiment in Experiment::ALL {
        let (unit, decimals) = match experiment {
            Experiment::Area => ("Mpx", 2),
            Experiment::Faces => ("faces", 0),
        };
        let _ = writeln!(md, "{}{}:\n", experiment.title(), area_note);
        for (a, b) in pairs {
            let c = compare(
                a,
                &series(results, experiment, a, size),
                b,
                &series(results, experiment, b, size),
            );
            let _ = writeln!(md, "- {a} vs {b}: {}", c.describe(unit, decimals));
        }
        md.push('\n');
    }
    if !cells.is_empty() {
        md.push_str(&crossover_report::markdown(cells));
        md.push('\n');
    }
    md.push_str("## The study's claims beside ours\n\n");
    let _ = writeln!(
        md,
        "A crossover agrees when ours is within ×{AGREEMENT_FACTOR} of the study's (the last \
         crossing counts: the area beyond which one algorithm stays ahead); a speed ratio agrees \
         when it is within ×{AGREEMENT_FACTOR} of the study's at three quarters of the points or \
         more.\n"
    );
    md.push_str("| Study | rastray | Verdict | Why |\n|---|---|---|---|\n");
    for claim in claims(results, size) {
        let _ = writeln!(
            md,
            "| {} | {} | **{}** | {} |",
            claim.study,
            claim.ours,
            claim.verdict.name(),
            claim.why
        );
    }
    md
}

/// Writes [`CSV_FILE`] and [`REPORT_FILE`] into `dir`, and experiment 3's
/// [`crossover_report::CROSSOVER_CSV`] when it ran.
pub fn write(
    dir: &Path,
    results: &[Measurement],
    cells: &[Cell],
    config: &BenchConfig,
    machine: &str,
) -> Result<(), BenchError> {
    let save = |name: &str, text: String| {
        let path = dir.join(name);
        write_atomically(&path, text.as_bytes())
            .map_err(|source| BenchError::Write { path, source })
    };
    save(CSV_FILE, csv(results))?;
    if !cells.is_empty() {
        save(
            crossover_report::CROSSOVER_CSV,
            crossover_report::csv(cells),
        )?;
    }
    save(REPORT_FILE, markdown(results, cells, config, machine))
}

fn plot_file(experiment: Experiment) -> &'static str {
    match experiment {
        Experiment::Area => AREA_PLOT,
        Experiment::Faces => FACES_PLOT,
    }
}

/// One row per point: faces, area, then each algorithm's median (min–max) in ms.
fn table(results: &[Measurement], experiment: Experiment) -> String {
    let mut md = String::from("| Faces | Total area (px) | (Mpx) |");
    for a in Algorithm::ALL {
        let _ = write!(md, " {a} (ms) |");
    }
    md.push_str("\n|---:|---:|---:|");
    md.push_str(&"---:|".repeat(Algorithm::ALL.len()));
    md.push('\n');
    let rows = results
        .iter()
        .filter(|m| m.experiment == experiment && m.algorithm == Algorithm::ALL[0]);
    for first in rows {
        let _ = write!(
            md,
            "| {} | {:.0} | {:.3} |",
            first.faces,
            first.area_px,
            first.area_px / 1e6
        );
        for a in Algorithm::ALL {
            let cell = results.iter().find(|m| {
                m.experiment == experiment
                    && m.algorithm == a
                    && m.faces == first.faces
                    && m.area_px == first.area_px
            });
            match cell {
                Some(m) => {
                    let _ = write!(
                        md,
                        " {} ({}–{}) |",
                        number(m.median_ms),
                        number(m.min_ms),
                        number(m.max_ms)
                    );
                }
                None => md.push_str(" – |"),
            }
        }
        md.push('\n');
    }
    md
}
