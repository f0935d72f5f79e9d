//! rastray: build small 3D scenes, render them with a Z-buffer (Gouraud or Phong shading) or a
//! Whitted ray tracer, and compare the three.
//!
//! The pipeline is `Scene` (TOML model) → [`World`] (world-space face lists with normals) →
//! [`render::render`] → [`render::Frame`] (linear RGB) → PNG or terminal preview.
#![forbid(unsafe_code)]

pub mod atomic_file;
pub mod bench;
pub mod export;
pub mod mesh;
pub mod render;
pub mod scene;
pub mod tui;
pub mod warnings;
pub mod world;

pub use render::{Algorithm, Frame, RenderOptions, render, render_into};
pub use scene::Scene;
pub use warnings::{Warning, warnings};
pub use world::World;
