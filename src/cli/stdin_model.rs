//! `rastray render - --input-format glb`: a model read from standard input, bounded by the
//! same limit as a model file, into a private folder that is removed when it is dropped.

use std::io::Read;
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use rastray::input_file::{MAX_MODEL_BYTES, too_large};

/// The formats a model from standard input is read as.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum InputFormat {
    Glb,
    /// glTF JSON with its buffers embedded (data: URIs): a pipe carries no other files.
    Gltf,
    Obj,
    Stl,
    Ply,
}

impl InputFormat {
    fn extension(self) -> &'static str {
        match self {
            InputFormat::Glb => "glb",
            InputFormat::Gltf => "gltf",
            InputFormat::Obj => "obj",
            InputFormat::Stl => "stl",
            InputFormat::Ply => "ply",
        }
    }
}

/// The model read from standard input, as a file that lives as long as this value.
#[derive(Debug)]
pub struct StdinModel {
    folder: PathBuf,
    path: PathBuf,
}

impl StdinModel {
    /// Reads standard input to its end, at most [`MAX_MODEL_BYTES`].
    pub fn read(format: InputFormat) -> anyhow::Result<StdinModel> {
        let mut bytes = Vec::new();
        std::io::stdin()
            .lock()
            .take(MAX_MODEL_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| anyhow::anyhow!("-: cannot read standard input: {e}"))?;
        if bytes.len() as u64 > MAX_MODEL_BYTES {
            let error = too_large(bytes.len() as u64, MAX_MODEL_BYTES, "a model file");
            anyhow::bail!("-: {error}");
        }
        let folder = std::env::temp_dir().join(format!(
            "rastray-stdin-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.subsec_nanos())
        ));
        std::fs::create_dir(&folder).map_err(|e| anyhow::anyhow!("{}: {e}", folder.display()))?;
        let model = StdinModel {
            path: folder.join(format!("stdin.{}", format.extension())),
            folder,
        };
        std::fs::write(&model.path, bytes)
            .map_err(|e| anyhow::anyhow!("{}: {e}", model.path.display()))?;
        Ok(model)
    }

    /// The file holding the model.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// `message` with the private file's path named as `-`, standard input.
    pub fn rename_in(&self, message: &str) -> String {
        message.replace(&self.path.display().to_string(), "-")
    }
}

impl Drop for StdinModel {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.folder);
    }
}
