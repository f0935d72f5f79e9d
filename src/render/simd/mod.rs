//! Arithmetic on eight f32 lanes at a time, written once for one lane or eight: the lane types
//! (`lanes`), 3-vectors of lanes (`lane_vec`), and `pow` for the specular highlight.

mod lane_vec;
mod lanes;
mod pow;

pub(crate) use lane_vec::V3;
pub(crate) use lanes::{F32x8, Lanes, WIDTH, load};
pub(crate) use pow::pow;
