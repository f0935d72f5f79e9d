//! Rendering into a reused frame: every pixel is rewritten, so the result is the fresh render's,
//! whatever the frame held before and whatever its size was.

mod common;

use glam::Vec3;
use rastray::render::{Algorithm, Frame, Progress, RenderOptions};
use rastray::{render, render_into};

#[test]
fn a_reused_frame_is_rewritten_to_the_last_bit() {
    let scene = common::default_scene();
    let world = common::world(&scene);
    let progress = Progress::new();
    for algorithm in Algorithm::ALL {
        for samples in [1, 2] {
            let options = RenderOptions {
                samples,
                ..RenderOptions::new(algorithm, 96, 54)
            };
            let fresh = render(&world, &scene.camera, &options, &progress).expect("render");
            // A frame of the same size full of NaN: any pixel left unwritten shows.
            let mut reused = Frame::filled(96, 54, Vec3::NAN);
            render_into(&world, &scene.camera, &options, &progress, &mut reused).expect("render");
            let bits = |f: &Frame| -> Vec<[u32; 3]> {
                f.pixels
                    .iter()
                    .map(|p| p.to_array().map(f32::to_bits))
                    .collect()
            };
            assert_eq!(
                bits(&reused),
                bits(&fresh),
                "{algorithm}, {samples}x{samples}"
            );
            // A frame of another size takes the new size.
            let mut other = Frame::filled(7, 5, Vec3::NAN);
            render_into(&world, &scene.camera, &options, &progress, &mut other).expect("render");
            assert_eq!((other.width, other.height), (96, 54));
            assert_eq!(bits(&other), bits(&fresh), "{algorithm}, resized");
        }
    }
}
