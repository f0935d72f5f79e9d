//! `rastray bench`: the study's two experiments for the three algorithms and experiment 3 (who
//! wins where over image size × face count), written as CSVs, a Markdown report and plots;
//! `rastray bench throughput SCENE`: throughput on one scene.

use super::stdout::outln;
use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Context;
use clap::{Args, Subcommand};
use indicatif::ProgressBar;
use rastray::World;
use rastray::bench::crossover::{BvhCount, run_crossover};
use rastray::bench::report::{CSV_FILE, REPORT_FILE};
use rastray::bench::throughput::measure;
use rastray::bench::{BenchConfig, crossover_plot, crossover_report, number, plot, report, run};
use rastray::render::Size;
use rastray::world::MeshFileCache;

/// Timed renders per point by default, and in quick mode.
const DEFAULT_REPS: u32 = 5;
const QUICK_REPS: u32 = 1;

#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct BenchArgs {
    #[command(subcommand)]
    pub command: Option<BenchCommand>,
    /// Fewer points and one render per point: a first look in under a minute.
    #[arg(long)]
    pub quick: bool,
    /// Directory for results.csv, report.md and the plots (created if missing).
    #[arg(short, long, default_value = "bench-out")]
    pub out: PathBuf,
    /// Image size, WIDTHxHEIGHT.
    #[arg(short, long, default_value = "1920x1080", value_parser = super::parse_size)]
    pub size: Size,
    /// Timed renders per point and algorithm (default 5, quick 1); the median is reported.
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub reps: Option<u32>,
}

#[derive(Debug, Subcommand)]
pub enum BenchCommand {
    /// Rasterizer Mtriangles/s and Mpixels/s, ray tracer Mrays/s and BVH build time on one scene.
    Throughput(ThroughputArgs),
}

#[derive(Debug, Args)]
pub struct ThroughputArgs {
    /// Scene file (TOML), or a model file (.obj, .gltf, .glb) shown on its own.
    pub scene: PathBuf,
    /// Image size, WIDTHxHEIGHT.
    #[arg(short, long, default_value = "1920x1080", value_parser = super::parse_size)]
    pub size: Size,
    /// Renders per algorithm; the median is reported.
    #[arg(long, default_value_t = DEFAULT_REPS, value_parser = clap::value_parser!(u32).range(1..=1000))]
    pub reps: u32,
}

pub fn run_bench(args: &BenchArgs) -> anyhow::Result<()> {
    if let Some(BenchCommand::Throughput(t)) = &args.command {
        return throughput(t);
    }
    let config = BenchConfig {
        size: args.size,
        reps: args
            .reps
            .unwrap_or(if args.quick { QUICK_REPS } else { DEFAULT_REPS }),
        quick: args.quick,
    };
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let machine = machine();
    outln!(
        "rastray bench: {}, {} render(s) per point, {machine}",
        config.size,
        config.reps
    );
    let load_before = load_average();
    let results = run(&config, &ProgressBar::new(0))?;
    let cells = run_crossover(config.quick, config.reps, &ProgressBar::new(0))?;
    let machine = match (load_before, load_average()) {
        (Some(before), Some(after)) => {
            format!("{machine}; load average {before} before the run, {after} after.")
        }
        _ => format!("{machine}."),
    };
    report::write(&args.out, &results, &cells, &config, &machine)?;
    plot::write(&args.out, &results, config.size)?;
    crossover_plot::write(&args.out, &cells)?;
    outln!();
    for claim in rastray::bench::analysis::claims(&results, config.size) {
        outln!("[{}] {}", claim.verdict.name(), claim.study);
        outln!("          rastray: {}", claim.ours);
    }
    for bvh in BvhCount::ALL {
        outln!(
            "[who wins where] {}",
            crossover_report::verdict(&cells, bvh)
        );
    }
    outln!(
        "\nwrote {}, {}, {}, {}, {} and {} in {}",
        CSV_FILE,
        REPORT_FILE,
        plot::AREA_PLOT,
        plot::FACES_PLOT,
        crossover_report::CROSSOVER_CSV,
        crossover_plot::CROSSOVER_PLOT,
        args.out.display()
    );
    Ok(())
}

/// Where the numbers come from: CPU model when known, threads, OS and architecture.
fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, name)| name.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".to_string());
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!(
        "{cpu}, {threads} threads, {} {}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

/// The one-minute load average, when the system reports it: other work on the machine shows up
/// in the timings.
fn load_average() -> Option<String> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    text.split_whitespace().next().map(str::to_string)
}

fn throughput(args: &ThroughputArgs) -> anyhow::Result<()> {
    let mut cache = MeshFileCache::default();
    let (scene, base) = super::load_scene(Some(&args.scene), None, &mut cache)?;
    let world = Arc::new(World::build_cached(&scene, &base, &mut cache)?);
    drop(cache);
    let t = measure(&scene, &world, args.size, args.reps)?;
    outln!(
        "{}: {} triangles at {}, median of {} render(s)",
        args.scene.display(),
        world.triangle_count(),
        args.size,
        args.reps
    );
    for r in &t.raster {
        outln!(
            "{:8} {:>9} ms  {:>8} Mtriangles/s  {:>8} Mpixels/s  ({} Mpx/s of face area; \
             renderer kept, one-off {} ms)",
            r.algorithm.name(),
            number(r.time.as_secs_f64() * 1e3),
            number(r.mtriangles_per_s()),
            number(r.mpixels_per_s()),
            number(r.mfragments_per_s()),
            number(r.one_off.as_secs_f64() * 1e3)
        );
    }
    let ray = &t.ray;
    let s = ray.stats;
    outln!(
        "{:8} {:>9} ms  BVH build {} ms, tracing {} ms",
        "Ray",
        number(ray.time().as_secs_f64() * 1e3),
        number(ray.build.as_secs_f64() * 1e3),
        number(ray.trace_time().as_secs_f64() * 1e3)
    );
    for kind in ray.kinds() {
        outln!(
            "         {:10} {:>12} rays  {:>8} Mrays/s  ({} ms on its own)",
            kind.name,
            kind.rays,
            number(kind.mrays_per_s()),
            number(kind.time.as_secs_f64() * 1e3)
        );
    }
    outln!(
        "         {:10} {:>12} rays  {:>8} Mrays/s",
        "all",
        s.rays.total(),
        number(ray.mrays_per_s(s.rays.total()))
    );
    // One line for scripts: key=value, times in milliseconds.
    let [primary, shadow, reflection] = ray.kinds();
    outln!(
        "ray-throughput tracing_ms={:.3} build_ms={:.3} rays={} primary_ms={:.3} primary_rays={} shadow_ms={:.3} shadow_rays={} reflection_ms={:.3} reflection_rays={}",
        ray.trace_time().as_secs_f64() * 1e3,
        ray.build.as_secs_f64() * 1e3,
        s.rays.total(),
        primary.time.as_secs_f64() * 1e3,
        primary.rays,
        shadow.time.as_secs_f64() * 1e3,
        shadow.rays,
        reflection.time.as_secs_f64() * 1e3,
        reflection.rays
    );
    Ok(())
}
