//! `rastray join`: still PNG frames, rendered apart (`--frames`, `--shard`, other machines),
//! joined into one GIF or animated PNG, byte for byte the file one `--turntable` run writes.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use rastray::export::{DEFAULT_FPS, Destination, MAX_FPS, join_frames};
use rastray::render::Progress;
use rastray::text_escape::Escaped;

use super::format_arg::FormatArg;
use super::stdout::outln;

#[derive(Debug, Args)]
pub struct JoinArgs {
    /// The frames, PNG files as `rastray render --turntable N -o 'frames/{frame:04}.png'`
    /// writes them, joined in the order given (a shell's glob sorts them).
    #[arg(required = true, value_name = "FRAME")]
    pub frames: Vec<PathBuf>,
    /// The animation: .gif, or .png for an animated PNG; `-`, a FIFO or a device as a stream.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Frames per second (default that of --turntable).
    #[arg(long, default_value_t = DEFAULT_FPS, value_parser = clap::value_parser!(u32).range(1..=MAX_FPS as i64))]
    pub fps: u32,
    /// Encoding of an animated PNG (png8 or png16); it must match the frames.
    #[arg(long, value_enum)]
    pub format: Option<FormatArg>,
}

pub fn run(args: &JoinArgs) -> anyhow::Result<ExitCode> {
    let destination = if args.output == Path::new("-") {
        Destination::Stdout
    } else {
        Destination::for_path(&args.output)?
    };
    destination.refuse_inputs(&args.frames)?;
    let stats = join_frames(
        &args.frames,
        args.fps,
        args.format.map(|f| f.0),
        &destination,
        &Progress::new(),
    )?;
    let summary = format!(
        "joined {} frames of {}x{} at {} fps in {:.2} s; wrote {}",
        stats.frames,
        stats.width,
        stats.height,
        args.fps,
        stats.elapsed.as_secs_f64(),
        Escaped(&destination.path().display().to_string())
    );
    if destination == Destination::Stdout {
        let _ = writeln!(std::io::stderr(), "{summary}");
    } else {
        outln!("{summary}");
    }
    Ok(ExitCode::SUCCESS)
}
