//! Model import speed: a grid of triangles written as binary STL and binary PLY (float x y z,
//! uchar red green blue; uchar count and int indices, the common layout), then each loaded a
//! few times through rastray's readers, in GB of file per second (best run). The readers run on
//! one thread; the rate is given by wall-clock time and by CPU time (user + system, from
//! /proc): on a shared machine the CPU time is what the load takes on an idle core.
//!
//! Run with `cargo run --release --example model_load [TRIANGLES] [--shuffle] [stl|ply]`
//! (`stl` or `ply`: that format alone, for a peak-memory figure of its own): by default
//! 9,000,000 triangles (the most a scene holds; a 450 MB STL and a 180 MB PLY, written once to
//! the system's temporary folder and kept there for the next run). `--shuffle` writes the
//! STL's triangles in a random order, as a mesh with no locality would have them: welding then
//! misses the cache on most corners.

#[path = "common/cpu_time.rs"]
mod cpu_time;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use cpu_time::cpu_time;

use rastray::mesh::{load_ply, load_stl};

const RUNS: usize = 3;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let triangles: usize = args
        .iter()
        .find_map(|a| a.parse().ok())
        .unwrap_or(9_000_000);
    let shuffle = args.iter().any(|a| a == "--shuffle");
    let only = |format: &str| {
        !args.iter().any(|a| a == "stl" || a == "ply") || args.iter().any(|a| a == format)
    };
    let side = ((triangles / 2) as f64).sqrt().floor() as usize;
    let grid = Grid { side };
    let tag = if shuffle { "-shuffled" } else { "" };
    let dir = std::env::temp_dir();
    let stl = dir.join(format!("rastray-grid-{side}{tag}.stl"));
    let ply = dir.join(format!("rastray-grid-{side}.ply"));
    if !stl.exists() && only("stl") {
        write(&stl, &grid.stl(shuffle));
    }
    if !ply.exists() && only("ply") {
        write(&ply, &grid.ply());
    }
    println!(
        "grid of {side}×{side} quads: {} triangles, {} vertices",
        grid.triangles().len(),
        (side + 1) * (side + 1)
    );
    if only("stl") {
        report("binary STL", &stl, || {
            load_stl(&stl).expect("loads").geometry.triangles.len()
        });
    }
    if only("ply") {
        report("binary PLY", &ply, || {
            load_ply(&ply).expect("loads").geometry.triangles.len()
        });
    }
}

/// Loads `path` [`RUNS`] times with `load` and prints the best time and rate.
fn report(name: &str, path: &Path, load: impl Fn() -> usize) {
    let bytes = std::fs::metadata(path).expect("written").len();
    let (mut wall, mut cpu) = (Duration::MAX, Duration::MAX);
    let mut count = 0;
    for _ in 0..RUNS {
        let (start, cpu_start) = (Instant::now(), cpu_time());
        count = load();
        wall = wall.min(start.elapsed());
        cpu = cpu.min(cpu_time() - cpu_start);
    }
    let rate = |t: Duration| bytes as f64 / t.as_secs_f64() / 1e9;
    println!(
        "{name:<11} {:>7.1} MB  {count} triangles  best of {RUNS}: {:>7.1} ms wall ({:.2} GB/s), \
         {:>7.1} ms CPU ({:.2} GB/s)",
        bytes as f64 / 1e6,
        wall.as_secs_f64() * 1e3,
        rate(wall),
        cpu.as_secs_f64() * 1e3,
        rate(cpu)
    );
}

fn write(path: &PathBuf, bytes: &[u8]) {
    let mut file = std::fs::File::create(path).expect("create");
    file.write_all(bytes).expect("write");
}

/// A `side`×`side` grid of unit quads in the XZ plane, each two triangles, heights rippled.
struct Grid {
    side: usize,
}

impl Grid {
    fn vertex(&self, i: usize, j: usize) -> [f32; 3] {
        let (x, z) = (i as f32 / self.side as f32, j as f32 / self.side as f32);
        [x, (x * 40.0).sin() * (z * 40.0).cos() * 0.02, z]
    }

    fn index(&self, i: usize, j: usize) -> u32 {
        (j * (self.side + 1) + i) as u32
    }

    fn triangles(&self) -> Vec<[u32; 3]> {
        let mut out = Vec::with_capacity(2 * self.side * self.side);
        for j in 0..self.side {
            for i in 0..self.side {
                let (a, b) = (self.index(i, j), self.index(i + 1, j));
                let (c, d) = (self.index(i, j + 1), self.index(i + 1, j + 1));
                out.push([a, c, b]);
                out.push([b, c, d]);
            }
        }
        out
    }

    fn position(&self, index: u32) -> [f32; 3] {
        let n = self.side + 1;
        self.vertex(index as usize % n, index as usize / n)
    }

    fn stl(&self, shuffle: bool) -> Vec<u8> {
        let mut triangles = self.triangles();
        if shuffle {
            // A fixed xorshift permutation (Fisher–Yates).
            let mut state = 0x2545_f491_4f6c_dd1du64;
            for i in (1..triangles.len()).rev() {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                triangles.swap(i, (state % (i as u64 + 1)) as usize);
            }
        }
        let mut bytes = vec![b' '; 80];
        bytes[..5].copy_from_slice(b"solid");
        bytes.extend((triangles.len() as u32).to_le_bytes());
        for t in &triangles {
            bytes.extend([0f32, 1.0, 0.0].iter().flat_map(|c| c.to_le_bytes()));
            for &v in t {
                bytes.extend(self.position(v).iter().flat_map(|c| c.to_le_bytes()));
            }
            bytes.extend([0, 0]);
        }
        bytes
    }

    fn ply(&self) -> Vec<u8> {
        let n = self.side + 1;
        let triangles = self.triangles();
        let mut bytes = format!(
            "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
             property float y\nproperty float z\nproperty uchar red\nproperty uchar green\n\
             property uchar blue\nelement face {}\nproperty list uchar int vertex_indices\n\
             end_header\n",
            n * n,
            triangles.len()
        )
        .into_bytes();
        for index in 0..(n * n) as u32 {
            let p = self.position(index);
            bytes.extend(p.iter().flat_map(|c| c.to_le_bytes()));
            bytes.extend([(p[0] * 255.0) as u8, 128, (p[2] * 255.0) as u8]);
        }
        for t in &triangles {
            bytes.push(3);
            bytes.extend(t.iter().flat_map(|&i| (i as i32).to_le_bytes()));
        }
        bytes
    }
}
