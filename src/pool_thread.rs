//! Running a piece of work on a thread of rayon's global pool.
//!
//! Loading a model, building a world and measuring it take many short parallel steps. Called
//! from a thread outside the pool (the main thread, the editor's render worker), each step
//! wakes the pool's threads and sleeps until they are done; on the 2-core machine those wake-ups
//! cost more than a small model's parallel work. Run on a pool thread, the same steps share their
//! work between the pool's threads by work stealing, and the caller is woken once, at the end.

/// Runs `work` on a thread of rayon's global pool (on the current thread when it is one already)
/// and returns what it returns; the calling thread waits. The work and its results are the same
/// on any thread; only the hand-offs between threads differ.
///
/// `rastray info` on the Stanford bunny (2.4 MB of OBJ, 69,451 triangles) took 15.6 ms as a whole
/// process with its steps called from the main thread and 11.9 ms with them on the pool (idle
/// 2-core machine, medians of 30, taking turns; rapidobj: 9.1 ms).
pub fn on_pool_thread<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| work())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn work_from_outside_the_pool_runs_on_a_pool_thread_and_returns_its_result() {
        let outside = std::thread::spawn(|| {
            assert_eq!(rayon::current_thread_index(), None);
            on_pool_thread(|| (rayon::current_thread_index(), std::thread::current().id()))
        });
        let caller = outside.thread().id();
        let (index, ran_on) = outside.join().expect("no panic");
        assert!(index.is_some(), "ran off the pool");
        assert_ne!(ran_on, caller);
    }

    #[test]
    fn work_already_on_a_pool_thread_runs_where_it_is() {
        let (outer, inner) = rayon::scope(|_| {
            let outer = std::thread::current().id();
            (outer, on_pool_thread(|| std::thread::current().id()))
        });
        assert_eq!(outer, inner);
    }
}
