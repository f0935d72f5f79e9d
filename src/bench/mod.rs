//! The benchmark: the study's two experiments repeated for the three algorithms, a report that
//! sets the study's claims beside ours, and throughput figures for a single scene.

pub mod analysis;
pub mod area;
pub mod experiments;
pub mod plot;
pub mod report;
pub mod runner;
pub mod throughput;

pub use area::{face_count, total_face_area};
pub use experiments::{Experiment, REFERENCE_PIXELS};
pub use runner::{BenchConfig, BenchError, Measurement, run};
