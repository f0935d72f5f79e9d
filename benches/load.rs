//! Loading model files, the load alone (no world, no normals): the icosphere of 1,310,720
//! triangles (an icosahedron with 8 subdivisions, 655,362 vertices) written as OBJ text,
//! binary STL and binary little-endian PLY. Throughput is in bytes of file a second.
//!
//! The files are written once into Cargo's scratch folder for benches. The whole process
//! (`rastray info FILE`) is timed by `../shared/perf/vs-rapidobj.sh` for OBJ; for STL and PLY
//! run it on files that `scripts/obj-to-stl-ply.py` writes.

use std::hint::black_box;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Duration;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rastray::mesh::{MeshFile, icosahedron};

/// Writes the icosphere as `icosphere8.obj`, `.stl` and `.ply` in `dir` (when not there yet).
fn icosphere_files(dir: &Path) -> [PathBuf; 3] {
    let [obj, stl, ply] = ["obj", "stl", "ply"].map(|ext| dir.join(format!("icosphere8.{ext}")));
    if obj.exists() && stl.exists() && ply.exists() {
        return [obj, stl, ply];
    }
    let sphere = icosahedron(1.0, 8);
    let mut text = Vec::new();
    for p in &sphere.positions {
        writeln!(text, "v {:.7} {:.7} {:.7}", p.x, p.y, p.z).unwrap();
    }
    for t in &sphere.triangles {
        writeln!(text, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).unwrap();
    }
    std::fs::write(&obj, text).unwrap();
    let mut bytes = vec![0u8; 80];
    bytes.extend((sphere.triangles.len() as u32).to_le_bytes());
    for t in &sphere.triangles {
        let [a, b, c] = t.map(|i| sphere.positions[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        for v in [n, a, b, c] {
            bytes.extend(v.to_array().iter().flat_map(|x| x.to_le_bytes()));
        }
        bytes.extend([0, 0]);
    }
    std::fs::write(&stl, bytes).unwrap();
    let mut bytes = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        sphere.positions.len(),
        sphere.triangles.len()
    )
    .into_bytes();
    for p in &sphere.positions {
        bytes.extend(p.to_array().iter().flat_map(|x| x.to_le_bytes()));
    }
    for t in &sphere.triangles {
        bytes.push(3);
        bytes.extend(t.iter().flat_map(|&i| (i as i32).to_le_bytes()));
    }
    std::fs::write(&ply, bytes).unwrap();
    [obj, stl, ply]
}

fn load(c: &mut Criterion) {
    let files = icosphere_files(Path::new(env!("CARGO_TARGET_TMPDIR")));
    let mut group = c.benchmark_group("load icosphere8 (1.3M triangles)");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(10));
    for path in &files {
        let size = std::fs::metadata(path).unwrap().len();
        group.throughput(Throughput::Bytes(size));
        let name = path.extension().unwrap().to_string_lossy().into_owned();
        group.bench_function(name, |b| {
            b.iter(|| {
                let model = MeshFile::load(black_box(path)).expect("the icosphere loads");
                assert_eq!(model.triangle_count(), 1_310_720);
                model
            })
        });
    }
    group.finish();
}

criterion_group!(benches, load);
criterion_main!(benches);
