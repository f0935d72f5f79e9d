//! Flat patches split into grids: the faces of boxes and prisms. Splitting adds faces without
//! changing the area, which the face-count experiment needs.

use glam::Vec3;

/// Welded vertices and triangles under construction.
#[derive(Debug, Default)]
pub struct FaceList {
    pub positions: Vec<Vec3>,
    pub triangles: Vec<[u32; 3]>,
}

impl FaceList {
    /// Adds the parallelogram `origin + s·u + t·v` (s, t in [0, 1]) as a `segments`×`segments`
    /// grid of quads, two triangles each, wound counter-clockwise seen from `u × v`.
    pub fn quad(&mut self, origin: Vec3, u: Vec3, v: Vec3, segments: u32) {
        let n = segments.max(1) as f32;
        self.grid(segments, |col, row| {
            origin + u * (col as f32 / n) + v * (row as f32 / n)
        });
    }

    /// Adds a `segments`×`segments` grid of quads, two triangles each, whose vertex in column
    /// `col` and row `row` (each 0 to `segments`) is `point(col, row)`; wound as
    /// [`FaceList::quad`] winds it with columns along `u` and rows along `v`. Faces that meet
    /// along an edge share its vertices' bits when their `point`s compute them alike.
    pub fn grid(&mut self, segments: u32, point: impl Fn(u32, u32) -> Vec3) {
        let n = segments.max(1);
        let base = self.positions.len() as u32;
        for row in 0..=n {
            for col in 0..=n {
                self.positions.push(point(col, row));
            }
        }
        let at = |row: u32, col: u32| base + row * (n + 1) + col;
        for row in 0..n {
            for col in 0..n {
                let (a, b, c, d) = (
                    at(row, col),
                    at(row, col + 1),
                    at(row + 1, col + 1),
                    at(row + 1, col),
                );
                self.triangles.push([a, b, c]);
                self.triangles.push([a, c, d]);
            }
        }
    }

    /// Adds a triangle split into `segments`² similar triangles, whose vertex `k` steps along
    /// its first edge and `r` rows toward its third corner (k + r ≤ `segments`) is
    /// `point(k, r)`; wound like its corners `point(0, 0)`, `point(segments, 0)`,
    /// `point(0, segments)`.
    pub fn triangle_grid(&mut self, segments: u32, point: impl Fn(u32, u32) -> Vec3) {
        let n = segments.max(1);
        let base = self.positions.len() as u32;
        // Row r (0 at the first edge, n at the third corner) holds n − r + 1 vertices.
        let mut row_start = Vec::with_capacity(n as usize + 1);
        for r in 0..=n {
            row_start.push(self.positions.len() as u32 - base);
            for k in 0..=(n - r) {
                self.positions.push(point(k, r));
            }
        }
        let at = |r: u32, k: u32| base + row_start[r as usize] + k;
        for r in 0..n {
            for k in 0..(n - r) {
                self.triangles.push([at(r, k), at(r, k + 1), at(r + 1, k)]);
                if k + 1 < n - r {
                    self.triangles
                        .push([at(r, k + 1), at(r + 1, k + 1), at(r + 1, k)]);
                }
            }
        }
    }
}
