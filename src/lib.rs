//! rastray: build small 3D scenes, render them with a Z-buffer (Gouraud or Phong shading) or a
//! Whitted ray tracer, and compare the three.
//!
//! The pipeline is [`Scene`] (the TOML model, [`scene`]) → [`World`] (world-space face lists
//! with normals, [`mesh`]) → [`Renderer`] ([`render`]) → [`Frame`] (linear RGB) → PNG,
//! OpenEXR or a turntable ([`export`]) or the terminal preview ([`tui`]). A renderer prepares a
//! world once (the ray tracer's BVH) and then renders it from any camera, into a frame you keep:
//!
//! ```
//! use std::{path::Path, sync::Arc};
//! use rastray::render::{Algorithm, Frame, Progress, RenderOptions, Renderer};
//! use rastray::{World, export, scene};
//!
//! let path = Path::new("scenes/default.toml");
//! let scene = scene::load(path)?;
//! let world = Arc::new(World::build(&scene, path.parent().unwrap())?);
//! let mut renderer = Renderer::new(RenderOptions::new(Algorithm::Ray, 320, 180));
//! let mut frame = Frame::default();
//! let stats = renderer.render(&world, &scene.camera, &Progress::new(), &mut frame)?;
//! let png = std::env::temp_dir().join("rastray-example.png");
//! export::save_image(&frame, export::ImageFormat::PNG8, &png)?;
//! println!("{} triangles, {} rays in {:?}", stats.triangles, stats.rays.total(), stats.total());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! [`export::render_to_file`] does the last five lines in one call, for an image or a
//! turntable. `docs/ARCHITECTURE.md` maps the modules.
#![deny(unsafe_code)]

pub mod atomic_file;
pub mod bench;
pub mod bundled_font;
pub mod export;
mod huge_pages;
pub mod input_file;
pub mod instance;
pub mod memory_budget;
pub mod mesh;
pub mod model_folder;
pub mod model_scene;
pub mod pool_thread;
pub mod preset_view;
pub mod render;
pub mod scene;
pub mod temporary_file;
pub mod terminal_image;
#[cfg(test)]
mod test_draws;
pub mod text_escape;
pub mod tui;
pub mod warnings;
pub mod world;

pub use render::{Algorithm, Frame, RenderOptions, RenderStats, Renderer};
pub use scene::Scene;
pub use warnings::{Warning, warnings};
pub use world::World;
