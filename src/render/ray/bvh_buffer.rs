//! The one large allocation of a BVH build: the prims live in its upper half while the tree is
//! built, and are then turned, in place, into the triangles in leaf order, which fill it whole.
//!
//! A prim is 32 bytes and a triangle 64, so n triangles fill the room of 2n prims. Building the
//! triangles over the prims they come from, rather than into an array of their own, spares the
//! build a fresh 32·n bytes, the page faults that come with them and their release (42 MB for
//! the 1.31M-triangle icosphere, whose build this made 6% faster on one thread: median of 25
//! builds alternating with the former two arrays in one process). The allocation is reserved as
//! zero pages, so nothing is written twice but the upper half, prims first and triangles last.

use glam::Vec3A;
use rayon::prelude::*;

use super::bvh_prims::Prim;
use super::intersect::Triangle;
use crate::huge_pages;
use crate::mesh::Mesh;
use crate::render::prefetch;

/// Triangles per parallel task.
const CHUNK: usize = 4096;

/// Room for `n` triangles, whose upper half holds the prims of the build.
pub struct BuildBuffer {
    /// 2·n prims, all zero until written: triangles 0..n/2 own the lower half.
    slots: Vec<Prim>,
}

impl BuildBuffer {
    /// A buffer for `mesh`'s triangles, its prims set from their boxes.
    pub fn new(mesh: &Mesh) -> BuildBuffer {
        let n = mesh.triangles.len();
        let mut slots = bytemuck::zeroed_vec::<Prim>(2 * n);
        huge_pages::advise(&mut slots);
        slots[n..]
            .par_iter_mut()
            .with_min_len(CHUNK)
            .enumerate()
            .for_each(|(t, p)| {
                let [a, b, c] = mesh.corners(t).map(Vec3A::from);
                *p = Prim::new(a.min(b).min(c), a.max(b).max(c), t as u32);
            });
        BuildBuffer { slots }
    }

    /// The prims (one per triangle), for the build to reorder.
    pub fn prims(&mut self) -> &mut [Prim] {
        let n = self.slots.len() / 2;
        &mut self.slots[n..]
    }

    /// The triangles of `mesh` in the order of the prims, and their mesh indices.
    ///
    /// Triangle k takes prim slots 2k and 2k + 1 and comes from prim k, in slot n + k. Taken in
    /// rounds of ascending k, each round's triangles land below the prims it reads (2·end ≤
    /// n + start), and every prim a later round reads lies above them. The last few thousand
    /// are taken one by one, in ascending order: each prim is read before its slot is written.
    pub fn into_triangles(mut self, mesh: &Mesh) -> (Vec<Triangle>, Vec<u32>) {
        let n = self.slots.len() / 2;
        let mut ids = vec![0u32; n];
        huge_pages::advise(&mut ids);
        let mut start = 0;
        loop {
            let end = (n + start) / 2;
            if end - start < CHUNK {
                break;
            }
            let (out, prims) = self.slots.split_at_mut(n + start);
            let triangles: &mut [Triangle] = bytemuck::cast_slice_mut(&mut out[2 * start..2 * end]);
            triangles
                .par_chunks_mut(CHUNK)
                .zip(ids[start..end].par_chunks_mut(CHUNK))
                .zip(prims[..end - start].par_chunks(CHUNK))
                .for_each(|((triangles, ids), prims)| fill(mesh, prims, triangles, ids));
            start = end;
        }
        for k in start..n {
            let p = self.slots[n + k];
            let triangles: &mut [Triangle] = bytemuck::cast_slice_mut(&mut self.slots);
            triangles[k] = triangle(mesh, &p);
            ids[k] = p.index();
        }
        (bytemuck::cast_vec(self.slots), ids)
    }
}

/// Prims this many places ahead have their mesh triangle's vertex indices fetched …
const INDICES_AHEAD: usize = 16;
/// … and this many places ahead, their corners: the prims are in leaf order, so a triangle's
/// corners lie anywhere in the mesh, and each would otherwise be a wait.
const CORNERS_AHEAD: usize = 8;

/// Sets `triangles` and `ids` from `prims`, one each, asking for the mesh data of the prims a
/// few places ahead while it works (the icosphere's triangles took 22–32 ms without the hints
/// and 14–22 ms with them, the bunny's 0.7–2.1 ms and 0.5–1.3 ms; builds alternating).
fn fill(mesh: &Mesh, prims: &[Prim], triangles: &mut [Triangle], ids: &mut [u32]) {
    for (k, (t, id)) in triangles.iter_mut().zip(ids).enumerate() {
        if let Some(p) = prims.get(k + INDICES_AHEAD) {
            prefetch::ahead(&mesh.triangles[p.index() as usize]);
        }
        if let Some(p) = prims.get(k + CORNERS_AHEAD) {
            for v in mesh.triangles[p.index() as usize] {
                prefetch::ahead(&mesh.positions[v as usize]);
            }
        }
        *t = triangle(mesh, &prims[k]);
        *id = prims[k].index();
    }
}

fn triangle(mesh: &Mesh, p: &Prim) -> Triangle {
    let [a, b, c] = mesh.corners(p.index() as usize);
    Triangle::new(a, b, c)
}
