//! Alpha cut-outs (glTF `alphaMode: MASK`) for rays: a hit on a masked object whose alpha is
//! below its cutoff is no surface, so the ray goes on past it, primary, reflected and shadow
//! rays alike. Built on the scene's queries as they are (nearest hit, any hit): a cut hit
//! asks again from just beyond it, so the acceleration structure knows nothing of alpha.
//!
//! Worlds without a masked object take one branch here and trace exactly as before.

use glam::Vec3;

use super::accel::{Hit, SceneAccel};
use super::half_line::Ray;
use super::packet::{PacketHits, RayPacket};
use crate::render::simd::{F32x8, V3, WIDTH};
use crate::render::texturing::ObjectTextures;
use crate::world::World;

/// Most cut-out surfaces a ray passes through; beyond them it sees nothing (and a shadow ray is
/// unblocked): bounds the work of a ray through a dense stack of cut-outs.
const MAX_CUTS: u32 = 64;

/// Where a ray goes on from past a cut-out hit at `t`: a few units in the last place beyond, so
/// that the triangle just cut (whose t an edge's `f64` test may round a unit differently) is not
/// met again.
#[inline]
fn beyond(t: f32) -> f32 {
    t + t.abs() * (4.0 * f32::EPSILON)
}

/// The queries of a scene with its masked objects cut out.
pub struct CutScene<'a> {
    pub accel: &'a SceneAccel,
    pub world: &'a World,
    pub textures: &'a ObjectTextures<'a>,
}

impl CutScene<'_> {
    /// Whether `hit`, at path length `path` (the cone's length at the ray's origin plus the
    /// hit's t) along unit `dir`, is cut out.
    #[inline]
    fn cuts(&self, object: u32, triangle: u32, u: f32, v: f32, path: f32, dir: Vec3) -> bool {
        let mesh = self.world.objects[object as usize].local_mesh();
        self.textures
            .is_cut(object as usize, mesh, triangle, u, v, path, dir)
    }

    /// The nearest hit of each ray of `packet` that is not cut out; `path` is how far each
    /// ray's cone has come before its origin. [`SceneAccel::intersect_packet`] where no object
    /// is masked.
    #[inline]
    pub fn intersect_packet(&self, packet: &RayPacket, path: &[f32; WIDTH]) -> PacketHits {
        let mut hits = self.accel.intersect_packet(packet);
        if !self.textures.any_mask {
            return hits;
        }
        let dirs = packet.dir.to_vec3s();
        let mut pending = hits.hit().move_mask() as u32;
        for round in 0..=MAX_CUTS {
            let (t, u, v) = (hits.t.to_array(), hits.u.to_array(), hits.v.to_array());
            let (object, triangle) = (hits.object.to_array(), hits.triangle.to_array());
            let cut = (0..WIDTH)
                .filter(|&k| pending & 1 << k != 0)
                .filter(|&k| {
                    self.textures.is_masked(object[k] as usize)
                        && self.cuts(object[k], triangle[k], u[k], v[k], path[k] + t[k], dirs[k])
                })
                .fold(0u32, |lanes, k| lanes | 1 << k);
            if cut == 0 {
                break;
            }
            if round == MAX_CUTS {
                hits = take_lanes(&hits, &PacketHits::none(), cut);
                break;
            }
            let mut further = *packet;
            let past = F32x8::from(t.map(beyond));
            further.t_min = lane_mask(cut).blend(past, packet.t_min);
            let further = self.accel.intersect_packet(&further);
            hits = take_lanes(&hits, &further, cut);
            pending = cut & hits.hit().move_mask() as u32;
        }
        hits
    }

    /// The nearest hit of `ray` beyond `t_min` that is not cut out; `path` as for
    /// [`CutScene::intersect_packet`].
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_min: f32, path: f32) -> Option<Hit> {
        let mut hit = self.accel.intersect(ray, t_min, f32::INFINITY)?;
        if !self.textures.any_mask {
            return Some(hit);
        }
        let dir = Vec3::from(ray.dir);
        for _ in 0..MAX_CUTS {
            if !self.cuts(hit.object, hit.triangle, hit.u, hit.v, path + hit.t, dir) {
                return Some(hit);
            }
            hit = self.accel.intersect(ray, beyond(hit.t), f32::INFINITY)?;
        }
        None
    }

    /// Whether anything not cut out lies on the segment from `from` to `to`; `path` is how far
    /// the cone has come at `from`.
    pub fn occluded(&self, from: Vec3, to: Vec3, path: f32) -> bool {
        self.accel.occluded(from, to) && (!self.textures.any_mask || self.blocked(from, to, path))
    }

    /// The lanes of `wanted` whose segment from `from` to `to` is blocked by a surface that is
    /// not cut out; `path` as for [`CutScene::intersect_packet`]. The packet's any-hit test
    /// first: only the lanes it finds blocked are asked again, one by one, past cut-outs.
    pub fn occluded_packet(
        &self,
        from: V3<F32x8>,
        to: Vec3,
        wanted: F32x8,
        path: &[f32; WIDTH],
    ) -> F32x8 {
        let blocked = self.accel.occluded_packet(from, to, wanted);
        if !self.textures.any_mask || !blocked.any() {
            return blocked;
        }
        let lanes = blocked.move_mask() as u32;
        let from = from.to_vec3s();
        let still = (0..WIDTH)
            .filter(|&k| lanes & 1 << k != 0 && self.blocked(from[k], to, path[k]))
            .fold(0u32, |lanes, k| lanes | 1 << k);
        lane_mask(still)
    }

    /// Whether a surface that is not cut out lies on the segment from `from` to `to`.
    fn blocked(&self, from: Vec3, to: Vec3, path: f32) -> bool {
        let d = to - from;
        let dist = d.length();
        if dist <= 0.0 {
            return false;
        }
        let ray = Ray::new(from, d / dist);
        let mut t_min = 0.0;
        for _ in 0..MAX_CUTS {
            let Some(hit) = self.accel.intersect(&ray, t_min, dist) else {
                return false;
            };
            if !self.cuts(
                hit.object,
                hit.triangle,
                hit.u,
                hit.v,
                path + hit.t,
                d / dist,
            ) {
                return true;
            }
            t_min = beyond(hit.t);
        }
        false
    }
}

/// `hits` with the lanes set in `lanes` taken from `other`.
fn take_lanes(hits: &PacketHits, other: &PacketHits, lanes: u32) -> PacketHits {
    let f = lane_mask(lanes);
    let i = bytemuck::cast::<F32x8, wide::u32x8>(f);
    PacketHits {
        t: f.blend(other.t, hits.t),
        u: f.blend(other.u, hits.u),
        v: f.blend(other.v, hits.v),
        object: i.blend(other.object, hits.object),
        triangle: i.blend(other.triangle, hits.triangle),
        slot: i.blend(other.slot, hits.slot),
    }
}

/// The lanes whose bit is set in `bits`, as a lane mask (all bits set or clear).
#[inline]
pub fn lane_mask(bits: u32) -> F32x8 {
    bytemuck::cast::<[u32; WIDTH], F32x8>(std::array::from_fn(|k| {
        if bits & 1 << k != 0 { u32::MAX } else { 0 }
    }))
}
