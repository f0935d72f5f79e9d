//! The bounding box's dimensions written into the image beside its edges: one length per axis,
//! at the middle of the edge of that axis that lies lowest (x and z) or leftmost (y) on the
//! screen, pushed away from the box's centre so the text does not cover the edge. Drawn on the
//! finished (filtered) frame in the bounding box's colour over a dark halo, so they read on any
//! background. Text comes from the bundled font, anti-aliased.

use glam::{Vec2, Vec3};
use plotters::prelude::*;

use super::colors;
use crate::bundled_font::{FONT, register_bundled_font};
use crate::render::Frame;
use crate::render::camera::{NEAR, View};

/// Frames lower than this, pixels, get no labels: their text could not be read.
pub const MIN_HEIGHT: u32 = 120;

/// Edges shorter than this on the screen, pixels, get no label: seen end-on they are points.
const MIN_EDGE: f32 = 24.0;

/// How much of the halo's darkness covers what lies under it, 0..1.
const HALO_OPACITY: f32 = 0.75;

/// One length to write: its text, and the point it is written beside, in pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct Label {
    pub text: String,
    /// The middle of the edge, pixels of the frame.
    pub at: Vec2,
    /// Unit direction on the screen in which the text moves away from the box.
    pub away: Vec2,
}

/// The labels of the box `(lo, hi)` (world units) seen through `view` (a whole frame, one
/// sample a pixel): one per axis whose chosen edge is in front of the camera and at least
/// [`MIN_EDGE`] pixels long on the screen. Lengths are in the scene's units, three decimals.
pub fn labels((lo, hi): (Vec3, Vec3), view: &View) -> Vec<Label> {
    let corner = |k: usize| {
        Vec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        )
    };
    let in_front = |p: Vec3| (p - view.eye).dot(view.forward) > NEAR;
    let pixel = |p: Vec3| view.clip_to_pixel(view.to_clip(p));
    if !(0..8).all(|k| in_front(corner(k))) {
        return Vec::new();
    }
    let centre = pixel((lo + hi) * 0.5);
    let size = hi - lo;
    let mut out = Vec::new();
    for (axis, bit) in [(0, 1), (1, 2), (2, 4)] {
        // The four edges along this axis (corners k and k | bit, for k without the bit), each
        // cut to the frame, long enough on the screen to be labelled.
        let frame = Vec2::new(view.width as f32, view.image_height as f32);
        let edges = (0..8)
            .filter(|k| k & bit == 0)
            .filter_map(|k| clip_to_frame(pixel(corner(k)), pixel(corner(k | bit)), frame))
            .filter(|(a, b)| a.distance(*b) >= MIN_EDGE)
            .map(|(a, b)| (a + b) * 0.5);
        let chosen = if axis == 1 {
            edges.min_by(|p, q| p.x.total_cmp(&q.x))
        } else {
            edges.max_by(|p, q| p.y.total_cmp(&q.y))
        };
        let Some(middle) = chosen else {
            continue;
        };
        out.push(Label {
            text: format!("{:.3}", size[axis]),
            at: middle,
            away: (middle - centre).try_normalize().unwrap_or(Vec2::Y),
        });
    }
    out
}

/// The part of the segment `a`–`b` inside the rectangle from the origin to `size`, pixels
/// (Liang–Barsky); `None` when none of it is.
fn clip_to_frame(a: Vec2, b: Vec2, size: Vec2) -> Option<(Vec2, Vec2)> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f32, 1.0_f32);
    for (p, q) in [
        (-d.x, a.x),
        (d.x, size.x - a.x),
        (-d.y, a.y),
        (d.y, size.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 < t1).then(|| (a + d * t0, a + d * t1))
}

/// Writes `labels` into `frame`, text `text_height` pixels high. Colours are linear; a frame
/// with alpha is premultiplied, and the text makes its pixels opaque as far as it covers them.
pub fn draw(labels: &[Label], text_height: u32, frame: &mut Frame) {
    register_bundled_font();
    let font = (FONT, text_height).into_font();
    for label in labels {
        let Ok((w, h)) = font.box_size(&label.text) else {
            continue;
        };
        // The text's coverage, 0..=255, drawn white on black with a 2-pixel margin for the halo.
        let (bw, bh) = (w + 4, h + 4);
        let mut buffer = vec![0_u8; bw as usize * bh as usize * 3];
        {
            let root = BitMapBackend::with_buffer(&mut buffer, (bw, bh)).into_drawing_area();
            let style = font.color(&WHITE);
            if root
                .draw(&Text::new(label.text.as_str(), (2, 2), style))
                .is_err()
            {
                continue;
            }
            let _ = root.present();
        }
        let coverage: Vec<f32> = buffer.chunks(3).map(|p| f32::from(p[0]) / 255.0).collect();
        // The box's top-left corner: centred on the edge's middle, moved away from the box by
        // half the box's extent along `away` and a little more.
        let half = Vec2::new(bw as f32, bh as f32) * 0.5;
        let reach = half.x * label.away.x.abs() + half.y * label.away.y.abs() + 3.0;
        // Kept inside the frame, so a label near its border is not cut.
        let top_left = (label.at + label.away * reach - half)
            .clamp(
                Vec2::ZERO,
                Vec2::new(
                    frame.width.saturating_sub(bw) as f32,
                    frame.height.saturating_sub(bh) as f32,
                ),
            )
            .round();
        let halo = |x: i64, y: i64| {
            let mut most = 0.0_f32;
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (sx, sy) = (x + dx, y + dy);
                    if sx >= 0 && sy >= 0 && sx < i64::from(bw) && sy < i64::from(bh) {
                        most = most.max(coverage[(sy * i64::from(bw) + sx) as usize]);
                    }
                }
            }
            most
        };
        for y in 0..i64::from(bh) {
            for x in 0..i64::from(bw) {
                let (fx, fy) = (top_left.x as i64 + x, top_left.y as i64 + y);
                if fx < 0 || fy < 0 || fx >= i64::from(frame.width) || fy >= i64::from(frame.height)
                {
                    continue;
                }
                let i = (fy * i64::from(frame.width) + fx) as usize;
                let ink = coverage[(y * i64::from(bw) + x) as usize];
                over(frame, i, Vec3::ZERO, HALO_OPACITY * halo(x, y));
                over(frame, i, colors::BOUNDS, ink);
            }
        }
    }
}

/// Puts `color` at `opacity` over pixel `i` of `frame` (premultiplied when it has alpha).
fn over(frame: &mut Frame, i: usize, color: Vec3, opacity: f32) {
    if opacity <= 0.0 {
        return;
    }
    frame.pixels[i] = color * opacity + frame.pixels[i] * (1.0 - opacity);
    if let Some(alpha) = frame.alpha.as_mut() {
        alpha[i] = opacity + alpha[i] * (1.0 - opacity);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Camera;

    fn front_view(width: u32, height: u32) -> View {
        let camera = Camera {
            position: Vec3::new(0.6, 0.8, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        };
        View::new(&camera, width, height)
    }

    #[test]
    fn each_axis_is_labelled_with_its_length_beside_an_outer_edge() {
        let bounds = (Vec3::new(-1.0, -0.25, -0.5), Vec3::new(1.0, 0.25, 0.5));
        let view = front_view(400, 300);
        let labels = labels(bounds, &view);
        let texts: Vec<&str> = labels.iter().map(|l| l.text.as_str()).collect();
        assert_eq!(texts, ["2.000", "0.500", "1.000"]);
        let centre = view.clip_to_pixel(view.to_clip(Vec3::ZERO));
        // x and z below the box's centre, y to its left.
        assert!(labels[0].at.y > centre.y && labels[0].away.y > 0.0);
        assert!(labels[1].at.x < centre.x && labels[1].away.x < 0.0);
        assert!(labels[2].at.y > centre.y);
    }

    #[test]
    fn an_edge_seen_end_on_gets_no_label() {
        let camera = Camera {
            position: Vec3::new(0.0, 0.0, 4.0),
            target: Vec3::ZERO,
            ..Camera::default()
        };
        let view = View::new(&camera, 400, 300);
        let labels = labels((Vec3::splat(-0.5), Vec3::splat(0.5)), &view);
        let texts: Vec<&str> = labels.iter().map(|l| l.text.as_str()).collect();
        assert_eq!(texts, ["1.000", "1.000"], "x and y; z is seen end-on");
    }

    #[test]
    fn edges_are_cut_to_the_frame() {
        let size = Vec2::new(100.0, 50.0);
        let (a, b) = clip_to_frame(Vec2::new(-50.0, 25.0), Vec2::new(50.0, 25.0), size).unwrap();
        assert_eq!((a, b), (Vec2::new(0.0, 25.0), Vec2::new(50.0, 25.0)));
        assert!(clip_to_frame(Vec2::new(-5.0, -5.0), Vec2::new(-1.0, 60.0), size).is_none());
    }

    #[test]
    fn text_is_drawn_in_the_box_colour_over_a_dark_halo() {
        let mut frame = Frame::filled(200, 100, Vec3::splat(0.5));
        let label = Label {
            text: "1.000".into(),
            at: Vec2::new(100.0, 50.0),
            away: Vec2::Y,
        };
        draw(&[label], 24, &mut frame);
        let near = |p: Vec3, q: Vec3| (p - q).abs().max_element() < 0.02;
        let inked = frame
            .pixels
            .iter()
            .filter(|p| near(**p, colors::BOUNDS))
            .count();
        let dark = frame
            .pixels
            .iter()
            .filter(|p| p.max_element() < 0.2)
            .count();
        assert!(inked > 20, "{inked} pixels of text");
        assert!(dark > 20, "{dark} pixels of halo");
        // Below the point (away is +Y), not above it.
        let rows_touched: Vec<u32> = (0..100)
            .filter(|&y| (0..200).any(|x| frame.pixel(x, y) != Vec3::splat(0.5)))
            .collect();
        assert!(rows_touched.iter().all(|&y| y > 50), "{rows_touched:?}");
    }
}
