//! What a Z-buffer shader interpolates across a triangle: one value per mesh vertex (a normal,
//! or a lit colour), asked for only at the triangles that survive setup.

use glam::Vec3;

use crate::render::prefetch;
use crate::render::texturing::ObjectTextures;
use crate::world::World;

/// The varying of every vertex of a world's meshes.
pub trait Varying: Sync + Send {
    /// Called once per frame before any [`Varying::corners`], with the number of triangles per
    /// object whose corners will be asked for, or, once a frame of the world was drawn, beside
    /// the vertex stage with the last frame's numbers: a varying that is costly per vertex can
    /// work out whole objects at once where most of their vertices are likely to be needed.
    /// The choice changes no value.
    fn prepare(&mut self, _triangles_needed: &[usize]) {}

    /// Appends to `out` the values at the three vertices of each of `triangles` (indices into
    /// the object's triangles) of object `object`. A varying of K values per vertex (the
    /// Z-buffer's shader says how many it takes) appends K entries per triangle, the first
    /// value's corners, then the second's, and so on.
    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>);

    /// Hints that the corners of `triangle` of `object` will be asked for soon: the mesh data
    /// they are read from may start moving into the cache. Changes nothing else.
    fn prefetch(&self, _object: usize, _triangle: u32) {}
}

/// One slice of values per object, indexed by vertex: normals, or colours worked out already.
pub struct PerVertex<'a> {
    /// `values[object][vertex]`.
    values: Vec<&'a [Vec3]>,
    /// `triangles[object]`: each triangle's vertex indices.
    triangles: Vec<&'a [[u32; 3]]>,
}

impl<'a> PerVertex<'a> {
    /// The values `values[object][vertex]` on the meshes of `world`.
    pub fn new(world: &'a World, values: Vec<&'a [Vec3]>) -> PerVertex<'a> {
        debug_assert_eq!(values.len(), world.objects.len());
        PerVertex {
            values,
            triangles: world
                .objects
                .iter()
                .map(|o| &o.mesh.triangles[..])
                .collect(),
        }
    }

    /// The vertex normals of `world`'s meshes.
    pub fn normals(world: &'a World) -> PerVertex<'a> {
        let normals = world.objects.iter().map(|o| &o.mesh.normals[..]).collect();
        PerVertex::new(world, normals)
    }
}

impl Varying for PerVertex<'_> {
    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        let (values, indices) = (self.values[object], self.triangles[object]);
        // All the loads first, so that the misses overlap.
        for &t in triangles {
            for i in indices[t as usize] {
                prefetch::ahead(&values[i as usize]);
            }
        }
        out.extend(
            triangles
                .iter()
                .map(|&t| indices[t as usize].map(|i| values[i as usize])),
        );
    }

    fn prefetch(&self, object: usize, triangle: u32) {
        prefetch::ahead(&self.triangles[object][triangle as usize]);
    }
}

/// Two values per vertex: the vertex normals of a world's meshes, then their vertex colours
/// (white for a mesh without them). Phong shading's varyings where some mesh has colours.
pub struct NormalsAndColors<'a> {
    normals: PerVertex<'a>,
    /// `colors[object]`: the mesh's vertex colours, if it has them.
    colors: Vec<Option<&'a [Vec3]>>,
}

impl<'a> NormalsAndColors<'a> {
    /// The normals and colours of `world`'s meshes.
    pub fn new(world: &'a World) -> NormalsAndColors<'a> {
        NormalsAndColors {
            normals: PerVertex::normals(world),
            colors: world
                .objects
                .iter()
                .map(|o| o.mesh.colors.as_deref())
                .collect(),
        }
    }
}

impl Varying for NormalsAndColors<'_> {
    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        let (normals, indices) = (self.normals.values[object], self.normals.triangles[object]);
        let colors = self.colors[object];
        for &t in triangles {
            for i in indices[t as usize] {
                prefetch::ahead(&normals[i as usize]);
            }
        }
        for &t in triangles {
            let corners = indices[t as usize];
            out.push(corners.map(|i| normals[i as usize]));
            out.push(colors.map_or([Vec3::ONE; 3], |c| corners.map(|i| c[i as usize])));
        }
    }

    fn prefetch(&self, object: usize, triangle: u32) {
        self.normals.prefetch(object, triangle);
    }
}

/// Three values per vertex: the normals and colours of [`NormalsAndColors`], then the texture
/// coordinates (u, v) with the triangle's texel density as the third component (the same at
/// its three corners; zeros on an untextured mesh). Phong shading's varyings where some mesh
/// is textured; where no mesh has vertex colours, [`NormalsColorsAndUvs::without_colors`] leaves
/// the colours out: two values per vertex, the normal and (u, v, density).
pub struct NormalsColorsAndUvs<'a> {
    normals_and_colors: NormalsAndColors<'a>,
    /// Whether the colours are among the values.
    colors: bool,
    world: &'a World,
    textures: ObjectTextures<'a>,
}

impl<'a> NormalsColorsAndUvs<'a> {
    /// The normals, colours and texture coordinates of `world`'s meshes.
    pub fn new(world: &'a World) -> NormalsColorsAndUvs<'a> {
        NormalsColorsAndUvs {
            normals_and_colors: NormalsAndColors::new(world),
            colors: true,
            world,
            textures: ObjectTextures::with_spread(world, 0.0),
        }
    }

    /// The normals and texture coordinates of `world`'s meshes, without their colours.
    pub fn without_colors(world: &'a World) -> NormalsColorsAndUvs<'a> {
        NormalsColorsAndUvs {
            colors: false,
            ..NormalsColorsAndUvs::new(world)
        }
    }
}

impl Varying for NormalsColorsAndUvs<'_> {
    fn corners(&self, object: usize, triangles: &[u32], out: &mut Vec<[Vec3; 3]>) {
        let start = out.len();
        let firsts = if self.colors {
            self.normals_and_colors.corners(object, triangles, out);
            2
        } else {
            self.normals_and_colors
                .normals
                .corners(object, triangles, out);
            1
        };
        let before = out.split_off(start);
        let mesh = &self.world.objects[object].mesh;
        for (&t, values) in triangles.iter().zip(before.chunks_exact(firsts)) {
            out.extend_from_slice(values);
            out.push(match self.textures.corners(object, mesh, t) {
                Some((uv, density)) => uv.map(|uv| uv.extend(density)),
                None => [Vec3::ZERO; 3],
            });
        }
    }

    fn prefetch(&self, object: usize, triangle: u32) {
        self.normals_and_colors.prefetch(object, triangle);
    }
}
