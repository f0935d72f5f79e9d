//! Experiment 3 written out: its CSV, its section of the report, and the verdict: where the ray
//! tracer is the fastest of the three, with its BVH kept and built for every frame.

use std::fmt::Write as _;

use super::crossover::{BvhCount, Cell};
use super::crossover_plot::CROSSOVER_PLOT;
use super::format::number;
use crate::render::Algorithm;

/// File name of experiment 3's CSV.
pub const CROSSOVER_CSV: &str = "who-wins-where.csv";
/// Its header, in column order.
pub const CROSSOVER_HEADER: &str = "width,height,faces,gouraud_ms,phong_ms,ray_trace_ms,ray_build_ms,fastest_bvh_kept,fastest_bvh_per_frame";

/// The CSV text of `cells`: [`CROSSOVER_HEADER`] then one row per cell.
pub fn csv(cells: &[Cell]) -> String {
    let mut out = format!("{CROSSOVER_HEADER}\n");
    for c in cells {
        let _ = writeln!(
            out,
            "{},{},{},{:.4},{:.4},{:.4},{:.4},{},{}",
            c.size.width,
            c.size.height,
            c.faces,
            c.gouraud_ms,
            c.phong_ms,
            c.ray_trace_ms,
            c.ray_build_ms,
            c.winner(BvhCount::Kept).name().to_lowercase(),
            c.winner(BvhCount::PerFrame).name().to_lowercase()
        );
    }
    out
}

/// Where the ray tracer wins with the build counted as `bvh` says, in one sentence: per image
/// size, the face counts at which it is the fastest of the three.
pub fn verdict(cells: &[Cell], bvh: BvhCount) -> String {
    let sizes = distinct(cells.iter().map(|c| c.size));
    let wins = cells
        .iter()
        .filter(|c| c.winner(bvh) == Algorithm::Ray)
        .count();
    let mut per_size = Vec::new();
    let mut nowhere = Vec::new();
    for size in sizes {
        let row: Vec<&Cell> = cells.iter().filter(|c| c.size == size).collect();
        let ray_wins = |c: &&Cell| c.winner(bvh) == Algorithm::Ray;
        match row.iter().position(ray_wins) {
            None => nowhere.push(size.to_string()),
            Some(0) if row.iter().all(ray_wins) => {
                per_size.push(format!("at {size} at every face count"));
            }
            // From some face count up to the largest: a crossover.
            Some(i) if row[i..].iter().all(ray_wins) => {
                per_size.push(format!("at {size} from {} faces up", row[i].faces));
            }
            Some(_) => {
                let list: Vec<String> = row
                    .iter()
                    .filter(|c| ray_wins(c))
                    .map(|c| c.faces.to_string())
                    .collect();
                per_size.push(format!("at {size} at {} faces", list.join(", ")));
            }
        }
    }
    let mut text = format!(
        "{}: the ray tracer is the fastest in {wins} of {} cells",
        bvh.title(),
        cells.len()
    );
    if !per_size.is_empty() {
        let _ = write!(text, ": {}", per_size.join("; "));
    }
    if !nowhere.is_empty() {
        let _ = write!(text, "; nowhere at {}", nowhere.join(", "));
    }
    text.push('.');
    text
}

/// The report's section on experiment 3.
pub fn markdown(cells: &[Cell]) -> String {
    let mut md = String::from("## Experiment 3: who wins where\n\n");
    md.push_str(
        "The experiment 2 scene (its total face area a constant fraction of the image) at every \
         image size and face count. Each cell names the fastest algorithm and its median time; \
         the ray tracer's BVH build is counted once per scene, as the editor keeps its BVH, or \
         for every frame, as a one-off `rastray render` builds it. The black line of the heat \
         map is the crossover.\n\n",
    );
    let _ = writeln!(md, "![Who wins where]({CROSSOVER_PLOT})\n");
    for bvh in BvhCount::ALL {
        let _ = writeln!(md, "- {}", verdict(cells, bvh));
    }
    md.push('\n');
    let faces = distinct(cells.iter().map(|c| c.faces));
    md.push_str("| Size | Faces | Gouraud (ms) | Phong (ms) | Ray, trace (ms) | BVH build (ms) | Fastest, BVH kept | Fastest, BVH per frame |\n");
    md.push_str("|---|---:|---:|---:|---:|---:|---|---|\n");
    for size in distinct(cells.iter().map(|c| c.size)) {
        for &n in &faces {
            let Some(c) = cells.iter().find(|c| c.size == size && c.faces == n) else {
                continue;
            };
            let _ = writeln!(
                md,
                "| {size} | {} | {} | {} | {} | {} | {} | {} |",
                c.faces,
                number(c.gouraud_ms),
                number(c.phong_ms),
                number(c.ray_trace_ms),
                number(c.ray_build_ms),
                c.winner(BvhCount::Kept),
                c.winner(BvhCount::PerFrame)
            );
        }
    }
    md
}

/// The values of `items`, each once, in the order first met.
fn distinct<T: PartialEq>(items: impl Iterator<Item = T>) -> Vec<T> {
    let mut out = Vec::new();
    for item in items {
        if !out.contains(&item) {
            out.push(item);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::Size;

    /// A cell where the ray tracer takes `ray_ms` (build 1 ms) against Z-buffer times of 5 ms.
    fn cell(width: u32, faces: usize, ray_ms: f64) -> Cell {
        Cell {
            size: Size::new(width, width / 2),
            faces,
            gouraud_ms: 5.0,
            phong_ms: 6.0,
            ray_trace_ms: ray_ms,
            ray_build_ms: 1.0,
        }
    }

    #[test]
    fn the_verdict_names_where_the_ray_tracer_wins_per_size() {
        let cells = [
            cell(200, 1000, 9.0),
            cell(200, 4000, 4.5),
            cell(200, 16000, 3.0),
            cell(400, 1000, 9.0),
            cell(400, 4000, 9.0),
            cell(400, 16000, 9.0),
        ];
        let kept = verdict(&cells, BvhCount::Kept);
        assert!(kept.contains("fastest in 2 of 6 cells"), "{kept}");
        assert!(kept.contains("at 200x100 from 4000 faces up"), "{kept}");
        assert!(kept.contains("nowhere at 400x200"), "{kept}");
        // Counting the build (1 ms) turns the 4.5 ms cell back to the Z-buffer.
        let per_frame = verdict(&cells, BvhCount::PerFrame);
        assert!(per_frame.contains("fastest in 1 of 6 cells"), "{per_frame}");
        assert!(per_frame.contains("from 16000 faces up"), "{per_frame}");
    }

    #[test]
    fn scattered_wins_are_listed() {
        let cells = [
            cell(200, 1000, 3.0),
            cell(200, 4000, 9.0),
            cell(200, 16000, 3.0),
        ];
        let kept = verdict(&cells, BvhCount::Kept);
        assert!(kept.contains("at 200x100 at 1000, 16000 faces"), "{kept}");
    }

    #[test]
    fn the_csv_has_a_row_per_cell_with_both_winners() {
        let text = csv(&[cell(200, 1000, 4.5)]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], CROSSOVER_HEADER);
        assert_eq!(
            lines[1],
            "200,100,1000,5.0000,6.0000,4.5000,1.0000,ray,gouraud"
        );
    }
}
