//! Pictures brought to another pixel grid: a render made with square pixels, taken to the
//! grid an encoder samples (a fixed number of samples a cell, whatever the cell's shape).

use super::preview::PreviewImage;

/// `image` at `width`×`height` pixels, each pixel the source pixel under its centre (nearest
/// neighbour). Exact when one size divides the other; the same image when the size is its own.
/// An empty source gives black pixels.
pub fn nearest(image: &PreviewImage, width: u32, height: u32) -> PreviewImage {
    if image.width == width && image.height == height {
        return image.clone();
    }
    let source = |v: u32, from: u32, to: u32| {
        ((2 * u64::from(v) + 1) * u64::from(from) / (2 * u64::from(to.max(1)))) as u32
    };
    let columns: Vec<u32> = (0..width).map(|x| source(x, image.width, width)).collect();
    let mut pixels = Vec::with_capacity(width as usize * height as usize);
    for y in 0..height {
        let sy = source(y, image.height, height);
        for &sx in &columns {
            pixels.push(image.pixel(sx, sy).unwrap_or([0; 3]));
        }
    }
    PreviewImage {
        width,
        height,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_pixel_takes_the_source_pixel_under_its_centre() {
        let image = PreviewImage {
            width: 2,
            height: 2,
            pixels: vec![[1; 3], [2; 3], [3; 3], [4; 3]],
        };
        let up = nearest(&image, 4, 6);
        assert_eq!(up.pixel(1, 2), Some([1; 3]));
        assert_eq!(up.pixel(2, 2), Some([2; 3]));
        assert_eq!(up.pixel(0, 3), Some([3; 3]));
        assert_eq!(up.pixel(3, 5), Some([4; 3]));
        assert_eq!(nearest(&up, 2, 2), image);
        // 19 rows to 16: rows keep their order and the last row stays.
        let tall = PreviewImage {
            width: 1,
            height: 19,
            pixels: (0..19).map(|v| [v; 3]).collect(),
        };
        let short = nearest(&tall, 1, 16);
        assert_eq!(short.pixel(0, 0), Some([0; 3]));
        assert_eq!(short.pixel(0, 15), Some([18; 3]));
        assert!(short.pixels.windows(2).all(|w| w[0][0] < w[1][0]));
    }
}
