//! The file formats rastray writes, and the choice of one from a file name and an explicit
//! request: the extension must match the format, so a name never promises bytes it does not get.

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// Bits per channel of a PNG.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PngDepth {
    Eight,
    Sixteen,
}

/// How a still image is encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// PNG, sRGB-encoded, 8 or 16 bits per channel; with alpha, the colour is straight (not
    /// premultiplied) and the alpha linear.
    Png(PngDepth),
    /// OpenEXR, linear 32-bit float colour with no tone curve; with alpha, the colour is
    /// premultiplied.
    Exr,
}

/// How a turntable is encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AnimationFormat {
    /// GIF: 256 colours per frame; alpha below ½ is transparent, the rest opaque.
    Gif,
    /// Animated PNG, sRGB-encoded, 8 or 16 bits per channel; alpha as in a still PNG.
    Apng(PngDepth),
}

/// A file name and format that do not go together.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FormatError {
    #[error(
        "{}: rastray writes images as .png (PNG, 8- or 16-bit) or .exr (OpenEXR), and turntables as .gif or .png (animated PNG); {}",
        path.display(),
        match extension {
            Some(e) => format!("`.{e}` is none of them"),
            None => "this name has no extension".to_string(),
        }
    )]
    Unsupported {
        path: PathBuf,
        extension: Option<String>,
    },
    #[error("{}: format {format} writes .{expected} files", path.display())]
    Mismatch {
        path: PathBuf,
        format: ImageFormat,
        expected: &'static str,
    },
    #[error(
        "{}: a GIF is written for turntables only; write a still image as .png or .exr",
        path.display()
    )]
    StillGif { path: PathBuf },
    #[error(
        "{}: a turntable is written as .gif or .png (animated PNG, format png8 or png16), not as {format}",
        path.display()
    )]
    NotAnimated { path: PathBuf, format: ImageFormat },
    #[error("`{0}` is not an image format: use png8, png16 or exr")]
    Unknown(String),
}

impl ImageFormat {
    /// 8-bit PNG, the format rastray writes unless asked otherwise.
    pub const PNG8: ImageFormat = ImageFormat::Png(PngDepth::Eight);
    /// 16-bit PNG.
    pub const PNG16: ImageFormat = ImageFormat::Png(PngDepth::Sixteen);
    /// Every format, in the order `--format` lists them.
    pub const ALL: [ImageFormat; 3] = [ImageFormat::PNG8, ImageFormat::PNG16, ImageFormat::Exr];

    /// The name a user types for this format: `png8`, `png16` or `exr`.
    pub fn name(self) -> &'static str {
        match self {
            ImageFormat::Png(PngDepth::Eight) => "png8",
            ImageFormat::Png(PngDepth::Sixteen) => "png16",
            ImageFormat::Exr => "exr",
        }
    }

    /// The file extension this format is written with, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            ImageFormat::Png(_) => "png",
            ImageFormat::Exr => "exr",
        }
    }

    /// The format of a still image written to `path`: `requested`, when its extension matches
    /// the name's; else the one the extension names (`.png` is 8-bit).
    pub fn for_path(
        path: &Path,
        requested: Option<ImageFormat>,
    ) -> Result<ImageFormat, FormatError> {
        let named = match extension(path).as_deref() {
            Some("png") => ImageFormat::PNG8,
            Some("exr") => ImageFormat::Exr,
            Some("gif") => {
                return Err(FormatError::StillGif {
                    path: path.to_path_buf(),
                });
            }
            _ => return Err(unsupported(path)),
        };
        match requested {
            None => Ok(named),
            Some(format) if format.extension() == named.extension() => Ok(format),
            Some(format) => Err(FormatError::Mismatch {
                path: path.to_path_buf(),
                format,
                expected: format.extension(),
            }),
        }
    }
}

impl AnimationFormat {
    /// The format of a turntable written to `path`: GIF for `.gif`, animated PNG for `.png`
    /// (16-bit when `requested` is png16).
    pub fn for_path(
        path: &Path,
        requested: Option<ImageFormat>,
    ) -> Result<AnimationFormat, FormatError> {
        let not_animated = |format| FormatError::NotAnimated {
            path: path.to_path_buf(),
            format,
        };
        match (extension(path).as_deref(), requested) {
            (_, Some(ImageFormat::Exr)) => Err(not_animated(ImageFormat::Exr)),
            (Some("gif"), None) => Ok(AnimationFormat::Gif),
            (Some("gif"), Some(format)) => Err(FormatError::Mismatch {
                path: path.to_path_buf(),
                format,
                expected: format.extension(),
            }),
            (Some("png"), None) => Ok(AnimationFormat::Apng(PngDepth::Eight)),
            (Some("png"), Some(ImageFormat::Png(depth))) => Ok(AnimationFormat::Apng(depth)),
            (Some("exr"), _) => Err(not_animated(ImageFormat::Exr)),
            _ => Err(unsupported(path)),
        }
    }
}

/// The lower-case extension of `path`, if it has one.
fn extension(path: &Path) -> Option<String> {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
}

fn unsupported(path: &Path) -> FormatError {
    FormatError::Unsupported {
        path: path.to_path_buf(),
        extension: path.extension().map(|e| e.to_string_lossy().into_owned()),
    }
}

impl fmt::Display for ImageFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ImageFormat {
    type Err = FormatError;

    fn from_str(s: &str) -> Result<ImageFormat, FormatError> {
        ImageFormat::ALL
            .into_iter()
            .find(|f| f.name().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| FormatError::Unknown(s.to_string()))
    }
}

impl fmt::Display for AnimationFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AnimationFormat::Gif => "GIF",
            AnimationFormat::Apng(PngDepth::Eight) => "animated PNG",
            AnimationFormat::Apng(PngDepth::Sixteen) => "16-bit animated PNG",
        })
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::{AnimationFormat, FormatError, ImageFormat, PngDepth};

    #[test]
    fn the_extension_picks_the_format_and_a_request_must_match_it() {
        let still = |name: &str, requested| ImageFormat::for_path(Path::new(name), requested);
        assert_eq!(still("a.png", None), Ok(ImageFormat::PNG8));
        assert_eq!(still("a.PNG", None), Ok(ImageFormat::PNG8));
        assert_eq!(
            still("a.png", Some(ImageFormat::PNG16)),
            Ok(ImageFormat::PNG16)
        );
        assert_eq!(still("dir.v2/a.exr", None), Ok(ImageFormat::Exr));
        assert!(matches!(
            still("a.png", Some(ImageFormat::Exr)),
            Err(FormatError::Mismatch {
                expected: "exr",
                ..
            })
        ));
        assert!(matches!(
            still("a.exr", Some(ImageFormat::PNG16)),
            Err(FormatError::Mismatch {
                expected: "png",
                ..
            })
        ));
        assert!(matches!(
            still("a.gif", None),
            Err(FormatError::StillGif { .. })
        ));
        let jpg = still("out.jpg", None).unwrap_err().to_string();
        assert!(
            jpg.contains("out.jpg") && jpg.contains(".jpg") && jpg.contains(".png"),
            "{jpg}"
        );
        assert!(jpg.contains(".exr") && jpg.contains(".gif"), "{jpg}");
        let bare = still("out", Some(ImageFormat::Exr))
            .unwrap_err()
            .to_string();
        assert!(bare.contains("no extension"), "{bare}");
    }

    #[test]
    fn a_turntable_is_a_gif_or_an_animated_png() {
        let animated =
            |name: &str, requested| AnimationFormat::for_path(Path::new(name), requested);
        assert_eq!(animated("spin.gif", None), Ok(AnimationFormat::Gif));
        assert_eq!(
            animated("spin.png", None),
            Ok(AnimationFormat::Apng(PngDepth::Eight))
        );
        assert_eq!(
            animated("spin.png", Some(ImageFormat::PNG16)),
            Ok(AnimationFormat::Apng(PngDepth::Sixteen))
        );
        assert!(matches!(
            animated("spin.exr", None),
            Err(FormatError::NotAnimated { .. })
        ));
        assert!(matches!(
            animated("spin.png", Some(ImageFormat::Exr)),
            Err(FormatError::NotAnimated { .. })
        ));
        assert!(matches!(
            animated("spin.gif", Some(ImageFormat::PNG8)),
            Err(FormatError::Mismatch { .. })
        ));
        assert!(matches!(
            animated("spin.webp", None),
            Err(FormatError::Unsupported { .. })
        ));
    }

    #[test]
    fn format_names_parse_back() {
        for format in ImageFormat::ALL {
            assert_eq!(format.name().parse(), Ok(format));
        }
        assert_eq!(" PNG16 ".parse(), Ok(ImageFormat::PNG16));
        assert!(matches!(
            "jpeg".parse::<ImageFormat>(),
            Err(FormatError::Unknown(_))
        ));
    }
}
