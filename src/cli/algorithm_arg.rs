//! `--algorithm`: the command line's spelling and help for the core's [`Algorithm`].

use clap::ValueEnum;
use clap::builder::PossibleValue;
use rastray::Algorithm;

/// An [`Algorithm`] as the command line names it: `gouraud`, `phong`, or `ray` (alias
/// `raytrace`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AlgorithmArg(pub Algorithm);

impl AlgorithmArg {
    /// The name `--algorithm` takes for it: `gouraud`, `phong` or `ray`.
    pub fn spelling(self) -> String {
        self.to_possible_value()
            .map(|v| v.get_name().to_string())
            .unwrap_or_default()
    }
}

impl ValueEnum for AlgorithmArg {
    fn value_variants<'a>() -> &'a [AlgorithmArg] {
        const ALL: [AlgorithmArg; 3] = [
            AlgorithmArg(Algorithm::Gouraud),
            AlgorithmArg(Algorithm::Phong),
            AlgorithmArg(Algorithm::Ray),
        ];
        &ALL
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        Some(match self.0 {
            Algorithm::Gouraud => PossibleValue::new("gouraud")
                .help("Z-buffer, lighting at the vertices, colour interpolated across faces"),
            Algorithm::Phong => PossibleValue::new("phong")
                .help("Z-buffer, normal interpolated across faces, lighting at every pixel"),
            Algorithm::Ray => PossibleValue::new("ray")
                .alias("raytrace")
                .help("Backward (Whitted) ray tracing with shadows and reflections"),
        })
    }
}
