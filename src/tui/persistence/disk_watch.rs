//! Live reload: the open scene file, the model files it uses and the files those pull in (MTL
//! libraries, textures, glTF buffers and images, as the last world built read them), watched by
//! polling their modification time and length, so that a scene edited in another program (a
//! text editor in the next pane, a modeller writing an OBJ, a paint program saving a texture)
//! shows up in the preview.
//!
//! Polling costs one `stat` per watched file every [`POLL_EVERY`]: nothing to set up, nothing
//! that differs between platforms or file systems (network mounts included).

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

use crate::scene::Shape;
use crate::tui::state::document::Document;

/// How often the files are looked at.
pub const POLL_EVERY: Duration = Duration::from_millis(400);

/// What a file looked like when last seen; two stamps differ when it was written in between.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Stamp {
    modified: Option<SystemTime>,
    len: u64,
}

/// The stamp of the file at `path`; `None` when there is no such file.
fn stamp(path: &Path) -> Option<Stamp> {
    let meta = std::fs::metadata(path).ok()?;
    Some(Stamp {
        modified: meta.modified().ok(),
        len: meta.len(),
    })
}

/// Each of `paths` with its stamp now.
fn stamped(paths: Vec<PathBuf>) -> HashMap<PathBuf, Option<Stamp>> {
    paths
        .into_iter()
        .map(|p| {
            let s = stamp(&p);
            (p, s)
        })
        .collect()
}

/// Which of the watched files were written since the last look.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DiskChange {
    /// Nothing was written.
    None,
    /// The scene file was (its models may have been too).
    Scene,
    /// Only model files the scene uses, or files they pull in, were.
    Models,
}

/// The watched files and how they looked when last seen.
///
/// Invariant: a file is reported once per write. A file that appears or disappears from the
/// watch (another scene opened, a mesh added or removed) is taken as it is, not reported; a
/// file that is deleted is not reported either, so a scene stays on screen while a text editor
/// replaces its file.
#[derive(Debug, Default)]
pub struct DiskWatch {
    last_poll: Option<Instant>,
    scene: Option<(PathBuf, Option<Stamp>)>,
    models: HashMap<PathBuf, Option<Stamp>>,
    /// The files the models pulled in when the world was last built.
    pulled_in: HashMap<PathBuf, Option<Stamp>>,
}

impl DiskWatch {
    /// Takes the files of `doc` as they are now as seen: an edit the editor itself wrote (a
    /// save) is not reported back as a change.
    pub fn sync(&mut self, doc: &Document) {
        self.scene = doc.path().map(|p| (p.to_path_buf(), stamp(p)));
        self.models = stamped(model_paths(doc));
    }

    /// Watches `files`, which the models of the world just built read (as they are now: the
    /// world has them so).
    pub fn watch_model_files(&mut self, files: Vec<PathBuf>) {
        self.pulled_in = stamped(files);
    }

    /// Looks at the files of `doc`, at most once every [`POLL_EVERY`] (by `now`), and says which
    /// were written since the last look.
    pub fn poll(&mut self, doc: &Document, now: Instant) -> DiskChange {
        if self
            .last_poll
            .is_some_and(|at| now.saturating_duration_since(at) < POLL_EVERY)
        {
            return DiskChange::None;
        }
        self.last_poll = Some(now);
        let mut change = DiskChange::None;
        let mut models = HashMap::new();
        for path in model_paths(doc) {
            let now_seen = stamp(&path);
            if let Some(before) = self.models.get(&path)
                && written(*before, now_seen)
            {
                change = DiskChange::Models;
            }
            models.insert(path, now_seen);
        }
        self.models = models;
        for (path, seen) in &mut self.pulled_in {
            let now_seen = stamp(path);
            if written(*seen, now_seen) {
                change = DiskChange::Models;
            }
            *seen = now_seen;
        }
        match (doc.path(), &mut self.scene) {
            (Some(path), Some((seen_path, seen))) if seen_path == path => {
                let now_seen = stamp(path);
                if written(*seen, now_seen) {
                    change = DiskChange::Scene;
                }
                *seen = now_seen;
            }
            (path, scene) => *scene = path.map(|p| (p.to_path_buf(), stamp(p))),
        }
        change
    }
}

/// Whether a file seen as `before` and now as `now` was written in between (and still exists).
fn written(before: Option<Stamp>, now: Option<Stamp>) -> bool {
    now.is_some() && before != now
}

/// The model files of `doc`'s scene, as paths the process can open.
fn model_paths(doc: &Document) -> Vec<PathBuf> {
    doc.scene()
        .objects
        .iter()
        .filter_map(|o| match &o.shape {
            Shape::Mesh { path, .. } => Some(doc.base_dir().join(path)),
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{default_scene, to_toml_string};

    /// A poll time far enough past the last that the rate limit never holds a test back.
    fn later(t: &mut Instant) -> Instant {
        *t += POLL_EVERY;
        *t
    }

    /// Writes `text` to `path` with a modification time one second after its last, so that
    /// file systems with coarse timestamps see the write too.
    fn write(path: &Path, text: &str) {
        let before = std::fs::metadata(path).and_then(|m| m.modified()).ok();
        std::fs::write(path, text).unwrap();
        let after = before.map_or_else(SystemTime::now, |t| t + Duration::from_secs(1));
        std::fs::File::options()
            .write(true)
            .open(path)
            .unwrap()
            .set_modified(after)
            .unwrap();
    }

    #[test]
    fn each_write_of_the_scene_file_is_reported_once() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.toml");
        let text = to_toml_string(&default_scene());
        write(&path, &text);
        let doc = Document::new(default_scene(), Some(path.clone()), dir.path().into());
        let mut watch = DiskWatch::default();
        watch.sync(&doc);
        let mut t = Instant::now();
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::None);
        write(&path, &format!("{text}\n"));
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::Scene);
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::None);
        // A deleted file keeps the scene as it is; its return is a write.
        std::fs::remove_file(&path).unwrap();
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::None);
        write(&path, &text);
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::Scene);
    }

    #[test]
    fn polls_closer_than_the_interval_do_not_look() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("s.toml");
        write(&path, "a");
        let doc = Document::new(default_scene(), Some(path.clone()), dir.path().into());
        let mut watch = DiskWatch::default();
        watch.sync(&doc);
        let t = Instant::now();
        assert_eq!(watch.poll(&doc, t), DiskChange::None);
        write(&path, "ab");
        assert_eq!(watch.poll(&doc, t + POLL_EVERY / 2), DiskChange::None);
        assert_eq!(watch.poll(&doc, t + POLL_EVERY), DiskChange::Scene);
    }

    #[test]
    fn a_written_model_is_reported_and_a_newly_used_one_is_not() {
        let dir = tempfile::tempdir().unwrap();
        let obj = dir.path().join("m.obj");
        write(&obj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
        let mut scene = default_scene();
        let doc = Document::new(scene.clone(), None, dir.path().into());
        let mut watch = DiskWatch::default();
        watch.sync(&doc);
        let mut t = Instant::now();
        scene.objects.push(crate::scene::Object::new(Shape::new(
            crate::scene::ShapeKind::Mesh,
            glam::Vec3::ZERO,
            "m.obj".into(),
        )));
        let doc = Document::new(scene, None, dir.path().into());
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::None);
        write(&obj, "v 0 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\n");
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::Models);
        assert_eq!(watch.poll(&doc, later(&mut t)), DiskChange::None);
    }
}
