//! A world made ready for queries, as Embree commits a scene: built once, then kept while
//! renders ask it the same world again, whatever their camera or options.

use std::sync::Arc;
use std::time::Duration;

use super::algorithm::Algorithm;
use super::progress::{Cancelled, Progress};
use super::ray::SceneAccel;
use crate::world::World;

/// The world a renderer last drew and the acceleration structures built for it so far.
#[derive(Debug)]
pub(super) struct Prepared {
    /// Held, so that the allocation, and with it the identity [`Prepared::is_of`] compares,
    /// stays this world's for as long as it is kept.
    world: Arc<World>,
    /// The ray tracer's structure, built the first time the ray tracer draws this world.
    accel: Option<SceneAccel>,
    /// For the Z-buffer, the world with every instance placed into a mesh of its own
    /// ([`World::placed`]); built the first time the Z-buffer draws a world with instances.
    placed: Option<World>,
}

impl Prepared {
    /// `world`, with nothing built yet.
    pub(super) fn new(world: &Arc<World>) -> Prepared {
        Prepared {
            world: world.clone(),
            accel: None,
            placed: None,
        }
    }

    /// Whether this is `world` itself (the same allocation, not merely equal contents).
    pub(super) fn is_of(&self, world: &Arc<World>) -> bool {
        Arc::ptr_eq(&self.world, world)
    }

    /// The world as `algorithm` draws it: the ray tracer the world itself, whose instances it
    /// moves rays into; the Z-buffer its placed copy, when the world has instances and it was
    /// built ([`Prepared::build_for`]).
    pub(super) fn world_for(&self, algorithm: Algorithm) -> &World {
        match (algorithm, &self.placed) {
            (Algorithm::Gouraud | Algorithm::Phong, Some(placed)) => placed,
            _ => &self.world,
        }
    }

    /// Builds what `algorithm` queries and is not built yet; returns the time this took (zero
    /// when everything was kept).
    pub(super) fn build_for(
        &mut self,
        algorithm: Algorithm,
        progress: &Progress,
    ) -> Result<Duration, Cancelled> {
        if algorithm != Algorithm::Ray {
            if self.placed.is_some() || !self.world.has_instances() {
                return Ok(Duration::ZERO);
            }
            progress.check()?;
            let started = std::time::Instant::now();
            self.placed = self.world.placed();
            return Ok(started.elapsed());
        }
        if self.accel.is_some() {
            return Ok(Duration::ZERO);
        }
        progress.check()?;
        let accel = SceneAccel::build(&self.world, progress)?;
        let took = accel.build_time;
        self.accel = Some(accel);
        Ok(took)
    }

    /// The ray tracer's structure, when built.
    pub(super) fn accel(&self) -> Option<&SceneAccel> {
        self.accel.as_ref()
    }
}
