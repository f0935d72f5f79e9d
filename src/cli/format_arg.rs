//! `--format`: the command line's spelling and help for the export's [`ImageFormat`].

use clap::ValueEnum;
use clap::builder::PossibleValue;
use rastray::export::{ImageFormat, PngDepth};

/// An [`ImageFormat`] as the command line names it: `png8`, `png16` or `exr`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FormatArg(pub ImageFormat);

impl ValueEnum for FormatArg {
    fn value_variants<'a>() -> &'a [FormatArg] {
        const ALL: [FormatArg; 3] = [
            FormatArg(ImageFormat::ALL[0]),
            FormatArg(ImageFormat::ALL[1]),
            FormatArg(ImageFormat::ALL[2]),
        ];
        &ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        let help = match self.0 {
            ImageFormat::Png(PngDepth::Eight) => "PNG, 8-bit sRGB (.png)",
            ImageFormat::Png(PngDepth::Sixteen) => "PNG, 16-bit sRGB (.png)",
            ImageFormat::Exr => "OpenEXR: linear 32-bit float colour, no tone curve (.exr)",
        };
        Some(PossibleValue::new(self.0.name()).help(help))
    }
}
