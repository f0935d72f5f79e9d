//! The recovery file: where unsaved edits go when the editor is killed by SIGTERM or SIGHUP.

use std::path::{Path, PathBuf};

use crate::scene::Scene;

/// `<scene>.recovered.toml` next to the scene file, or `rastray-recovered.toml` in the current
/// directory for the built-in scene.
pub fn path_for(scene_path: Option<&Path>) -> PathBuf {
    match scene_path {
        Some(p) => {
            let stem = p
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default();
            p.with_file_name(format!("{stem}.recovered.toml"))
        }
        None => PathBuf::from("rastray-recovered.toml"),
    }
}

/// Writes `scene` to the recovery file for `scene_path`; returns where.
pub fn write(
    scene: &Scene,
    scene_path: Option<&Path>,
) -> Result<PathBuf, crate::scene::SceneError> {
    let path = path_for(scene_path);
    crate::scene::save(scene, &path)?;
    Ok(path)
}

/// The message to show at start when a recovery file exists.
pub fn notice(scene_path: Option<&Path>) -> Option<String> {
    let path = path_for(scene_path);
    path.is_file().then(|| {
        format!(
            "earlier unsaved edits are in {} (o opens it)",
            path.display()
        )
    })
}
