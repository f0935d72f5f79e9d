//! The one memory budget every input is held to: what loading a scene or model and rendering it
//! will take, estimated from counts known before the memory is allocated (triangles and world
//! objects after instancing, texture texels, frame pixels), against one stated bound.
//!
//! All figures are bytes of peak resident memory (decimal: 1 GB = 10^9 bytes), as
//! `/usr/bin/time -v` reports its "maximum resident set size". The per-item costs are measured
//! worst cases (see the README's "Memory budget" for the runs), so an estimate within the bound
//! keeps the process within it, whichever algorithm draws the world.

use std::fmt;
use std::path::{Path, PathBuf};

use std::sync::Arc;

use crate::mesh::texture::Texture;
use crate::world::World;

/// The bound a load and a render keep within, bytes of peak resident memory (6 GB, a quarter of
/// a 24 GiB machine: room for [`MAX_TRIANGLES`], 11.3M triangles, so a 10M-triangle scan opens),
/// unless the environment variable [`BOUND_VARIABLE`] sets another.
pub const MEMORY_BOUND: u64 = 6_000_000_000;

/// The environment variable that sets the bound instead of [`MEMORY_BOUND`]: bytes, or a
/// number with `K`, `M` or `G` (decimal), as `RASTRAY_MEMORY_BOUND=2G`.
pub const BOUND_VARIABLE: &str = "RASTRAY_MEMORY_BOUND";

/// What the process takes before any scene: the program, its threads and the allocator, bytes.
pub const BASE_BYTES: u64 = 120_000_000;

/// Bytes one triangle costs at most, from the file to the rendered frame: the loaded model and
/// the world's flat-shaded mesh (about 150), then the Z-buffer's screen triangle, corners and
/// binned copies when every triangle survives culling (about 320), which is more than the ray
/// tracer's BVH adds; and texture coordinates (48). Measured 473 untextured on glTF node trees
/// of 2,000-triangle meshes rendered with Gouraud. One large mesh costs less: the 9M-triangle
/// scan of `scripts/big-scan-ply.py` filling a 960×540 frame at 8×8 samples measured 281 flat
/// and 209 smooth (Phong and Gouraud alike); `tests/memory_budget.rs` checks a smaller one.
pub const BYTES_PER_TRIANGLE: u64 = 520;

/// Bytes one triangle of a scan (a smooth mesh on shared vertices, about half a vertex a
/// triangle) costs at the peak of a one-off ray-traced render, beyond the program: the world's
/// mesh (a position and a normal a vertex, three indices: about 24), then at the end of its BVH
/// build the BVH's triangles in leaf order (64), their mesh indices (4) and the inner nodes, as
/// built and joined (about 2 × 12). Measured 122 on the 9M-triangle scan of
/// `scripts/big-scan-ply.py` (1.09 GB), 119 at 10M (1.19 GB); `tests/memory_budget.rs` checks a
/// 1.6M-triangle one (163: the program's own growth is a larger share there). The budget counts [`BYTES_PER_TRIANGLE`], which holds for every
/// algorithm.
pub const RAY_BYTES_PER_TRIANGLE: u64 = 150;

/// Bytes one world object costs beyond its triangles: its mesh, distinct positions and bounds,
/// the model part it came from, and the Z-buffer's setup task and projected vertices for it.
/// Measured 1.8 kB on glTF node trees of 65,535 instances of a 2- and a 34-triangle mesh.
pub const BYTES_PER_OBJECT: u64 = 2_000;

/// Bytes one instance of a shared mesh costs (a glTF mesh that several nodes name): its
/// placement in the model, its world object (an empty mesh, bounds and the maps in and out of
/// the mesh's space), its label and the ray tracer's leaf for it. Its triangles are the shared
/// mesh's, counted once at [`BYTES_PER_TRIANGLE`].
pub const BYTES_PER_INSTANCE: u64 = 1_000;

/// Bytes each triangle an instance places costs while the Z-buffer draws it: the placed copy of
/// the instance's mesh (positions, normals, distinct positions and its object) and the screen
/// triangle, corners and binned copies when every triangle survives culling. Measured 487 on
/// the node tree of 262,143 instances of a 34-triangle fan (Gouraud at 64×48: 4.72 GB, Phong
/// 4.62 GB). The ray tracer places nothing (it moves rays into the shared mesh's space: 0.35 GB
/// there), but the budget holds whichever algorithm draws the world, so placed triangles are
/// counted for all.
pub const BYTES_PER_PLACED_TRIANGLE: u64 = 500;

/// Bytes one pixel of a still image costs while it renders and is written: the frame's linear
/// RGB and alpha (16) and the encoder's copy. Measured 41 for OpenEXR with alpha (the worst),
/// 35 for a 16-bit PNG with alpha and 15 for an 8-bit PNG, at 4096×4096.
pub const BYTES_PER_STILL_PIXEL: u64 = 42;

/// Bytes one pixel of a turntable frame in flight costs: the frame being rendered (16) and two
/// encoder-ready copies, one waiting and one being written (one to eight bytes each, with the
/// GIF quantizer's working copy).
pub const BYTES_PER_ANIMATION_PIXEL: u64 = 32;

/// Most triangles a world may hold under the default bound: what [`MEMORY_BOUND`] leaves,
/// after the program, for triangles at their worst cost ([`BYTES_PER_TRIANGLE`]). Loaders refuse
/// a file past it before reading its triangles. A world is held to the bound in force by its
/// full estimate ([`Estimate::check`]: triangles, objects, textures), and to
/// [`TRIANGLE_INDEX_LIMIT`] whatever the bound.
pub const MAX_TRIANGLES: u64 = triangles_within(MEMORY_BOUND);

/// Most triangles any bound allows: the Z-buffer carries a triangle's index in 24 bits.
pub const TRIANGLE_INDEX_LIMIT: u64 = (1 << 24) - 1;

/// Most triangles `bound` bytes hold beside the program, at [`BYTES_PER_TRIANGLE`] each (and at
/// most [`TRIANGLE_INDEX_LIMIT`]).
pub const fn triangles_within(bound: u64) -> u64 {
    let triangles = bound.saturating_sub(BASE_BYTES) / BYTES_PER_TRIANGLE;
    if triangles < TRIANGLE_INDEX_LIMIT {
        triangles
    } else {
        TRIANGLE_INDEX_LIMIT
    }
}

/// Most triangles a model file may hold under the bound in force ([`memory_bound`]): what that
/// bound leaves beside the program at [`BYTES_PER_TRIANGLE`] each, at most
/// [`TRIANGLE_INDEX_LIMIT`]; [`MAX_TRIANGLES`] under the default bound. Loaders refuse a file past
/// it before reading its triangles.
pub fn triangle_cap() -> u64 {
    triangles_within(memory_bound())
}

/// The bound in force: [`BOUND_VARIABLE`] when set to a valid size, else [`MEMORY_BOUND`].
pub fn memory_bound() -> u64 {
    std::env::var(BOUND_VARIABLE)
        .ok()
        .and_then(|text| parse_bytes(&text))
        .unwrap_or(MEMORY_BOUND)
}

/// `text` as bytes: a whole number, optionally followed by `K`, `M` or `G` (powers of 1000).
fn parse_bytes(text: &str) -> Option<u64> {
    let text = text.trim();
    let (digits, unit) = match text.char_indices().last()? {
        (at, 'k' | 'K') => (&text[..at], 1_000),
        (at, 'm' | 'M') => (&text[..at], 1_000_000),
        (at, 'g' | 'G') => (&text[..at], 1_000_000_000),
        _ => (text, 1),
    };
    digits.trim().parse::<u64>().ok()?.checked_mul(unit)
}

/// What a load and a render will hold at their peak, as counts.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Estimate {
    /// Triangles stored, after triangulation and subdivision: a mesh that instances share
    /// counts once.
    pub triangles: u64,
    /// World objects with a mesh of their own: one per primitive object, one per part (glTF
    /// primitive drawn once, OBJ material group) of a model.
    pub objects: u64,
    /// World objects that are instances of a shared mesh (a glTF mesh several nodes name).
    pub instances: u64,
    /// Triangles the instances place in the world (each instance its shared mesh's).
    pub placed_triangles: u64,
    /// Bytes of decoded textures: 8 a texel (16-bit linear RGBA) of each image's base level and
    /// of its mip chain (a third as many texels).
    pub texture_bytes: u64,
    /// Bytes of the frames being rendered and written.
    pub frame_bytes: u64,
}

impl Estimate {
    /// The counts of a built `world`: its triangles, objects and distinct textures.
    pub fn of_world(world: &World) -> Estimate {
        let texture_bytes = distinct_texture_bytes(
            world
                .objects
                .iter()
                .filter_map(|o| o.appearance.base_color.as_ref())
                .map(|binding| binding.texture.clone()),
        );
        let instances = world.objects.iter().filter(|o| o.instance.is_some());
        let placed_triangles = instances
            .clone()
            .map(|o| o.local_mesh().triangle_count() as u64)
            .sum();
        let instances = instances.count() as u64;
        Estimate {
            triangles: world.stored_triangle_count() as u64,
            objects: world.objects.len() as u64 - instances,
            instances,
            placed_triangles,
            texture_bytes,
            frame_bytes: 0,
        }
    }

    /// This estimate with `frames` frames of `pixels` pixels each in flight, at `per_pixel`
    /// bytes a pixel ([`BYTES_PER_STILL_PIXEL`] or [`BYTES_PER_ANIMATION_PIXEL`]).
    pub fn with_frames(self, frames: u64, pixels: u64, per_pixel: u64) -> Estimate {
        Estimate {
            frame_bytes: frames.saturating_mul(pixels).saturating_mul(per_pixel),
            ..self
        }
    }

    /// Estimated peak bytes: the program, the triangles, objects, instances and the
    /// triangles they place, textures and frames.
    pub fn bytes(&self) -> u64 {
        BASE_BYTES
            .saturating_add(self.triangles.saturating_mul(BYTES_PER_TRIANGLE))
            .saturating_add(self.objects.saturating_mul(BYTES_PER_OBJECT))
            .saturating_add(self.instances.saturating_mul(BYTES_PER_INSTANCE))
            .saturating_add(
                self.placed_triangles
                    .saturating_mul(BYTES_PER_PLACED_TRIANGLE),
            )
            .saturating_add(self.texture_bytes)
            .saturating_add(self.frame_bytes)
    }

    /// `Ok` when the estimate is within the bound in force ([`memory_bound`]); else the figures,
    /// naming `file`, the input they were counted for.
    pub fn check(&self, file: &Path) -> Result<(), OverBudget> {
        let bound = memory_bound();
        if self.bytes() <= bound {
            return Ok(());
        }
        Err(OverBudget {
            file: file.to_path_buf(),
            estimate: *self,
            bound,
        })
    }
}

/// Bytes of `textures` with their mip chains, each texture counted once however many parts
/// share it.
pub fn distinct_texture_bytes(textures: impl Iterator<Item = Arc<Texture>>) -> u64 {
    let mut textures: Vec<(*const Texture, u64)> = textures
        .map(|texture| (Arc::as_ptr(&texture), texture.memory_bytes() as u64))
        .collect();
    textures.sort_unstable_by_key(|&(at, _)| at);
    textures.dedup_by_key(|&mut (at, _)| at);
    textures.iter().map(|&(_, bytes)| bytes).sum()
}

/// How many turntable frames of `pixels` pixels may render at once beside `world` (its
/// estimate): as many as the bound leaves room for, at least one and at most `threads`.
pub fn frames_in_flight(world: &Estimate, pixels: u64, threads: usize) -> usize {
    let left = memory_bound().saturating_sub(world.bytes());
    // Each frame in flight also waits once in the writer's queue, ready to write.
    let per_frame = pixels.saturating_mul(BYTES_PER_ANIMATION_PIXEL).max(1);
    ((left / per_frame) as usize).clamp(1, threads.max(1))
}

/// A load or render whose estimate passes the bound: exit code 2, with the figures.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct OverBudget {
    /// The input the estimate was counted for.
    pub file: PathBuf,
    pub estimate: Estimate,
    /// The bound in force, bytes.
    pub bound: u64,
}

impl OverBudget {
    /// The figures without the file's name, for messages that name it already.
    pub fn figures(&self) -> String {
        let e = &self.estimate;
        let mut text = format!("{} triangles in {} objects", e.triangles, e.objects);
        if e.instances > 0 {
            text += &format!(
                ", {} instances placing {} triangles",
                e.instances, e.placed_triangles
            );
        }
        if e.texture_bytes > 0 {
            text += &format!(", {} of textures", gigabytes(e.texture_bytes));
        }
        if e.frame_bytes > 0 {
            text += &format!(", {} of frames", gigabytes(e.frame_bytes));
        }
        text + &format!(
            " would take about {} ({} bytes) to load and render; the memory bound is {} ({} bytes; {BOUND_VARIABLE} sets another)",
            gigabytes(e.bytes()),
            e.bytes(),
            gigabytes(self.bound),
            self.bound
        )
    }
}

impl fmt::Display for OverBudget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}: {}",
            crate::text_escape::Escaped(&self.file.display().to_string()),
            self.figures()
        )
    }
}

/// `bytes` as decimal gigabytes, two decimals: "4.80 GB".
fn gigabytes(bytes: u64) -> String {
    format!("{:.2} GB", bytes as f64 / 1e9)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_triangle_cap_follows_from_the_bound() {
        // (6 GB − 0.12 GB) / 520 bytes: a 10M-triangle scan fits.
        assert_eq!(MAX_TRIANGLES, 11_307_692);
        assert_eq!(triangles_within(4_800_000_000), 9_000_000);
        assert_eq!(triangles_within(100_000_000_000), TRIANGLE_INDEX_LIMIT);
        assert_eq!(triangles_within(0), 0);
        let at_cap = Estimate {
            triangles: MAX_TRIANGLES,
            ..Estimate::default()
        };
        assert!(at_cap.bytes() <= MEMORY_BOUND);
        let past = Estimate {
            triangles: MAX_TRIANGLES + 1,
            ..at_cap
        };
        assert!(past.bytes() > MEMORY_BOUND);
    }

    #[test]
    fn sizes_read_with_decimal_units() {
        assert_eq!(parse_bytes("2G"), Some(2_000_000_000));
        assert_eq!(parse_bytes(" 300 M"), Some(300_000_000));
        assert_eq!(parse_bytes("1500"), Some(1500));
        assert_eq!(parse_bytes("k"), None);
        assert_eq!(parse_bytes("2T"), None);
        assert_eq!(parse_bytes("99999999999999999999G"), None);
    }

    #[test]
    fn objects_and_frames_count_toward_the_bound() {
        // The node-tree GLB: 262,143 instances of a 34-triangle mesh, against a bound of
        // 4.8 GB (`RASTRAY_MEMORY_BOUND=4800M`). Baked, each instance its own object, it would
        // pass the bound; shared, it keeps within it.
        let bound = 4_800_000_000;
        let baked = Estimate {
            triangles: 262_143 * 34,
            objects: 262_143,
            ..Estimate::default()
        };
        assert!(baked.bytes() > bound, "{}", baked.bytes());
        // Shared, it stores 34 triangles, but the Z-buffer places all 8.9M: still past it
        // (4.84 GB), though within the default bound.
        let tree = Estimate {
            triangles: 34,
            instances: 262_143,
            placed_triangles: 262_143 * 34,
            ..Estimate::default()
        };
        assert!(tree.bytes() > bound, "{}", tree.bytes());
        assert!(tree.bytes() < MEMORY_BOUND, "{}", tree.bytes());
        assert!(tree.bytes() < baked.bytes());
        // Two levels fewer, a quarter of it, keeps well within.
        let smaller = Estimate {
            triangles: 34,
            instances: 65_535,
            placed_triangles: 65_535 * 34,
            ..Estimate::default()
        };
        assert!(smaller.bytes() < MEMORY_BOUND / 3, "{}", smaller.bytes());
        let one = Estimate {
            triangles: 12,
            objects: 1,
            ..Estimate::default()
        };
        let still = one.with_frames(1, 8192 * 8192, BYTES_PER_STILL_PIXEL);
        assert_eq!(
            still.bytes() - one.bytes(),
            8192 * 8192 * BYTES_PER_STILL_PIXEL
        );
    }

    #[test]
    fn frames_in_flight_fit_the_room_the_world_leaves() {
        let small = Estimate::default();
        assert_eq!(frames_in_flight(&small, 640 * 480, 2), 2);
        // At the sample cap (8192×8192 pixels) one frame takes 2.1 GB: two of them beside a
        // world of 2.2 GB would pass 6 GB.
        let world = Estimate {
            triangles: 4_000_000,
            ..small
        };
        assert_eq!(frames_in_flight(&world, 8192 * 8192, 2), 1);
        // Never none: a frame that does not fit is refused by the render's own check.
        let full = Estimate {
            triangles: MAX_TRIANGLES,
            ..small
        };
        assert_eq!(frames_in_flight(&full, 8192 * 8192, 8), 1);
    }
}
