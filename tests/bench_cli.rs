//! `rastray bench --quick` and `rastray bench throughput` run as a user would run them: the
//! files they write are parsed back and checked.

use std::path::Path;
use std::process::Command;

use rastray::bench::crossover::{SIZES_QUICK, STEPS_QUICK};
use rastray::bench::crossover_plot::CROSSOVER_PLOT;
use rastray::bench::crossover_report::{CROSSOVER_CSV, CROSSOVER_HEADER};
use rastray::bench::plot::{AREA_PLOT, FACES_PLOT, PLOT_SIZE};
use rastray::bench::report::{CSV_FILE, REPORT_FILE};

fn rastray(args: &[&str]) -> String {
    let output = Command::new(env!("CARGO_BIN_EXE_rastray"))
        .args(args)
        .output()
        .expect("the binary runs");
    assert!(
        output.status.success(),
        "rastray {args:?} failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8(output.stdout).expect("UTF-8 output")
}

/// `rastray bench throughput PATH` at 64×48, one render each.
fn throughput(path: &Path) -> String {
    let path = path.to_str().unwrap();
    rastray(&[
        "bench",
        "throughput",
        path,
        "--size",
        "64x48",
        "--reps",
        "1",
    ])
}

#[test]
fn quick_bench_writes_a_csv_a_report_and_two_plots() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let stdout = rastray(&[
        "bench",
        "--quick",
        "--size",
        "64x48",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        stdout.contains(" px ("),
        "each point prints its area: {stdout}"
    );

    let csv = std::fs::read_to_string(out.join(CSV_FILE)).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        header,
        [
            "experiment",
            "algorithm",
            "faces",
            "total_area_px",
            "median_ms",
            "min_ms",
            "max_ms"
        ]
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let mut seen = std::collections::HashSet::new();
    for row in &rows {
        assert_eq!(row.len(), header.len(), "{row:?}");
        assert!(["area", "faces"].contains(&row[0]), "{row:?}");
        assert!(["gouraud", "phong", "ray"].contains(&row[1]), "{row:?}");
        let numbers: Vec<f64> = row[2..].iter().map(|v| v.parse().unwrap()).collect();
        assert!(numbers.iter().all(|&v| v > 0.0), "{row:?}");
        let (median, min, max) = (numbers[2], numbers[3], numbers[4]);
        assert!(min <= median && median <= max, "{row:?}");
        seen.insert((row[0], row[1]));
    }
    assert_eq!(seen.len(), 6, "both experiments for all three algorithms");
    let faces: Vec<u64> = rows
        .iter()
        .filter(|r| r[0] == "faces" && r[1] == "phong")
        .map(|r| r[2].parse().unwrap())
        .collect();
    assert!(faces.windows(2).all(|w| w[0] < w[1]), "{faces:?}");
    assert!(*faces.last().unwrap() >= 1_000_000, "{faces:?}");

    let report = std::fs::read_to_string(out.join(REPORT_FILE)).unwrap();
    for needle in [
        "## Crossovers",
        "## The study's claims beside ours",
        AREA_PLOT,
        FACES_PLOT,
    ] {
        assert!(report.contains(needle), "report lacks {needle}");
    }
    let verdicts = report.matches("**agrees**").count() + report.matches("**differs**").count();
    assert_eq!(verdicts, 5, "one verdict per claim");

    for plot in [AREA_PLOT, FACES_PLOT] {
        let image = image::open(out.join(plot)).unwrap();
        assert_eq!((image.width(), image.height()), PLOT_SIZE, "{plot}");
        let rgb = image.to_rgb8();
        let distinct: std::collections::HashSet<_> = rgb.pixels().map(|p| p.0).collect();
        assert!(distinct.len() > 10, "{plot} has lines and text on it");
    }

    // Experiment 3: a cell per quick size and face count, each naming the faster algorithms its
    // own times make faster, with the build counted or not.
    let cells = std::fs::read_to_string(out.join(CROSSOVER_CSV)).unwrap();
    let mut lines = cells.lines();
    assert_eq!(lines.next(), Some(CROSSOVER_HEADER));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), SIZES_QUICK.len() * STEPS_QUICK.len());
    let name = |i: usize| ["gouraud", "phong", "ray"][i];
    for row in &rows {
        let ms: Vec<f64> = row[3..7].iter().map(|v| v.parse().unwrap()).collect();
        assert!(ms[..3].iter().all(|&t| t > 0.0) && ms[3] >= 0.0, "{row:?}");
        let fastest = |times: [f64; 3]| {
            (0..3)
                .min_by(|&a, &b| times[a].total_cmp(&times[b]))
                .map(name)
                .unwrap()
        };
        assert_eq!(row[7], fastest([ms[0], ms[1], ms[2]]), "{row:?}");
        assert_eq!(row[8], fastest([ms[0], ms[1], ms[2] + ms[3]]), "{row:?}");
    }
    assert!(report.contains("## Experiment 3: who wins where"));
    assert_eq!(
        report.matches("the ray tracer is the fastest in").count(),
        2
    );
    let heat_map = image::open(out.join(CROSSOVER_PLOT)).unwrap().to_rgb8();
    let distinct: std::collections::HashSet<_> = heat_map.pixels().map(|p| p.0).collect();
    assert!(distinct.len() > 10, "the heat map has cells and text on it");
}

#[test]
fn throughput_reports_rates_for_a_scene_and_an_obj_model() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/default.toml");
    let stdout = throughput(&scene);
    for needle in [
        "Gouraud",
        "Phong",
        "Mtriangles/s",
        "Mpixels/s",
        "primary",
        "shadow",
        "reflection",
        "Mrays/s",
        "BVH build",
        "renderer kept, one-off",
    ] {
        assert!(stdout.contains(needle), "output lacks {needle}: {stdout}");
    }

    // A tetrahedron: 4 faces.
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("tetra.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    )
    .unwrap();
    let stdout = throughput(&obj);
    assert!(stdout.contains(": 4 triangles at 64x48"), "{stdout}");
}
