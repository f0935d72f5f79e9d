//! Cheap preview frames while keys are arriving, the exact frame once they stop.
//!
//! A truecolor cell costs up to 40 bytes of escape codes, and an orbit step changes nearly every
//! cell of the picture: 40 kB a key at 160×48 cells, more than a slow link carries between keys.
//! While the user is moving the camera, [`MotionFilter`] has every pixel that changed since the
//! last exact frame drawn in the 256-colour palette instead: its escapes are half as long, and
//! its coarse steps leave most cells unchanged from one motion frame to the next, so the
//! terminal diff skips them. Pixels that did not change (the background, the still parts) keep
//! their exact colours, so the exact frame drawn when input pauses repaints only what moved.

use crate::terminal_image::preview::{ColorMode, PreviewImage};

/// Which pixels of a preview image are drawn in the 256-colour palette, row-major; `None`
/// means none (an exact frame).
pub type CoarseMask = Option<Vec<bool>>;

/// Remembers the last exact frame of one preview image, to draw cheap frames against it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MotionFilter {
    /// The image last presented exactly.
    exact: Option<PreviewImage>,
}

impl MotionFilter {
    /// The mask for drawing `image` in `mode`. `cheap` asks for a motion frame: the pixels that
    /// differ from the last exact frame go coarse. Otherwise the frame is exact and becomes the
    /// reference. In the 256-colour mode every frame is exact already.
    pub fn mask(&mut self, image: &PreviewImage, mode: ColorMode, cheap: bool) -> CoarseMask {
        match &self.exact {
            Some(exact) if cheap && mode == ColorMode::Truecolor => {
                let same_size = exact.width == image.width && exact.height == image.height;
                let mask = if same_size {
                    exact
                        .pixels
                        .iter()
                        .zip(&image.pixels)
                        .map(|(a, b)| a != b)
                        .collect()
                } else {
                    vec![true; image.pixels.len()]
                };
                Some(mask)
            }
            Some(exact) if exact == image => None,
            _ => {
                self.exact = Some(image.clone());
                None
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(pixels: &[[u8; 3]]) -> PreviewImage {
        PreviewImage {
            width: pixels.len() as u32,
            height: 1,
            pixels: pixels.to_vec(),
        }
    }

    const A: [u8; 3] = [200, 40, 40];
    const B: [u8; 3] = [12, 13, 20];
    const C: [u8; 3] = [201, 120, 37];

    #[test]
    fn changed_pixels_go_coarse_while_moving_and_the_pause_restores_them() {
        let mut filter = MotionFilter::default();
        let truecolor = ColorMode::Truecolor;
        assert_eq!(
            filter.mask(&image(&[A, B]), truecolor, true),
            None,
            "no reference yet"
        );
        let moving = filter.mask(&image(&[C, B]), truecolor, true);
        assert_eq!(
            moving,
            Some(vec![true, false]),
            "the still pixel stays exact"
        );
        assert_eq!(filter.mask(&image(&[C, B]), truecolor, false), None);
        // The exact frame is the new reference: the same image while moving is all exact.
        assert_eq!(
            filter.mask(&image(&[C, B]), truecolor, true),
            Some(vec![false, false])
        );
    }

    #[test]
    fn a_resized_image_is_all_coarse_and_256_colours_are_always_exact() {
        let mut filter = MotionFilter::default();
        filter.mask(&image(&[A]), ColorMode::Truecolor, false);
        assert_eq!(
            filter.mask(&image(&[A, A]), ColorMode::Truecolor, true),
            Some(vec![true, true])
        );
        assert_eq!(filter.mask(&image(&[C, B]), ColorMode::Ansi256, true), None);
    }
}
