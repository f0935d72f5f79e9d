//! The document: the scene being edited, the file it belongs to, its undo history and whether it
//! has unsaved edits. Every change of the scene passes through one place,
//! `Document::mark_changed`, which marks the document modified and bumps the generation the
//! render worker keys its world on.

use std::path::{Path, PathBuf};

use crate::scene::{Scene, SceneError, Shape};

/// Most undo steps kept.
pub const UNDO_LIMIT: usize = 200;

/// A scene, its file and its history. Fields change only through the methods below.
#[derive(Debug)]
pub struct Document {
    scene: Scene,
    /// `None` for the built-in scene until it is first saved.
    path: Option<PathBuf>,
    /// The folder mesh paths are relative to.
    base_dir: PathBuf,
    /// Earlier scenes, newest last, at most [`UNDO_LIMIT`].
    undo: Vec<Scene>,
    /// Undone scenes, newest last.
    redo: Vec<Scene>,
    /// Whether the scene differs from its file (or, built in, was edited at all).
    dirty: bool,
    /// Bumped on every change of the scene or of the folder its mesh paths are relative to.
    generation: u64,
    /// What the scene is called while it has no file.
    untitled: String,
}

impl Document {
    /// A clean document on `scene`, loaded from `path` (or built in), with mesh paths relative to
    /// `base_dir`.
    pub fn new(scene: Scene, path: Option<PathBuf>, base_dir: PathBuf) -> Document {
        Document {
            scene,
            path,
            base_dir,
            undo: Vec::new(),
            redo: Vec::new(),
            dirty: false,
            generation: 0,
            untitled: "built-in scene".into(),
        }
    }

    /// Calls the scene `name` while it has no file (a scene made for a model file, say).
    pub fn name_untitled(&mut self, name: impl Into<String>) {
        self.untitled = name.into();
    }

    /// What the scene is called while it has no file: "built-in scene" unless named otherwise.
    pub fn untitled_name(&self) -> &str {
        &self.untitled
    }

    /// The scene as edited.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The file the scene was loaded from or saved to; `None` for the built-in scene.
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The folder mesh paths are relative to.
    pub fn base_dir(&self) -> &Path {
        &self.base_dir
    }

    /// Whether there are edits since the last save or load.
    pub fn is_dirty(&self) -> bool {
        self.dirty
    }

    /// A number that changes exactly when the scene (or its folder) does: equal generations
    /// mean the same world.
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// How many edits undo can take back.
    pub fn undo_steps(&self) -> usize {
        self.undo.len()
    }

    /// Replaces the scene with `new` as one undoable edit. Returns `false`, changing nothing,
    /// when `new` is the scene already. The caller has validated `new`.
    pub fn edit(&mut self, new: Scene) -> bool {
        if new == self.scene {
            return false;
        }
        self.undo.push(std::mem::replace(&mut self.scene, new));
        if self.undo.len() > UNDO_LIMIT {
            self.undo.remove(0);
        }
        self.redo.clear();
        self.mark_changed();
        true
    }

    /// Takes back the latest edit; `false` when there is none.
    pub fn undo(&mut self) -> bool {
        self.travel(true)
    }

    /// Puts back the latest undone edit; `false` when there is none.
    pub fn redo(&mut self) -> bool {
        self.travel(false)
    }

    /// Moves one step back (`back`) or forward through the history.
    fn travel(&mut self, back: bool) -> bool {
        let (from, to) = if back {
            (&mut self.undo, &mut self.redo)
        } else {
            (&mut self.redo, &mut self.undo)
        };
        let Some(scene) = from.pop() else {
            return false;
        };
        to.push(std::mem::replace(&mut self.scene, scene));
        self.mark_changed();
        true
    }

    /// Writes the scene to `path`, which becomes the document's file. Saving into another folder
    /// re-expresses mesh paths (in the history too) relative to it, so they still find their
    /// models.
    pub fn save_to(&mut self, path: &Path) -> Result<(), SceneError> {
        let new_base = folder_of(path);
        let mut scene = self.scene.clone();
        rebase_mesh_paths(&mut scene, &self.base_dir, &new_base);
        crate::scene::save(&scene, path)?;
        if self.path.as_deref() != Some(path) {
            for old in self.undo.iter_mut().chain(&mut self.redo) {
                rebase_mesh_paths(old, &self.base_dir, &new_base);
            }
            self.scene = scene;
            self.base_dir = new_base;
            self.path = Some(path.to_path_buf());
            self.mark_changed();
        }
        self.mark_saved();
        Ok(())
    }

    /// Takes `scene`, the document's file as another program rewrote it, as one undoable step:
    /// the document then matches its file again. Returns `false`, changing nothing, when the file
    /// holds the scene already (the editor's own save, read back).
    pub fn reload(&mut self, scene: Scene) -> bool {
        let changed = self.edit(scene);
        if changed {
            self.mark_saved();
        }
        changed
    }

    /// The model files the scene uses were rewritten on disk: the world must be built again,
    /// though the scene itself is unchanged.
    pub fn models_changed(&mut self) {
        self.generation += 1;
    }

    /// Replaces the document with the scene file at `path`, without history; on error nothing
    /// changes.
    pub fn open(&mut self, path: &Path) -> Result<(), SceneError> {
        let scene = crate::scene::load(path)?;
        *self = Document {
            generation: self.generation,
            ..Document::new(scene, Some(path.to_path_buf()), folder_of(path))
        };
        self.mark_changed();
        self.mark_saved();
        Ok(())
    }

    /// `path` (relative to the working directory, or absolute) as the scene stores it: relative
    /// to the scene's folder where both share a root.
    pub fn stored_path(&self, path: &Path) -> PathBuf {
        relative_to(path, &self.base_dir)
    }

    /// The one place a change is recorded: the file no longer matches, the world is rebuilt.
    fn mark_changed(&mut self) {
        self.dirty = true;
        self.generation += 1;
    }

    /// The file now holds the scene.
    fn mark_saved(&mut self) {
        self.dirty = false;
    }
}

/// The folder of the scene file at `path`.
pub fn folder_of(path: &Path) -> PathBuf {
    path.parent().map(Path::to_path_buf).unwrap_or_default()
}

/// `path` as written in a scene whose file lives in `base`: relative to `base` (with `..` where
/// needed) when both share a root, absolute otherwise.
fn relative_to(path: &Path, base: &Path) -> PathBuf {
    let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let (path, base) = (absolute(path), absolute(base));
    let (p, b): (Vec<_>, Vec<_>) = (path.components().collect(), base.components().collect());
    let common = p.iter().zip(&b).take_while(|(x, y)| x == y).count();
    if common == 0 {
        return path;
    }
    let mut relative: PathBuf = b[common..].iter().map(|_| "..").collect();
    relative.extend(&p[common..]);
    relative
}

/// Rewrites the mesh paths of `scene`, relative to folder `from`, to be relative to `to`.
fn rebase_mesh_paths(scene: &mut Scene, from: &Path, to: &Path) {
    for object in &mut scene.objects {
        if let Shape::Mesh { path, .. } = &mut object.shape {
            *path = relative_to(&from.join(&*path), to);
        }
    }
}
