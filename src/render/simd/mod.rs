//! Arithmetic on eight f32 lanes at a time, written once for one lane or eight: the lane types
//! (`lanes`), 3-vectors of lanes (`lane_vec`), and `pow` for the specular highlight.

pub mod lane_vec;
pub mod lanes;
pub mod pow;
