//! The benchmark: the study's two experiments repeated for the three algorithms, a report that
//! sets the study's claims beside ours, and throughput figures for a single scene.
//!
//! Imports go one way, measurement → analysis → report and plot. Measurement: the scenes
//! (`experiments`, `area`), the timed renders (`runner`, `throughput`) and what they record
//! (`measurement`, `error`, `format`). `analysis` reads measurements; `report` and `plot` write
//! them out with the analysis (the report links the plots by their file names). Nothing below
//! imports anything above it.

pub mod analysis;
pub mod area;
pub mod crossover;
pub mod crossover_plot;
pub mod crossover_report;
mod error;
pub mod experiments;
mod format;
mod measurement;
pub mod plot;
pub mod report;
pub mod runner;
pub mod throughput;

pub use area::{face_count, total_face_area};
pub use error::BenchError;
pub use experiments::{Experiment, REFERENCE_PIXELS};
pub use format::number;
pub use measurement::{BenchConfig, Measurement};
pub use runner::run;
