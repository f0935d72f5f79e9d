//! What to render: size, algorithm, samples, and the limits that keep a request sane.

use std::fmt;
use std::num::NonZeroUsize;
use std::str::FromStr;

use super::algorithm::Algorithm;
use super::display_mode::DisplayMode;
use super::overlay::Overlays;

/// Largest width or height accepted, pixels.
pub const MAX_DIMENSION: u32 = 16_384;
/// Largest number of samples rendered for one image (width·height·samples²).
pub const MAX_SAMPLES_TOTAL: u64 = 8192 * 8192;
/// Largest supersampling factor N (N×N samples per pixel).
pub const MAX_SAMPLES: u32 = 8;
/// Most render threads a render may be given (`--threads`, the config file's `threads`): each
/// is an operating-system thread, started before the render.
pub const MAX_THREADS: usize = 1024;

/// An image size in pixels, both sides in 1..=[`MAX_DIMENSION`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Size {
    pub width: u32,
    pub height: u32,
}

impl Size {
    /// A size of `width` × `height` pixels.
    pub const fn new(width: u32, height: u32) -> Size {
        Size { width, height }
    }
}

/// A size, sample count or thread count refused before anything is allocated or started.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SizeError {
    #[error("`{0}` is not a size: write WIDTHxHEIGHT, such as 1920x1080")]
    Syntax(String),
    #[error(
        "{width}x{height} is out of range: width and height must each be between 1 and {MAX_DIMENSION}"
    )]
    Dimension { width: u64, height: u64 },
    #[error("{samples} samples per pixel side is out of range: use 1 to {MAX_SAMPLES}")]
    Samples { samples: u32 },
    #[error(
        "{width}x{height} with {samples}x{samples} supersampling needs {total} samples; the limit is {MAX_SAMPLES_TOTAL} (8192x8192)"
    )]
    Total {
        width: u32,
        height: u32,
        samples: u32,
        total: u64,
    },
    #[error("`{threads}` threads is out of range: use 1 to {MAX_THREADS}")]
    Threads { threads: usize },
}

impl FromStr for Size {
    type Err = SizeError;

    fn from_str(s: &str) -> Result<Size, SizeError> {
        let syntax = || SizeError::Syntax(s.to_string());
        let (w, h) = s.trim().split_once(['x', 'X', '×']).ok_or_else(syntax)?;
        let width: u64 = w.trim().parse().map_err(|_| syntax())?;
        let height: u64 = h.trim().parse().map_err(|_| syntax())?;
        if !(1..=MAX_DIMENSION as u64).contains(&width)
            || !(1..=MAX_DIMENSION as u64).contains(&height)
        {
            return Err(SizeError::Dimension { width, height });
        }
        Ok(Size {
            width: width as u32,
            height: height as u32,
        })
    }
}

impl fmt::Display for Size {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{}", self.width, self.height)
    }
}

/// Everything a render needs besides the world and camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    pub algorithm: Algorithm,
    /// Output width, pixels.
    pub width: u32,
    /// Output height, pixels.
    pub height: u32,
    /// Supersampling factor N: N×N samples per pixel, box-filtered; 1..=[`MAX_SAMPLES`].
    pub samples: u32,
    /// Ray tracer: whether shadow rays are cast (off: every light reaches every point).
    pub shadows: bool,
    /// Ray tracer: reflection depth; `None` takes the scene's `max_depth`.
    pub max_depth: Option<u32>,
    /// Whether the frame also carries coverage as alpha ([`crate::render::Frame::alpha`]): its
    /// colours are then premultiplied, the background left out. Off, the frame has no alpha and
    /// its colours include the background.
    pub alpha: bool,
    /// Render threads; `None` uses one per core (rayon's global pool). The image is the same
    /// for any count.
    pub threads: Option<NonZeroUsize>,
    /// How surfaces are shown; [`DisplayMode::Shaded`] is the algorithm's lit image.
    pub mode: DisplayMode,
    /// Lines drawn over the image; none by default.
    pub overlays: Overlays,
}

impl RenderOptions {
    /// Options for `algorithm` at `width`×`height`, one sample, shadows on, the scene's depth,
    /// no alpha, one thread per core, shaded, no overlays.
    pub fn new(algorithm: Algorithm, width: u32, height: u32) -> RenderOptions {
        RenderOptions {
            algorithm,
            width,
            height,
            samples: 1,
            shadows: true,
            max_depth: None,
            alpha: false,
            threads: None,
            mode: DisplayMode::Shaded,
            overlays: Overlays::default(),
        }
    }

    /// Checks the size, sample and thread limits: every render path calls this before it
    /// allocates a frame or starts a pool.
    pub fn check(&self) -> Result<(), SizeError> {
        if let Some(threads) = self.threads {
            thread_count(threads.get())?;
        }
        let (width, height, samples) = (self.width, self.height, self.samples);
        if !(1..=MAX_DIMENSION).contains(&width) || !(1..=MAX_DIMENSION).contains(&height) {
            return Err(SizeError::Dimension {
                width: width as u64,
                height: height as u64,
            });
        }
        if !(1..=MAX_SAMPLES).contains(&samples) {
            return Err(SizeError::Samples { samples });
        }
        let total = width as u64 * height as u64 * (samples as u64).pow(2);
        if total > MAX_SAMPLES_TOTAL {
            return Err(SizeError::Total {
                width,
                height,
                samples,
                total,
            });
        }
        Ok(())
    }
}

/// `threads` as a render's thread count, if it is 1 to [`MAX_THREADS`]: the one bound that
/// [`RenderOptions::check`] and the command line's `--threads` share.
pub fn thread_count(threads: usize) -> Result<NonZeroUsize, SizeError> {
    NonZeroUsize::new(threads)
        .filter(|n| n.get() <= MAX_THREADS)
        .ok_or(SizeError::Threads { threads })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_check_refuses_a_thread_count_past_the_limit_before_any_pool_starts() {
        let with = |threads: usize| RenderOptions {
            threads: NonZeroUsize::new(threads),
            ..RenderOptions::new(Algorithm::Phong, 16, 16)
        };
        assert_eq!(with(MAX_THREADS).check(), Ok(()));
        assert_eq!(
            with(MAX_THREADS + 1).check(),
            Err(SizeError::Threads {
                threads: MAX_THREADS + 1
            })
        );
        assert_eq!(
            SizeError::Threads { threads: 5000 }.to_string(),
            "`5000` threads is out of range: use 1 to 1024"
        );
    }
}
