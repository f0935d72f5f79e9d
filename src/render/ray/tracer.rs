//! Backward (Whitted) ray tracing: one primary ray per pixel centre, the shared lighting function
//! at the nearest hit with shadow rays deciding which lights count, and mirror reflection
//! recursing to a maximum depth.
//!
//! Primary rays go in packets of 4×2 neighbouring pixels: traced through the BVH together and
//! lit together, eight lanes at a time. Their shadow rays toward each light start from eight
//! neighbouring points and end at one, so they go as a packet too, each lane stopping at its
//! first blocker. The rays a packet reflects go on as a packet (lanes that hit no mirror sit
//! out), lit the same way, down to the depth limit; a few stragglers go one by one. Bands of rows
//! are traced in parallel, tile by tile; every pixel depends only on its own rays, so the image
//! is the same for any number of threads.
//!
//! The surface at a hit is interpolated from the triangle's corners in the mesh, except on a
//! flat-shaded mesh, where the BVH's copy of the triangle holds the point and the face normal:
//! a large mesh's arrays, which each hit would miss the cache in, are then not read at all
//! (1.31M-triangle icosphere at 640×360: 15% less time per frame).

use glam::Vec3;
use rayon::prelude::*;

use super::accel::{Hit, SceneAccel};
use super::alpha_cut::{CutScene, lane_mask};
use super::half_line::Ray;
use super::intersect::Triangle;
use super::packet::RayPacket;
use super::primary::primary_packet;
use crate::mesh::Mesh;
use crate::render::camera::View;
use crate::render::materials::ObjectMaterials;
use crate::render::options::RenderOptions;
use crate::render::progress::{Cancelled, Progress};
use crate::render::shading::Lighting;
use crate::render::simd::{F32x8, V3, WIDTH};
use crate::render::stats::RayCounts;
use crate::render::texturing::ObjectTextures;
use crate::scene::Light;
use crate::world::World;

/// Deepest reflection recursion traced, whatever the options ask: the limit scene files
/// already have, which also bounds the recursion's stack use.
pub const MAX_REFLECTION_DEPTH: u32 = crate::scene::MAX_DEPTH;

/// Primary rays are traced in packets of [`WIDTH`]: this many columns …
const PACKET_COLUMNS: usize = 4;
/// … by this many rows.
const PACKET_ROWS: usize = WIDTH / PACKET_COLUMNS;
/// Packets are traced tile by tile, tiles of this many columns (a multiple of
/// [`PACKET_COLUMNS`]) …
const TILE_COLUMNS: usize = 32;
/// … by this many rows (a multiple of [`PACKET_ROWS`]); a band of this many rows is one task.
const TILE_ROWS: usize = 8;
/// Reflected rays of one packet go as a packet of their own from this many lanes up, and one
/// by one below it, where a packet walk costs more than the few rays it carries.
const MIN_REFLECTION_PACKET: u32 = 3;

/// Traces `world` through `view` into `out` (`view.width`×`view.height` pixels), with an
/// acceleration structure built from `world`; returns the rays cast.
pub fn trace_into(
    accel: &SceneAccel,
    world: &World,
    view: &View,
    options: &RenderOptions,
    progress: &Progress,
    out: &mut [Vec3],
) -> Result<RayCounts, Cancelled> {
    let mut tracer = Tracer::new(accel, world, options);
    tracer.textures = ObjectTextures::new(world, view);
    let width = view.width as usize;
    debug_assert_eq!(out.len(), width * view.height as usize);
    out.par_chunks_mut(width * TILE_ROWS)
        .enumerate()
        .map(|(band, rows)| {
            progress.check()?;
            let mut stats = RayCounts::default();
            let (band_top, band_height) = (band * TILE_ROWS, rows.len() / width);
            // Tile by tile, and within a tile packet row by packet row: neighbouring packets,
            // which visit much the same BVH nodes, follow each other while those are cached.
            for tile_left in (0..width).step_by(TILE_COLUMNS) {
                let tile_right = (tile_left + TILE_COLUMNS).min(width);
                for pair_top in (0..band_height).step_by(PACKET_ROWS) {
                    for left in (tile_left..tile_right).step_by(PACKET_COLUMNS) {
                        let packet = Packet {
                            left,
                            pair_top,
                            band_top,
                        };
                        tracer.trace_packet(view, packet, rows, &mut stats);
                    }
                }
            }
            progress.advance(band_height as u64);
            Ok(stats)
        })
        .try_reduce(RayCounts::default, |a, b| Ok(a + b))
}

/// A packet of 4×2 pixels within a band of rows: its left column, its top row within the band,
/// and the band's top row in the image.
#[derive(Clone, Copy)]
struct Packet {
    left: usize,
    pair_top: usize,
    band_top: usize,
}

/// What every ray of one render shares.
pub(super) struct Tracer<'a> {
    world: &'a World,
    accel: &'a SceneAccel,
    lighting: Lighting<'a>,
    materials: ObjectMaterials,
    /// Whether any object's mesh has vertex colours: only then is the colour at a hit looked
    /// up, so that worlds without them trace as they did before colours existed.
    colored: bool,
    /// The objects' textures and the footprint of a pixel's ray cone.
    pub(super) textures: ObjectTextures<'a>,
    shadows: bool,
    max_depth: u32,
}

/// The corners of a triangle hit: positions (world units) and unit normals, in the mesh's order.
pub(super) struct Corners {
    positions: [Vec3; 3],
    normals: [Vec3; 3],
}

/// What the surface at a hit is worked out from: the BVH's copy of a flat-shaded triangle, or
/// the triangle's corners in the mesh, `C` (their vertex indices, then the corners read).
#[derive(Clone, Copy)]
enum Patch<'a, C> {
    Face(&'a Triangle),
    Mesh(C),
}

/// The surface at a ray's hit.
pub(super) struct Surface {
    /// The hit point, world units.
    pub(super) p: Vec3,
    /// The interpolated shading normal, unit length (zero on a degenerate triangle).
    pub(super) n: Vec3,
    /// Where secondary rays start: `p` lifted off the surface, on the side the ray came from.
    pub(super) origin: Vec3,
}

impl<'a> Tracer<'a> {
    /// What rays traced through `world` with `options` share; `accel` was built from `world`.
    pub(super) fn new(accel: &'a SceneAccel, world: &'a World, options: &RenderOptions) -> Self {
        debug_assert_eq!(accel.objects.len(), world.objects.len());
        Tracer {
            world,
            accel,
            lighting: Lighting::new(world),
            materials: ObjectMaterials::new(world),
            colored: world
                .objects
                .iter()
                .any(|o| o.local_mesh().colors.is_some()),
            textures: ObjectTextures::with_spread(world, 0.0),
            shadows: options.shadows,
            max_depth: options
                .max_depth
                .unwrap_or(world.max_depth)
                .min(MAX_REFLECTION_DEPTH),
        }
    }

    /// Traces the primary rays of `packet` and writes their colours into `rows`, the band's
    /// pixels (`view.width` to a row). Lane k is pixel (left + k % 4, top + k / 4); lanes past
    /// the image's right edge or the band's last row repeat a pixel inside it and are not
    /// written.
    #[inline(always)]
    fn trace_packet(&self, view: &View, packet: Packet, rows: &mut [Vec3], stats: &mut RayCounts) {
        let width = view.width as usize;
        let Packet {
            left,
            pair_top,
            band_top,
        } = packet;
        // The packet's rows within the band; the band's last may leave a single one.
        let height = (rows.len() / width - pair_top).min(PACKET_ROWS);
        let column = |k: usize| (left + k % PACKET_COLUMNS).min(width - 1);
        let row = |k: usize| (k / PACKET_COLUMNS).min(height - 1);
        let real = (0..WIDTH)
            .filter(|k| left + k % PACKET_COLUMNS < width && k / PACKET_COLUMNS < height)
            .fold(0u32, |lanes, k| lanes | 1 << k);
        let top = band_top + pair_top;
        let pixel = std::array::from_fn(|k| (column(k) as u32, (top + row(k)) as u32));
        let colors = self.trace_primary(view, pixel, real, stats);
        for k in (0..WIDTH).filter(|k| real & 1 << k != 0) {
            rows[(pair_top + row(k)) * width + column(k)] = colors[k];
        }
    }

    /// The surface where a ray along `d` hits `hit`: on a flat-shaded mesh, from the BVH's copy
    /// of the triangle ([`Tracer::face_surface`]), else from the mesh's corners
    /// ([`Tracer::surface_at`]).
    fn surface(&self, hit: &Hit, d: Vec3) -> Surface {
        if let Some(face) = self.face(hit.object, hit.slot) {
            return self.face_surface(face, hit.u, hit.v, d);
        }
        let abc = self.mesh(hit.object).triangles[hit.triangle as usize];
        self.surface_at(&self.corners(hit.object, abc), hit.u, hit.v, d)
    }

    /// The BVH's copy of the triangle in slot `slot` of object `object`, when the object is
    /// flat-shaded: then the triangle holds all its surface needs, and the mesh, whose arrays
    /// a ray on a large mesh would miss the cache in, is not read.
    #[inline]
    pub(super) fn face(&self, object: u32, slot: u32) -> Option<&Triangle> {
        // An instance's BVH holds its triangles in the mesh's own space: its surface comes
        // from the corners, moved into the world.
        let accel = &self.accel.objects[object as usize];
        (self.mesh(object).flat && accel.to_object.is_none())
            .then(|| &accel.bvh.triangles[slot as usize])
    }

    /// The surface of the flat triangle `face` where a ray along `d` hits it at barycentrics
    /// (u, v): the point v0 + u·e1 + v·e2, and the face normal, which is every corner's
    /// normal on a flat-shaded mesh.
    #[inline]
    pub(super) fn face_surface(&self, face: &Triangle, u: f32, v: f32, d: Vec3) -> Surface {
        let p = Vec3::from(face.v0 + face.e1() * u + face.e2() * v);
        let n = Vec3::from(face.n).normalize_or_zero();
        Surface {
            p,
            n,
            origin: p + toward(n, d) * self.accel.epsilon,
        }
    }

    /// The mesh object `object`'s triangle indices refer to (an instance's shared mesh).
    #[inline]
    fn mesh(&self, object: u32) -> &Mesh {
        self.world.objects[object as usize].local_mesh()
    }

    /// The world positions and normals at vertices `abc` of object `object`'s mesh (an
    /// instance's moved out of its mesh's space, normals by the inverse transpose, unit).
    #[inline]
    pub(super) fn corners(&self, object: u32, abc: [u32; 3]) -> Corners {
        let o = &self.world.objects[object as usize];
        if let Some(instance) = &o.instance {
            let (positions, normals) = instance.corners(abc);
            return Corners { positions, normals };
        }
        let mesh = &o.mesh;
        let abc = abc.map(|k| k as usize);
        Corners {
            positions: abc.map(|k| mesh.positions[k]),
            normals: abc.map(|k| mesh.normals[k]),
        }
    }

    /// The vertex colour at barycentrics (u, v) of triangle `triangle` of object `object`:
    /// the corners' colours weighted as [`Tracer::surface_at`] weights their normals, or white
    /// when the mesh has none.
    #[inline]
    fn vertex_color(&self, object: u32, triangle: u32, u: f32, v: f32) -> Vec3 {
        let mesh = self.mesh(object);
        let Some(colors) = &mesh.colors else {
            return Vec3::ONE;
        };
        let [a, b, c] = mesh.triangles[triangle as usize].map(|k| colors[k as usize]);
        a * (1.0 - u - v) + b * u + c * v
    }

    /// [`Tracer::surface`] on the corners of the triangle hit.
    #[inline]
    pub(super) fn surface_at(&self, corners: &Corners, u: f32, v: f32, d: Vec3) -> Surface {
        let ([pa, pb, pc], [na, nb, nc]) = (corners.positions, corners.normals);
        let w = [1.0 - u - v, u, v];
        let p = pa * w[0] + pb * w[1] + pc * w[2];
        let n = (na * w[0] + nb * w[1] + nc * w[2]).normalize_or_zero();
        // The geometric normal, turned toward where the ray came from; the offset is scaled to
        // the scene.
        let ng = (pb - pa).cross(pc - pa).normalize_or_zero();
        Surface {
            p,
            n,
            origin: p + toward(ng, d) * self.accel.epsilon,
        }
    }

    /// Colour of the eight primary rays through the centres of `pixel` (column, row); lanes
    /// whose bit is not set in `real` are computed but not counted.
    fn trace_primary(
        &self,
        view: &View,
        pixel: [(u32, u32); WIDTH],
        real: u32,
        stats: &mut RayCounts,
    ) -> [Vec3; WIDTH] {
        let x = F32x8::from(pixel.map(|(i, _)| i as f32 + 0.5));
        let y = F32x8::from(pixel.map(|(_, j)| j as f32 + 0.5));
        stats.primary += real.count_ones() as u64;
        self.trace_lanes(&primary_packet(view, x, y), real, 0, &[0.0; WIDTH], stats)
    }

    /// Colour seen along each ray of `packet` whose bit is set in `lanes`, the others left as
    /// the background; `depth` counts reflections so far, and `path` is how far each ray's
    /// cone has come before its origin (for the texture's level of detail). Each lane gets the bits its ray would
    /// get alone from [`Tracer::trace`].
    ///
    /// Inlined into the primary packet's loop, as the primary body was before reflected packets
    /// shared it (callgrind, bunny 320×180: 0.6% fewer instructions than out of line);
    /// reflected packets come back through [`Tracer::trace_reflected_lanes`], not inlined.
    #[inline(always)]
    pub(super) fn trace_lanes(
        &self,
        packet: &RayPacket,
        lanes: u32,
        depth: u32,
        path: &[f32; WIDTH],
        stats: &mut RayCounts,
    ) -> [Vec3; WIDTH] {
        let dir = packet.dir;
        let hits = self.cut().intersect_packet(packet, path);
        let hit_lanes = hits.hit().move_mask() as u32 & lanes;
        let Some(first) = (0..WIDTH).find(|&k| hit_lanes & 1 << k != 0) else {
            return [self.world.background; WIDTH];
        };
        // Lanes without a hit borrow the first hit's surface, so every lane computes with
        // finite values; their colour is the background.
        let source = |k: usize| if hit_lanes & 1 << k != 0 { k } else { first };
        let (objects, triangles) = (hits.object.to_array(), hits.triangle.to_array());
        let objects: [u32; WIDTH] = std::array::from_fn(|k| objects[source(k)]);
        let (u, v, slots) = (hits.u.to_array(), hits.v.to_array(), hits.slot.to_array());
        let dirs = dir.to_vec3s();
        // Each stage for all lanes before the next, so that the lanes' loads from the meshes,
        // which miss the cache on large meshes, overlap rather than wait one after another.
        let indices: [Patch<[u32; 3]>; WIDTH] = std::array::from_fn(|k| {
            let (object, s) = (objects[k], source(k));
            match self.face(object, slots[s]) {
                Some(face) => Patch::Face(face),
                None => Patch::Mesh(self.mesh(object).triangles[triangles[s] as usize]),
            }
        });
        let patches: [Patch<Corners>; WIDTH] = std::array::from_fn(|k| match indices[k] {
            Patch::Face(face) => Patch::Face(face),
            Patch::Mesh(abc) => Patch::Mesh(self.corners(objects[k], abc)),
        });
        let surfaces: [Surface; WIDTH] = std::array::from_fn(|k| {
            let s = source(k);
            match &patches[k] {
                Patch::Face(face) => self.face_surface(face, u[s], v[s], dirs[k]),
                Patch::Mesh(corners) => self.surface_at(corners, u[s], v[s], dirs[k]),
            }
        });
        let mut material = self.materials.of_lanes::<F32x8>(&objects);
        if self.colored {
            // The albedo: the material's colour times the vertex colour at the hit (white,
            // which changes no bit, on meshes without colours).
            let colors: [Vec3; WIDTH] = std::array::from_fn(|k| {
                let s = source(k);
                self.vertex_color(objects[k], triangles[s], u[s], v[s])
            });
            material.color = material.color.mul_elements(V3::gather(&colors));
        }
        let mut reached = *path;
        if self.textures.any {
            let t = hits.t.to_array();
            reached = std::array::from_fn(|k| path[k] + t[source(k)]);
            let texels: [Vec3; WIDTH] = std::array::from_fn(|k| {
                let s = source(k);
                let (object, triangle) = (objects[k], triangles[s]);
                self.texture_at(
                    object,
                    triangle,
                    u[s],
                    v[s],
                    reached[k],
                    dirs[k],
                    &surfaces[k],
                )
            });
            material.color = material.color.mul_elements(V3::gather(&texels));
        }
        let p = V3::gather(&surfaces.each_ref().map(|s| s.p));
        let n = V3::gather(&surfaces.each_ref().map(|s| s.n));
        let origins = V3::gather(&surfaces.each_ref().map(|s| s.origin));
        let lit = self
            .lighting
            .shade_lanes(p, n, -dir, &material, |_, light, facing| {
                let wanted = facing & lane_mask(hit_lanes);
                if !self.shadows {
                    return wanted;
                }
                stats.shadow += wanted.move_mask().count_ones() as u64;
                wanted
                    & !self
                        .cut()
                        .occluded_packet(origins, light.position, wanted, &reached)
            })
            .to_vec3s();
        let mirrored = self.reflections(
            &objects, &surfaces, &dirs, hit_lanes, depth, &reached, stats,
        );
        std::array::from_fn(|k| {
            if hit_lanes & 1 << k == 0 {
                return self.world.background;
            }
            lit[k] + mirrored[k]
        })
    }

    /// What the mirrors hit by the lanes of `hit_lanes` add to each lane (zero where the
    /// object does not reflect, or at the depth limit): Kr times the colour of the reflected
    /// ray. The reflected rays go as a packet when enough lanes cast one, else one by one.
    #[allow(clippy::too_many_arguments)]
    fn reflections(
        &self,
        objects: &[u32; WIDTH],
        surfaces: &[Surface; WIDTH],
        dirs: &[Vec3; WIDTH],
        hit_lanes: u32,
        depth: u32,
        path: &[f32; WIDTH],
        stats: &mut RayCounts,
    ) -> [Vec3; WIDTH] {
        let mut added = [Vec3::ZERO; WIDTH];
        if depth >= self.max_depth {
            return added;
        }
        let coefficient = |k: usize| self.world.objects[objects[k] as usize].material.reflection;
        let mirrors = (0..WIDTH)
            .filter(|&k| hit_lanes & 1 << k != 0 && coefficient(k) > 0.0)
            .fold(0u32, |lanes, k| lanes | 1 << k);
        if mirrors == 0 {
            return added;
        }
        stats.reflection += mirrors.count_ones() as u64;
        // Lanes without a reflected ray repeat the first one, which keeps the walk short.
        let first = mirrors.trailing_zeros() as usize;
        let rays: [Ray; WIDTH] = std::array::from_fn(|k| {
            let k = if mirrors & 1 << k != 0 { k } else { first };
            mirror_ray(&surfaces[k], dirs[k])
        });
        if mirrors.count_ones() < MIN_REFLECTION_PACKET {
            for k in (0..WIDTH).filter(|k| mirrors & 1 << k != 0) {
                added[k] = coefficient(k) * self.trace(&rays[k], 0.0, depth + 1, path[k], stats);
            }
            return added;
        }
        let packet = RayPacket::new(
            V3::gather(&rays.each_ref().map(|r| Vec3::from(r.origin))),
            V3::gather(&rays.each_ref().map(|r| Vec3::from(r.dir))),
            F32x8::ZERO,
        );
        let seen = self.trace_reflected_lanes(&packet, mirrors, depth + 1, path, stats);
        for k in (0..WIDTH).filter(|k| mirrors & 1 << k != 0) {
            added[k] = coefficient(k) * seen[k];
        }
        added
    }

    /// [`Tracer::trace_lanes`] for a packet of reflected rays, kept out of line so that the
    /// recursion has a call to come back through.
    #[inline(never)]
    fn trace_reflected_lanes(
        &self,
        packet: &RayPacket,
        lanes: u32,
        depth: u32,
        path: &[f32; WIDTH],
        stats: &mut RayCounts,
    ) -> [Vec3; WIDTH] {
        self.trace_lanes(packet, lanes, depth, path, stats)
    }

    /// Colour seen along `ray` beyond `t_min`; `depth` counts reflections so far, and `path` is
    /// how far the ray's cone has come before its origin.
    pub(super) fn trace(
        &self,
        ray: &Ray,
        t_min: f32,
        depth: u32,
        path: f32,
        stats: &mut RayCounts,
    ) -> Vec3 {
        let Some(hit) = self.cut().intersect(ray, t_min, path) else {
            return self.world.background;
        };
        let d = Vec3::from(ray.dir);
        let s = self.surface(&hit, d);
        let mut material = self.materials.one[hit.object as usize];
        if self.colored {
            let color = self.vertex_color(hit.object, hit.triangle, hit.u, hit.v);
            material.color = material.color.mul_elements(color.into());
        }
        let path = path + hit.t;
        if self.textures.any {
            let texel = self.texture_at(hit.object, hit.triangle, hit.u, hit.v, path, d, &s);
            material.color = material.color.mul_elements(texel.into());
        }
        let lit = self.lighting.shade(s.p, s.n, -d, &material, |_, light| {
            self.light_reaches(s.origin, light, path, stats)
        });
        lit + self.reflection(hit.object, &s, d, depth, path, stats)
    }

    /// Whether `light` reaches a point whose secondary rays start at `origin`, at path length
    /// `path`: always without shadows, else when its shadow ray is unblocked.
    fn light_reaches(&self, origin: Vec3, light: &Light, path: f32, stats: &mut RayCounts) -> bool {
        if !self.shadows {
            return true;
        }
        stats.shadow += 1;
        !self.cut().occluded(origin, light.position, path)
    }

    /// The scene's queries with masked objects cut out.
    #[inline]
    fn cut(&self) -> CutScene<'_> {
        CutScene {
            accel: self.accel,
            world: self.world,
            textures: &self.textures,
        }
    }

    /// What the mirror of object `object` at surface `s`, hit along `d` by a ray of reflection
    /// depth `depth`, adds: Kr times the colour of the reflected ray, until the depth limit.
    fn reflection(
        &self,
        object: u32,
        s: &Surface,
        d: Vec3,
        depth: u32,
        path: f32,
        stats: &mut RayCounts,
    ) -> Vec3 {
        let reflection = self.world.objects[object as usize].material.reflection;
        if depth >= self.max_depth || reflection <= 0.0 {
            return Vec3::ZERO;
        }
        stats.reflection += 1;
        reflection * self.trace(&mirror_ray(s, d), 0.0, depth + 1, path, stats)
    }

    /// The texture colour (RGB, white on an untextured object) at barycentrics (u, v) of
    /// triangle `triangle` of object `object`, hit at path length `path` along `d` on surface
    /// `s`: the footprint of the ray's cone there chooses the level.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn texture_at(
        &self,
        object: u32,
        triangle: u32,
        u: f32,
        v: f32,
        path: f32,
        d: Vec3,
        s: &Surface,
    ) -> Vec3 {
        let mesh = self.mesh(object);
        let Some((uv, density)) = self.textures.corners(object as usize, mesh, triangle) else {
            return Vec3::ONE;
        };
        let at = uv[0] * (1.0 - u - v) + uv[1] * u + uv[2] * v;
        let cos = s.n.dot(d);
        self.textures
            .sample(object as usize, at, density, path, cos)
            .truncate()
    }
}

/// The ray reflected at surface `s` hit along unit `d`: from the surface's lifted origin, along
/// `d` mirrored about the shading normal turned toward the viewer, as the lighting function
/// turns it.
#[inline]
fn mirror_ray(s: &Surface, d: Vec3) -> Ray {
    let n = if s.n.dot(-d) < 0.0 { -s.n } else { s.n };
    let r = d - 2.0 * n * d.dot(n);
    Ray::new(s.origin, r.normalize_or(d))
}

/// The unit normal `n` turned toward where a ray along `d` came from.
#[inline]
fn toward(n: Vec3, d: Vec3) -> Vec3 {
    if n.dot(d) > 0.0 { -n } else { n }
}
