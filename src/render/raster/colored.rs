//! Which objects have vertex colours, by lanes: a Z-buffer shader on the coloured path takes
//! the interpolated vertex colour where a lane's object has colours, and leaves the others as
//! they are. An interpolated constant 1 is not exactly 1 (the varying times 1/w, divided by
//! 1/w, rounds), so objects without colours must not be multiplied by it: that keeps their
//! bits those of a world without colours.

use crate::render::simd::{Lanes8, V3, WIDTH};
use crate::world::World;

/// Per object, whether its mesh has vertex colours.
pub struct ColoredObjects {
    colored: Vec<bool>,
}

impl ColoredObjects {
    /// The objects of `world`.
    pub fn new(world: &World) -> ColoredObjects {
        ColoredObjects {
            colored: world
                .objects
                .iter()
                .map(|o| o.mesh.colors.is_some())
                .collect(),
        }
    }

    /// The objects of `world`, a textured object counting as coloured: what takes Gouraud's
    /// separate specular path.
    pub fn with_textures(world: &World) -> ColoredObjects {
        ColoredObjects {
            colored: world
                .objects
                .iter()
                .map(|o| o.mesh.colors.is_some() || o.is_textured())
                .collect(),
        }
    }

    /// `coloured` in the lanes whose object (`objects`) has vertex colours, `plain` in the
    /// others; one test when the eight lanes share an object, as they mostly do.
    #[inline(always)]
    pub fn select<L: Lanes8>(
        &self,
        objects: &[u32; WIDTH],
        coloured: V3<L>,
        plain: V3<L>,
    ) -> V3<L> {
        if objects.iter().all(|&o| o == objects[0]) {
            return match self.colored[objects[0] as usize] {
                true => coloured,
                false => plain,
            };
        }
        let mask = L::from_array(objects.map(|o| f32::from(u8::from(self.colored[o as usize]))))
            .gt(L::splat(0.5));
        V3::new(
            L::select(mask, coloured.x, plain.x),
            L::select(mask, coloured.y, plain.y),
            L::select(mask, coloured.z, plain.z),
        )
    }
}
