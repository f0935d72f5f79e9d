//! What the sweeps measure: the configuration of a run and one algorithm's timings on one
//! scene. The analysis, the report and the plots read these; this module reads none of them.

use super::experiments::Experiment;
use crate::render::{Algorithm, Size};

/// What one sweep run measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BenchConfig {
    /// Image size of every render.
    pub size: Size,
    /// Timed renders per point and algorithm, ≥ 1.
    pub reps: u32,
    /// Fewer points, for a first look and for CI.
    pub quick: bool,
}

/// One algorithm on one scene: timing summary over the repetitions.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurement {
    pub experiment: Experiment,
    pub algorithm: Algorithm,
    /// Triangles in the scene.
    pub faces: usize,
    /// Total projected face area, square pixels, overdraw included.
    pub area_px: f64,
    /// Median render time, milliseconds.
    pub median_ms: f64,
    /// Fastest render, milliseconds.
    pub min_ms: f64,
    /// Slowest render, milliseconds.
    pub max_ms: f64,
}
