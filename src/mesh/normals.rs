//! Vertex normals: flat (one normal per face, vertices split) or smooth within a crease angle.

use std::collections::HashMap;

use glam::Vec3;
use rayon::prelude::*;

use super::face_list::Mesh;

/// Adjacent faces meeting at less than this angle share a smoothed normal, degrees.
pub const CREASE_ANGLE_DEGREES: f32 = 60.0;

/// `v` scaled to unit length, or zero when it has no direction that f32 can state: zero, not
/// finite, or so short that its squared length is subnormal (normalizing that gives a vector
/// whose length is not 1: a normal of length 2e-22 came out 1.13 long). Normals from files and
/// from faces both pass through it, and a zero normal counts as missing.
pub fn unit_or_zero(v: Vec3) -> Vec3 {
    let squared = v.length_squared();
    if squared.is_normal() {
        // As glam's `normalize_or_zero` computes it, so normals keep their bits.
        v * (1.0 / squared.sqrt())
    } else {
        Vec3::ZERO
    }
}

/// Builds a [`Mesh`] from welded `positions` and `triangles`, without colours: see
/// [`with_colors_and_normals`].
pub fn with_normals(positions: &[Vec3], triangles: &[[u32; 3]], smooth: bool) -> Mesh {
    with_colors_and_normals(positions, triangles, None, smooth)
}

/// Builds a [`Mesh`] from welded `positions` and `triangles`, with `colors` (one per position)
/// when given.
///
/// Flat: every triangle gets its own three vertices carrying the face normal.
/// Smooth: each corner's normal is the area-weighted sum of the normals of the faces around that
/// vertex that meet its own face at less than [`CREASE_ANGLE_DEGREES`]; corners of one position
/// that end with the same normal share one vertex. Degenerate faces (zero area) take the normal
/// of a neighbour or +Y.
///
/// Each output vertex keeps its position's colour. With colours, a model may hold one point
/// several times, once per colour (a seam between two colours): those entries are never merged,
/// but the faces around all of them count for each one's normal, so a colour seam is no crease.
pub fn with_colors_and_normals(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    colors: Option<&[Vec3]>,
    smooth: bool,
) -> Mesh {
    debug_assert!(colors.is_none_or(|c| c.len() == positions.len()));
    if !smooth {
        return flat_normals(positions, triangles, colors);
    }
    let (weighted, unit) = face_normals(triangles, positions);
    smooth_normals(positions, triangles, colors, &weighted, &unit)
}

/// Each triangle's area-weighted normal and its unit normal (zero for a degenerate one).
fn face_normals(triangles: &[[u32; 3]], positions: &[Vec3]) -> (Vec<Vec3>, Vec<Vec3>) {
    let weighted: Vec<Vec3> = triangles
        .par_iter()
        .map(|&t| area_weighted_normal(positions, t))
        .collect();
    let unit = weighted.par_iter().map(|&n| unit_or_zero(n)).collect();
    (weighted, unit)
}

/// The face normal of triangle `[a, b, c]` weighted by its area: the edges' cross product,
/// whose length is twice the area.
fn area_weighted_normal(positions: &[Vec3], [a, b, c]: [u32; 3]) -> Vec3 {
    let (a, b, c) = (
        positions[a as usize],
        positions[b as usize],
        positions[c as usize],
    );
    (b - a).cross(c - a)
}

/// Three vertices a triangle, each with the face's unit normal (computed as it goes: no
/// per-triangle array beside the mesh being built) and its position's colour.
fn flat_normals(positions: &[Vec3], triangles: &[[u32; 3]], colors: Option<&[Vec3]>) -> Mesh {
    let mut mesh = Mesh {
        positions: Vec::with_capacity(triangles.len() * 3),
        normals: Vec::with_capacity(triangles.len() * 3),
        triangles: Vec::with_capacity(triangles.len()),
        colors: colors.map(|_| Vec::with_capacity(triangles.len() * 3)),
        uvs: None,
        flat: true,
    };
    for tri in triangles {
        let unit = unit_or_zero(area_weighted_normal(positions, *tri));
        let n = if unit == Vec3::ZERO { Vec3::Y } else { unit };
        let base = mesh.positions.len() as u32;
        for &i in tri {
            mesh.positions.push(positions[i as usize]);
            mesh.normals.push(n);
        }
        if let (Some(out), Some(colors)) = (&mut mesh.colors, colors) {
            out.extend(tri.map(|i| colors[i as usize]));
        }
        mesh.triangles.push([base, base + 1, base + 2]);
    }
    mesh
}

/// The first index of each position's bit-identical point: what the faces around a vertex are
/// gathered by when colours split one point into several entries.
fn points(positions: &[Vec3]) -> Vec<u32> {
    let mut first: HashMap<[u32; 3], u32> = HashMap::with_capacity(positions.len());
    (0..positions.len() as u32)
        .map(|v| {
            *first
                .entry(positions[v as usize].to_array().map(f32::to_bits))
                .or_insert(v)
        })
        .collect()
}

/// The smooth mesh: each corner's normal from the faces around its point, and one output
/// vertex for each vertex and distinct normal, numbered in the order of the first corner
/// (triangle by triangle, corner by corner) that uses it, as a reader going corner by corner
/// and making a vertex at each new (vertex, normal) would number them.
///
/// Every step runs on all cores: the corners of each vertex are met through the faces around
/// its point (listed in triangle order), so each vertex finds its own distinct normals and the
/// corners that first use them; a vertex's number is the count of first-using corners before
/// its own (a rank in a bit set over the corners).
fn smooth_normals(
    positions: &[Vec3],
    triangles: &[[u32; 3]],
    colors: Option<&[Vec3]>,
    weighted: &[Vec3],
    unit: &[Vec3],
) -> Mesh {
    let cos_crease = CREASE_ANGLE_DEGREES.to_radians().cos();
    let faces = FacesAround::new(positions, triangles, colors);
    let point = |v: u32| faces.point(v);
    let around = |p: usize| faces.around(p);
    // Points met by more than EXACT_DEGREE faces, summarised once each (see `Crowd`).
    let crowds: HashMap<usize, Crowd> = (0..positions.len())
        .into_par_iter()
        .filter(|&p| around(p).len() > EXACT_DEGREE)
        .map(|p| (p, Crowd::new(around(p), weighted, unit, cos_crease)))
        .collect();
    // The normal of vertex `v` at a corner of face `t`: face by face where the point has few
    // faces, else from its crowd.
    let normal_at = |t: usize, v: u32| -> Vec3 {
        let p = point(v);
        let sum = match crowds.get(&p) {
            Some(crowd) => crowd.sum_for(unit[t], cos_crease),
            None => {
                let mut sum = Vec3::ZERO;
                for &g in around(p) {
                    if unit[t] == Vec3::ZERO || unit[g as usize].dot(unit[t]) >= cos_crease {
                        sum += weighted[g as usize];
                    }
                }
                sum
            }
        };
        corner_normal(sum, around(p), unit)
    };
    // Each vertex's distinct normals in order of first use, each with the corner (3t + k) that
    // first uses it: made[made_start[v]..made_start[v + 1]].
    let chunks: Vec<MadeVertices> = (0..positions.len().div_ceil(VERTEX_RUN))
        .into_par_iter()
        .map(|chunk| {
            let vertices = chunk * VERTEX_RUN..((chunk + 1) * VERTEX_RUN).min(positions.len());
            let mut counts = Vec::with_capacity(vertices.len());
            let mut made: Vec<(u32, Vec3)> = Vec::with_capacity(vertices.len());
            for v in vertices {
                let v = v as u32;
                let first = made.len();
                let mut previous = None;
                for &g in around(point(v)) {
                    // A face with two corners at the point is listed twice: read it once.
                    if previous == Some(g) {
                        continue;
                    }
                    previous = Some(g);
                    for (k, &w) in triangles[g as usize].iter().enumerate() {
                        if w != v {
                            continue;
                        }
                        let n = normal_at(g as usize, v);
                        if !made[first..].iter().any(|&(_, m)| m == n) {
                            made.push((3 * g + k as u32, n));
                        }
                    }
                }
                counts.push((made.len() - first) as u32);
            }
            (counts, made)
        })
        .collect();
    let mut made_start = Vec::with_capacity(positions.len() + 1);
    made_start.push(0u32);
    let mut made = Vec::with_capacity(chunks.iter().map(|c| c.1.len()).sum());
    for (counts, chunk_made) in chunks {
        for count in counts {
            made_start.push(made_start.last().copied().unwrap_or(0) + count);
        }
        made.extend(chunk_made);
    }
    // Output vertex numbers: the rank of each first-using corner among them all.
    let corners = FirstCorners::new(triangles.len() * 3, made.iter().map(|&(c, _)| c));
    let numbers: Vec<u32> = made.par_iter().map(|&(c, _)| corners.rank(c)).collect();
    let mut mesh = Mesh {
        positions: vec![Vec3::ZERO; made.len()],
        normals: vec![Vec3::ZERO; made.len()],
        triangles: Vec::new(),
        colors: colors.map(|_| vec![Vec3::ZERO; made.len()]),
        uvs: None,
        flat: false,
    };
    for v in 0..positions.len() {
        for j in made_start[v] as usize..made_start[v + 1] as usize {
            let out = numbers[j] as usize;
            mesh.positions[out] = positions[v];
            mesh.normals[out] = made[j].1;
            if let (Some(out_colors), Some(colors)) = (&mut mesh.colors, colors) {
                out_colors[out] = colors[v];
            }
        }
    }
    // Each corner's vertex: its vertex's only one, or the first whose normal equals its own.
    mesh.triangles = triangles
        .par_iter()
        .enumerate()
        .map(|(t, tri)| {
            tri.map(|v| {
                let range = made_start[v as usize] as usize..made_start[v as usize + 1] as usize;
                if range.len() == 1 {
                    return numbers[range.start];
                }
                let n = normal_at(t, v);
                let j = range
                    .clone()
                    .find(|&j| made[j].1 == n)
                    .unwrap_or(range.start);
                numbers[j]
            })
        })
        .collect();
    mesh
}

/// A run of vertices' output vertices: how many each makes, then each one's first-using corner
/// (3t + k) and normal, vertex by vertex.
type MadeVertices = (Vec<u32>, Vec<(u32, Vec3)>);

/// The faces around each point of a mesh, in triangle order, a face once per corner at the
/// point. Without colours a mesh's positions are welded already, so each is its own point;
/// with colours, entries of one position are one point (the first of them).
struct FacesAround {
    /// The point of each vertex; `None`: each vertex is its own.
    point_of: Option<Vec<u32>>,
    /// Compressed rows: the faces around point p are `faces_of[start[p]..start[p + 1]]`.
    start: Vec<u32>,
    faces_of: Vec<u32>,
}

impl FacesAround {
    fn new(positions: &[Vec3], triangles: &[[u32; 3]], colors: Option<&[Vec3]>) -> FacesAround {
        let mut faces = FacesAround {
            point_of: colors.map(|_| points(positions)),
            start: vec![0u32; positions.len() + 1],
            faces_of: vec![0u32; triangles.len() * 3],
        };
        for tri in triangles {
            for &v in tri {
                let p = faces.point(v);
                faces.start[p + 1] += 1;
            }
        }
        for p in 0..positions.len() {
            faces.start[p + 1] += faces.start[p];
        }
        let mut fill = faces.start.clone();
        for (t, tri) in triangles.iter().enumerate() {
            for &v in tri {
                let p = faces.point(v);
                faces.faces_of[fill[p] as usize] = t as u32;
                fill[p] += 1;
            }
        }
        faces
    }

    /// The point of vertex `v`.
    #[inline]
    fn point(&self, v: u32) -> usize {
        self.point_of.as_ref().map_or(v, |p| p[v as usize]) as usize
    }

    /// The faces around point `p`, ascending.
    #[inline]
    fn around(&self, p: usize) -> &[u32] {
        &self.faces_of[self.start[p] as usize..self.start[p + 1] as usize]
    }
}

/// Vertices whose distinct normals are found together, on one core.
const VERTEX_RUN: usize = 1 << 12;

/// The corners that first use an output vertex, as a bit set over all corners with the count
/// of set bits before each word: the rank of a corner among them in constant time.
struct FirstCorners {
    words: Vec<u64>,
    before: Vec<u32>,
}

impl FirstCorners {
    /// The set of `first` corners among `corners`.
    fn new(corners: usize, first: impl Iterator<Item = u32>) -> FirstCorners {
        let mut words = vec![0u64; corners.div_ceil(64)];
        for c in first {
            words[c as usize / 64] |= 1 << (c % 64);
        }
        let mut before = Vec::with_capacity(words.len());
        let mut count = 0u32;
        for w in &words {
            before.push(count);
            count += w.count_ones();
        }
        FirstCorners { words, before }
    }

    /// How many of the set's corners come before corner `c`.
    fn rank(&self, c: u32) -> u32 {
        let (word, bit) = (c as usize / 64, c % 64);
        self.before[word] + (self.words[word] & ((1u64 << bit) - 1)).count_ones()
    }
}

/// The unit normal of a corner whose faces around sum to `sum`; when that has no direction,
/// the first of `around`'s faces that has one, or +Y.
fn corner_normal(sum: Vec3, around: &[u32], unit: &[Vec3]) -> Vec3 {
    let n = unit_or_zero(sum);
    if n != Vec3::ZERO {
        return n;
    }
    around
        .iter()
        .map(|&g| unit[g as usize])
        .find(|u| *u != Vec3::ZERO)
        .unwrap_or(Vec3::Y)
}

/// Faces around one point up to which each corner's normal is summed face by face: the work
/// is the square of a point's faces, bounded here by 64² a corner.
const EXACT_DEGREE: usize = 64;

/// Cells a side of each cube face that a crowded point's face normals are gathered into.
const CELLS: f32 = 16.0;

/// The faces around a point met by more than [`EXACT_DEGREE`] of them (a fan's centre, a
/// cone's apex), summarised once so that every corner there costs at most the number of
/// normal cells, not the number of faces: a 1.7 kB model of fans cost minutes before.
enum Crowd {
    /// Every face's normal within half the crease angle of their mean, so any two meet within
    /// it: each corner sums the same faces as the face-by-face rule, in the same order, so the
    /// result is the same to the bit.
    Smooth {
        /// Σ of the weighted normals of the faces with a direction (a corner of such a face).
        directed: Vec3,
        /// Σ of all the weighted normals (a corner of a degenerate face).
        all: Vec3,
    },
    /// Normals spread wider: the faces are gathered by the cell of their unit normal on a cube
    /// map, and a corner sums the cells whose mean normal meets its own cell's mean within the
    /// crease angle, an approximation of the face-by-face rule.
    Cells {
        /// Each cell's key, mean unit normal and Σ of weighted normals.
        cells: Vec<(u32, Vec3, Vec3)>,
        /// Σ of all the weighted normals (a corner of a degenerate face).
        all: Vec3,
    },
}

impl Crowd {
    fn new(around: &[u32], weighted: &[Vec3], unit: &[Vec3], cos_crease: f32) -> Crowd {
        let all = around
            .iter()
            .fold(Vec3::ZERO, |s, &g| s + weighted[g as usize]);
        let directed_faces = around.iter().filter(|&&g| unit[g as usize] != Vec3::ZERO);
        let mean = unit_or_zero(directed_faces.clone().map(|&g| unit[g as usize]).sum());
        // cos(half the crease angle), a little tighter so rounding cannot cross the rule.
        let half = (0.5 * cos_crease.clamp(-1.0, 1.0).acos() - 1.0e-3).cos();
        if mean != Vec3::ZERO
            && directed_faces
                .clone()
                .all(|&g| unit[g as usize].dot(mean) >= half)
        {
            let directed = directed_faces.fold(Vec3::ZERO, |s, &g| s + weighted[g as usize]);
            return Crowd::Smooth { directed, all };
        }
        let mut cells: Vec<(u32, Vec3, Vec3)> = Vec::new();
        for &g in directed_faces {
            let key = cell_of(unit[g as usize]);
            let at = match cells.iter().position(|c| c.0 == key) {
                Some(at) => at,
                None => {
                    cells.push((key, Vec3::ZERO, Vec3::ZERO));
                    cells.len() - 1
                }
            };
            cells[at].1 += unit[g as usize];
            cells[at].2 += weighted[g as usize];
        }
        for cell in &mut cells {
            cell.1 = unit_or_zero(cell.1);
        }
        Crowd::Cells { cells, all }
    }

    /// The summed normal of a corner of a face whose unit normal is `face`.
    fn sum_for(&self, face: Vec3, cos_crease: f32) -> Vec3 {
        match self {
            _ if face == Vec3::ZERO => match self {
                Crowd::Smooth { all, .. } | Crowd::Cells { all, .. } => *all,
            },
            Crowd::Smooth { directed, .. } => *directed,
            Crowd::Cells { cells, .. } => {
                let key = cell_of(face);
                let own = cells.iter().find(|c| c.0 == key).map_or(face, |c| c.1);
                cells
                    .iter()
                    .filter(|c| c.1.dot(own) >= cos_crease)
                    .fold(Vec3::ZERO, |s, c| s + c.2)
            }
        }
    }
}

/// The cube-map cell of unit vector `n`: its major axis and sign, and a [`CELLS`]² grid on that
/// face.
fn cell_of(n: Vec3) -> u32 {
    let a = n.abs();
    let (axis, major, u, v) = if a.x >= a.y && a.x >= a.z {
        (0, n.x, n.y, n.z)
    } else if a.y >= a.z {
        (1, n.y, n.z, n.x)
    } else {
        (2, n.z, n.x, n.y)
    };
    let grid = |c: f32| ((c / major.abs() * 0.5 + 0.5) * CELLS).clamp(0.0, CELLS - 1.0) as u32;
    let face = axis * 2 + u32::from(major < 0.0);
    (face * CELLS as u32 + grid(u)) * CELLS as u32 + grid(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fan of `n` triangles around the origin, its rim at height `rim` (0: a flat disc;
    /// above the centre's: a cone's apex).
    fn fan(n: u32, rim: f32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let mut positions = vec![Vec3::ZERO];
        for i in 0..n {
            let a = std::f32::consts::TAU * i as f32 / n as f32;
            positions.push(Vec3::new(a.cos(), rim, -a.sin()));
        }
        let triangles = (0..n).map(|i| [0, 1 + i, 1 + (i + 1) % n]).collect();
        (positions, triangles)
    }

    /// The centre's normal by the face-by-face rule, for a corner of face `t`.
    fn exact_sum(positions: &[Vec3], triangles: &[[u32; 3]], t: usize) -> Vec3 {
        let cos = CREASE_ANGLE_DEGREES.to_radians().cos();
        let unit = |t: &[u32; 3]| unit_or_zero(area_weighted_normal(positions, *t));
        let own = unit(&triangles[t]);
        triangles
            .iter()
            .filter(|g| unit(g).dot(own) >= cos)
            .map(|g| area_weighted_normal(positions, *g))
            .sum()
    }

    #[test]
    fn a_crowded_smooth_point_gets_the_face_by_face_normal_to_the_bit() {
        // 200 faces around the centre of a shallow cone: all within 30° of their mean.
        let (positions, triangles) = fan(200, -0.3);
        let mesh = with_colors_and_normals(&positions, &triangles, None, true);
        let centre = mesh
            .positions
            .iter()
            .position(|p| *p == Vec3::ZERO)
            .expect("the centre");
        let expected = unit_or_zero(exact_sum(&positions, &triangles, 0));
        assert_eq!(mesh.normals[centre], expected);
        // One vertex for the centre: every corner there got the same normal.
        assert_eq!(
            mesh.positions.iter().filter(|p| **p == Vec3::ZERO).count(),
            1
        );
    }

    #[test]
    fn a_crowded_sharp_point_is_summed_by_normal_cells() {
        // A cone's apex with 20,000 faces whose normals turn all the way round: face by face
        // that is 20,000² tests. By cells, each corner's normal stays within a cell's width
        // (about 6°) of the exact rule's.
        let (positions, triangles) = fan(20_000, -2.0);
        let mesh = with_colors_and_normals(&positions, &triangles, None, true);
        for t in [0, 5_000, 12_345] {
            let exact = unit_or_zero(exact_sum(&positions, &triangles, t));
            let corner = mesh.triangles[t][0] as usize;
            assert_eq!(mesh.positions[corner], Vec3::ZERO);
            let angle = mesh.normals[corner]
                .dot(exact)
                .clamp(-1.0, 1.0)
                .acos()
                .to_degrees();
            assert!(angle < 6.0, "face {t}: {angle}° from the exact normal");
        }
    }

    #[test]
    fn a_normal_too_short_for_f32_counts_as_missing() {
        for v in [
            Vec3::new(2e-22, 0.0, 0.0),
            Vec3::new(1e-20, 1e-20, 1e-20),
            Vec3::ZERO,
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(f32::INFINITY, 0.0, 0.0),
        ] {
            assert_eq!(unit_or_zero(v), Vec3::ZERO, "{v}");
        }
        // The shortest that still normalizes comes out unit length.
        let short = Vec3::new(2e-19, 0.0, 0.0);
        assert!((unit_or_zero(short).length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn ordinary_normals_keep_glam_bits() {
        let mut x = 0.1f32;
        for _ in 0..1000 {
            x = (x * 3.7 + 0.13).fract();
            let v = Vec3::new(x - 0.5, (x * 7.0).fract() - 0.2, (x * 13.0).fract() * 3.0);
            assert_eq!(unit_or_zero(v), v.normalize_or_zero(), "{v}");
        }
    }

    #[test]
    fn a_tiny_triangle_takes_its_neighbours_normal() {
        // A unit right triangle in XY, and beside it one whose cross product is subnormal.
        let positions = [
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::new(1e-20, 0.0, 0.0),
            Vec3::new(0.0, 1e-20, 0.0),
        ];
        let mesh = with_normals(&positions, &[[0, 1, 2], [0, 3, 4]], true);
        for n in &mesh.normals {
            assert!((n.length() - 1.0).abs() < 1e-6, "{n}");
        }
    }

    /// The join as it was before it ran on all cores, corner by corner: the reference the
    /// parallel join must match to the bit (vertex order included).
    fn serial_smooth_normals(case: &Case) -> Mesh {
        let (positions, triangles, colors) = (&case.0[..], &case.1[..], case.2.as_deref());
        let (weighted, unit) = face_normals(triangles, positions);
        let cos_crease = CREASE_ANGLE_DEGREES.to_radians().cos();
        let faces = FacesAround::new(positions, triangles, colors);
        let point = |v: u32| faces.point(v);

        let mut mesh = Mesh {
            positions: Vec::with_capacity(positions.len()),
            normals: Vec::with_capacity(positions.len()),
            triangles: Vec::with_capacity(triangles.len()),
            colors: colors.map(|_| Vec::with_capacity(positions.len())),
            uvs: None,
            flat: false,
        };
        // The output vertices made for each welded vertex, as chains: `first_made[v]` is the first
        // (or NONE), `next_made[o]` the one made after output vertex `o` for the same welded
        // vertex. Two u32 a vertex, where a list per vertex cost some 90 bytes.
        const NONE: u32 = u32::MAX;
        let mut first_made = vec![NONE; positions.len()];
        let mut next_made: Vec<u32> = Vec::with_capacity(positions.len());
        // Points met by more than EXACT_DEGREE faces, summarised once each (see `Crowd`).
        let mut crowds: HashMap<usize, Crowd> = HashMap::new();
        let around = |p: usize| faces.around(p);
        // A corner's normal from the faces around its point, when they are few (each corner on its
        // own: the corners of a run of triangles are computed on all cores, then joined in order).
        let exact = |t: usize, v: u32| -> Option<Vec3> {
            let around = around(point(v));
            (around.len() <= EXACT_DEGREE).then(|| {
                let mut sum = Vec3::ZERO;
                for &g in around {
                    if unit[t] == Vec3::ZERO || unit[g as usize].dot(unit[t]) >= cos_crease {
                        sum += weighted[g as usize];
                    }
                }
                corner_normal(sum, around, &unit)
            })
        };
        for (run, tris) in triangles.chunks(1 << 14).enumerate() {
            let first = run * (1 << 14);
            let normals: Vec<[Option<Vec3>; 3]> = tris
                .par_iter()
                .enumerate()
                .map(|(k, tri)| tri.map(|v| exact(first + k, v)))
                .collect();
            for (k, (tri, corner_normals)) in tris.iter().zip(normals).enumerate() {
                let t = first + k;
                let mut out = [0u32; 3];
                for (corner, &v) in tri.iter().enumerate() {
                    let n = corner_normals[corner].unwrap_or_else(|| {
                        let p = point(v);
                        let sum = crowds
                            .entry(p)
                            .or_insert_with(|| Crowd::new(around(p), &weighted, &unit, cos_crease))
                            .sum_for(unit[t], cos_crease);
                        corner_normal(sum, around(p), &unit)
                    });
                    let mut made = first_made[v as usize];
                    let mut last = NONE;
                    while made != NONE && mesh.normals[made as usize] != n {
                        last = made;
                        made = next_made[made as usize];
                    }
                    if made == NONE {
                        made = mesh.positions.len() as u32;
                        mesh.positions.push(positions[v as usize]);
                        mesh.normals.push(n);
                        if let (Some(out), Some(colors)) = (&mut mesh.colors, colors) {
                            out.push(colors[v as usize]);
                        }
                        next_made.push(NONE);
                        match last {
                            NONE => first_made[v as usize] = made,
                            _ => next_made[last as usize] = made,
                        }
                    }
                    out[corner] = made;
                }
                mesh.triangles.push(out);
            }
        }
        mesh
    }

    /// Positions, triangles and maybe a colour per position.
    type Case = (Vec<Vec3>, Vec<[u32; 3]>, Option<Vec<Vec3>>);

    /// A random mesh on a small grid of points (so faces share them, cross creases and are
    /// sometimes degenerate), with a colour per position when `colors`: positions repeated
    /// with different colours split points into several entries.
    fn random_mesh(seed: u64, colors: bool) -> Case {
        let mut next = crate::test_draws::below(seed);
        let grid: Vec<Vec3> = (0..27)
            .map(|i| Vec3::new((i % 3) as f32, (i / 3 % 3) as f32, (i / 9) as f32 * 0.5))
            .collect();
        let count = 40 + next(200) as usize;
        let positions: Vec<Vec3> = (0..count).map(|_| grid[next(27) as usize]).collect();
        let colours = colors.then(|| {
            (0..count)
                .map(|_| Vec3::splat(next(3) as f32 / 2.0))
                .collect()
        });
        // Without colours the positions of a mesh are welded: keep the first of each.
        let positions = if colors {
            positions
        } else {
            let mut seen = Vec::new();
            for p in positions {
                if !seen.contains(&p) {
                    seen.push(p);
                }
            }
            seen
        };
        let n = positions.len() as u64;
        let triangles = (0..50 + next(400))
            .map(|_| [next(n) as u32, next(n) as u32, next(n) as u32])
            .collect();
        (positions, triangles, colours)
    }

    #[test]
    fn the_parallel_join_matches_the_corner_by_corner_join_to_the_bit() {
        let crowded = fan(300, -2.0);
        let mut cases: Vec<Case> = (0..200)
            .map(|seed| random_mesh(seed, seed % 2 == 1))
            .collect();
        cases.push((crowded.0, crowded.1, None));
        let mut split = 0;
        for (positions, triangles, colors) in &cases {
            let parallel = with_colors_and_normals(positions, triangles, colors.as_deref(), true);
            let serial =
                serial_smooth_normals(&(positions.clone(), triangles.clone(), colors.clone()));
            let bits = |m: &Mesh| {
                let v = |p: &Vec<Vec3>| p.iter().map(|p| p.to_array().map(f32::to_bits)).collect();
                let c: Option<Vec<[u32; 3]>> = m.colors.as_ref().map(v);
                (v(&m.positions), v(&m.normals), c, m.triangles.clone())
            };
            assert_eq!(bits(&parallel), bits(&serial));
            split += usize::from(parallel.positions.len() > positions.len());
        }
        // The cases do split vertices at creases (else the test would check little).
        assert!(split > 100, "{split}");
    }
}
