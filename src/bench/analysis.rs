//! Reading the measurements: crossover points, speed ratios, and the study's claims set beside
//! ours with a verdict on each.

use super::experiments::{Experiment, REFERENCE_PIXELS};
use super::measurement::Measurement;
use crate::render::{Algorithm, Size};

/// A measured value agrees with the study's when it is within this factor of it, either way; a
/// ratio claim agrees when this holds at three quarters of the points or more.
pub const AGREEMENT_FACTOR: f64 = 1.5;
/// The area at which the study quotes Gouraud's lag behind Phong, Mpx.
pub const STUDY_LAG_AREA_MPX: f64 = 4.08;

/// One point of a series: x (area in Mpx at 1920×1080, or faces) and the median time, ms.
type Series = Vec<(f64, f64)>;

/// Where two algorithms change places along a sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// x where the times are equal (linear interpolation between the two points around it).
    pub at: f64,
    /// True when the first algorithm becomes the faster one there.
    pub first_becomes_faster: bool,
}

/// How two algorithms compare along a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    pub first: Algorithm,
    pub second: Algorithm,
    /// Whether the first algorithm is faster at the first point.
    pub first_faster_at_start: bool,
    /// Whether the first algorithm is faster at the last point.
    pub first_faster_at_end: bool,
    /// Every change of places, in sweep order.
    pub crossings: Vec<Crossing>,
}

impl Comparison {
    /// x beyond which the first algorithm stays the faster one to the end of the sweep: the last
    /// crossing, when the first ends ahead. `None` when it ends behind or was never behind.
    pub fn first_ahead_beyond(&self) -> Option<f64> {
        if !self.first_faster_at_end {
            return None;
        }
        self.crossings.last().map(|c| c.at)
    }

    /// A note on repeated crossings (noise), or nothing.
    fn noise_note(&self) -> String {
        match self.crossings.len() {
            0 | 1 => String::new(),
            n => format!(" (the curves cross {n} times: the timings are noisy)"),
        }
    }

    /// A sentence describing the comparison, x in `unit` with `decimals` digits.
    pub fn describe(&self, unit: &str, decimals: usize) -> String {
        let (a, b) = (self.first, self.second);
        if self.crossings.is_empty() {
            let (fast, slow) = if self.first_faster_at_start {
                (a, b)
            } else {
                (b, a)
            };
            return format!("{fast} is faster than {slow} at every point: no crossover.");
        }
        let steps: Vec<String> = self
            .crossings
            .iter()
            .map(|c| {
                let (fast, slow) = if c.first_becomes_faster {
                    (a, b)
                } else {
                    (b, a)
                };
                format!("{fast} overtakes {slow} at {:.decimals$} {unit}", c.at)
            })
            .collect();
        format!("{}.", steps.join("; then "))
    }
}

/// The median-time series of `algorithm` in `experiment`, x = area in Mpx scaled to 1920×1080
/// (experiment 1) or faces (experiment 2), sorted by x.
pub fn series(
    results: &[Measurement],
    experiment: Experiment,
    algorithm: Algorithm,
    size: Size,
) -> Series {
    let to_reference = REFERENCE_PIXELS / (size.width as f64 * size.height as f64);
    let mut s: Series = results
        .iter()
        .filter(|m| m.experiment == experiment && m.algorithm == algorithm)
        .map(|m| {
            let x = match experiment {
                Experiment::Area => m.area_px * to_reference / 1e6,
                Experiment::Faces => m.faces as f64,
            };
            (x, m.median_ms)
        })
        .collect();
    s.sort_by(|p, q| p.0.total_cmp(&q.0));
    s
}

/// Compares two series measured at the same x values.
pub fn compare(first: Algorithm, a: &Series, second: Algorithm, b: &Series) -> Comparison {
    let diff: Vec<(f64, f64)> = a.iter().zip(b).map(|(p, q)| (p.0, p.1 - q.1)).collect();
    let mut crossings = Vec::new();
    for w in diff.windows(2) {
        let ((x0, d0), (x1, d1)) = (w[0], w[1]);
        if (d0 < 0.0) != (d1 < 0.0) {
            let t = if d0 == d1 { 0.0 } else { d0 / (d0 - d1) };
            crossings.push(Crossing {
                at: x0 + t * (x1 - x0),
                first_becomes_faster: d1 < 0.0,
            });
        }
    }
    Comparison {
        first,
        second,
        first_faster_at_start: diff.first().is_some_and(|d| d.1 < 0.0),
        first_faster_at_end: diff.last().is_some_and(|d| d.1 < 0.0),
        crossings,
    }
}

/// Linear interpolation of a series at `x` (clamped to its ends); `None` when empty.
pub fn value_at(s: &Series, x: f64) -> Option<f64> {
    let first = s.first()?;
    if x <= first.0 {
        return Some(first.1);
    }
    for w in s.windows(2) {
        if x <= w[1].0 {
            let t = (x - w[0].0) / (w[1].0 - w[0].0);
            return Some(w[0].1 + t * (w[1].1 - w[0].1));
        }
    }
    s.last().map(|p| p.1)
}

/// Pointwise ratios `a / b` of two series measured at the same x values.
pub fn ratios(a: &Series, b: &Series) -> Vec<f64> {
    a.iter().zip(b).map(|(p, q)| p.1 / q.1).collect()
}

/// Geometric mean of positive values; `None` when empty.
pub fn geometric_mean(values: &[f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    Some((values.iter().map(|v| v.ln()).sum::<f64>() / values.len() as f64).exp())
}

/// Whether `ours` is within [`AGREEMENT_FACTOR`] of `study`.
pub fn close_to(ours: f64, study: f64) -> bool {
    ours > 0.0 && study > 0.0 && (ours / study).max(study / ours) <= AGREEMENT_FACTOR
}

/// Whether a claim holds here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    Agrees,
    Differs,
}

impl Verdict {
    /// "agrees" or "differs".
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Agrees => "agrees",
            Verdict::Differs => "differs",
        }
    }
}

/// One of the study's claims beside our measurement.
#[derive(Debug, Clone, PartialEq)]
pub struct Claim {
    /// What the study found.
    pub study: String,
    /// What we measured.
    pub ours: String,
    pub verdict: Verdict,
    /// Why ours agrees or differs.
    pub why: String,
}

/// The study's five claims, checked against `results` measured at `size`.
pub fn claims(results: &[Measurement], size: Size) -> Vec<Claim> {
    let s = |e, a| series(results, e, a, size);
    let (g1, p1, r1) = (
        s(Experiment::Area, Algorithm::Gouraud),
        s(Experiment::Area, Algorithm::Phong),
        s(Experiment::Area, Algorithm::Ray),
    );
    let (g2, p2, r2) = (
        s(Experiment::Faces, Algorithm::Gouraud),
        s(Experiment::Faces, Algorithm::Phong),
        s(Experiment::Faces, Algorithm::Ray),
    );
    vec![
        ray_overtakes(compare(Algorithm::Ray, &r1, Algorithm::Gouraud, &g1)),
        ray_overtakes(compare(Algorithm::Ray, &r1, Algorithm::Phong, &p1)),
        phong_overtakes(
            compare(Algorithm::Phong, &p1, Algorithm::Gouraud, &g1),
            &g1,
            &p1,
        ),
        ratio_claim(
            "With growing face count at constant area, Gouraud is about 2× faster than Phong.",
            2.0,
            "Phong / Gouraud",
            &ratios(&p2, &g2),
            "Phong lights every visible pixel, a constant at constant area, while Gouraud lights \
             every vertex, which grows with the face count; both share the same rasterizer and \
             triangle setup, so the ratio falls as faces are added",
        ),
        ratio_claim(
            "With growing face count at constant area, Gouraud is about 12× faster than ray tracing.",
            12.0,
            "Ray / Gouraud",
            &ratios(&r2, &g2),
            "the ray tracer's cost depends on the pixels, the depth of its BVH and its shadow and \
             reflection rays; the Z-buffer's on the triangles it sets up and the pixels it covers",
        ),
    ]
}

/// The claim that ray tracing overtakes a Z-buffer variant beyond 3.28 Mpx.
fn ray_overtakes(c: Comparison) -> Claim {
    const STUDY: f64 = 3.28;
    let zbuffer = c.second;
    let study = format!("Ray tracing overtakes {zbuffer} beyond about {STUDY} Mpx of total area.");
    let ours = c.describe("Mpx", 2);
    let noise = c.noise_note();
    match c.first_ahead_beyond() {
        Some(at) if close_to(at, STUDY) => Claim {
            study,
            ours,
            verdict: Verdict::Agrees,
            why: format!(
                "the Z-buffer's time grows with the face area it scan-converts while the ray \
                 tracer's follows the pixel count, and ray tracing stays ahead beyond {at:.2} \
                 Mpx, within ×{AGREEMENT_FACTOR} of the study's figure{noise}"
            ),
        },
        Some(at) => Claim {
            study,
            ours,
            verdict: Verdict::Differs,
            why: format!(
                "ray tracing stays ahead beyond {at:.2} Mpx, not within ×{AGREEMENT_FACTOR} of \
                 the study's figure{noise}: the cost of a covered pixel relative to the cost of a ray is not \
                 the study's (rastray's rasterizer defers shading to one pass over the visible \
                 pixels, and its ray tracer uses a BVH and several threads)"
            ),
        },
        None if c.first_faster_at_end => Claim {
            study,
            ours,
            verdict: Verdict::Differs,
            why: format!(
                "ray tracing is already faster than {zbuffer} at the smallest area: per pixel, a \
                 ray costs less here than the Z-buffer's full-screen visibility and shading \
                 passes (check that the ray tracer draws the scene at all)"
            ),
        },
        None => Claim {
            study,
            ours,
            verdict: Verdict::Differs,
            why: format!(
                "ray tracing ends slower than {zbuffer}{noise}: scan-converting a covered pixel costs \
                 {zbuffer} a few integer operations and a depth compare, with shading deferred \
                 to one pass over the visible pixels, so overdraw adds little; each ray pays a \
                 BVH traversal, triangle tests and shadow and reflection rays"
            ),
        },
    }
}

/// The claim that Gouraud falls behind Phong beyond 3.68 Mpx, 6% at 4.08 Mpx.
fn phong_overtakes(c: Comparison, gouraud: &Series, phong: &Series) -> Claim {
    const STUDY: f64 = 3.68;
    let study = format!(
        "Gouraud falls behind Phong beyond about {STUDY} Mpx (6% slower at {STUDY_LAG_AREA_MPX} Mpx)."
    );
    let lag = match (
        value_at(gouraud, STUDY_LAG_AREA_MPX),
        value_at(phong, STUDY_LAG_AREA_MPX),
    ) {
        (Some(g), Some(p)) if p > 0.0 => {
            let change = (g / p - 1.0) * 100.0;
            let word = if change > 0.0 { "more" } else { "less" };
            format!(
                " At {STUDY_LAG_AREA_MPX} Mpx Gouraud takes {:.0}% {word} time than Phong.",
                change.abs()
            )
        }
        _ => String::new(),
    };
    let ours = format!("{}{lag}", c.describe("Mpx", 2));
    let shared = "both variants share one rasterizer that resolves visibility before shading, \
                  so overdraw costs them the same and only the shading differs: Gouraud lights \
                  the vertices and interpolates a colour, Phong lights every visible pixel";
    let noise = c.noise_note();
    match c.first_ahead_beyond() {
        Some(at) if close_to(at, STUDY) => Claim {
            study,
            ours,
            verdict: Verdict::Agrees,
            why: format!("Phong stays ahead beyond {at:.2} Mpx, near the study's figure{noise}"),
        },
        Some(at) => Claim {
            study,
            ours,
            verdict: Verdict::Differs,
            why: format!(
                "Phong stays ahead beyond {at:.2} Mpx, far from the study's figure{noise}; \
                 {shared}"
            ),
        },
        None if c.first_faster_at_end => Claim {
            study,
            ours,
            verdict: Verdict::Differs,
            why: format!(
                "Phong is faster than Gouraud from the smallest area on, so Gouraud never falls \
                 behind: it was never ahead; {shared}"
            ),
        },
        None => Claim {
            study,
            ours,
            verdict: Verdict::Differs,
            why: format!(
                "Gouraud ends ahead{noise}: {shared}, so Phong's per-pixel lighting keeps \
                 it behind (the study most likely shaded fragments as they were drawn, overdraw \
                 included, which made its per-fragment work weigh differently)"
            ),
        },
    }
}

/// A claim that one algorithm takes `study`× another's time at growing face count.
fn ratio_claim(claim: &str, study: f64, label: &str, ratios: &[f64], cause: &str) -> Claim {
    let (Some(mean), Some(first), Some(last)) =
        (geometric_mean(ratios), ratios.first(), ratios.last())
    else {
        return Claim {
            study: claim.to_string(),
            ours: "not measured.".to_string(),
            verdict: Verdict::Differs,
            why: "no measurements".to_string(),
        };
    };
    let close = ratios.iter().filter(|&&r| close_to(r, study)).count();
    let ours = format!(
        "{label} = {mean:.2}× (geometric mean), from {first:.2}× at the fewest faces to \
         {last:.2}× at the most; within ×{AGREEMENT_FACTOR} of the study's at {close} of {} points.",
        ratios.len()
    );
    let (verdict, why) = if close * 4 >= ratios.len() * 3 {
        (
            Verdict::Agrees,
            format!(
                "the ratio is close to the study's at three quarters of the points or more; {cause}"
            ),
        )
    } else {
        (
            Verdict::Differs,
            format!(
                "the ratio is close to the study's at fewer than three quarters of the points: {cause}"
            ),
        )
    };
    Claim {
        study: claim.to_string(),
        ours,
        verdict,
        why,
    }
}
