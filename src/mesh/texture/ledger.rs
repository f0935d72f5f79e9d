//! The memory one model's textures will take once decoded, committed texture by texture from
//! their headers before each is decoded, and held against the memory bound together with the
//! model's triangles and objects. A model naming many large images is refused after reading
//! headers alone, not after decoding gigabytes of texels.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::limits::MAX_TEXTURE_BASE_TEXELS;
use super::texels::TEXEL_BYTES;
use crate::memory_budget::{Estimate, OverBudget};

/// The running account of one model load. Clones share one account.
#[derive(Debug, Clone)]
pub struct TextureLedger {
    account: Arc<Mutex<Account>>,
}

#[derive(Debug)]
struct Account {
    /// The model file the figures are for.
    model: PathBuf,
    /// The model's triangles and objects, as far as they are known when textures are read.
    model_estimate: Estimate,
    /// Bytes of the textures committed so far (decoded size, mip chains included).
    committed: u64,
    /// The first texture refused, with the figures: the load fails with it.
    refused: Option<OverBudget>,
}

impl TextureLedger {
    /// An empty account for the model file at `model`.
    pub fn new(model: &Path) -> TextureLedger {
        TextureLedger {
            account: Arc::new(Mutex::new(Account {
                model: model.to_path_buf(),
                model_estimate: Estimate::default(),
                committed: 0,
                refused: None,
            })),
        }
    }

    /// Counts the model's own triangles and objects beside its textures (the loader calls this
    /// once it knows them, before reading textures where it can).
    pub fn count_model(&self, estimate: Estimate) {
        self.lock().model_estimate = Estimate {
            texture_bytes: 0,
            frame_bytes: 0,
            ..estimate
        };
    }

    /// Commits the memory a texture whose header declares `width × height` will take once
    /// decoded, when the model's estimate with it stays within the bound in force; else the
    /// figures, and the account remembers the refusal.
    pub fn commit(&self, width: u32, height: u32) -> Result<(), OverBudget> {
        let mut account = self.lock();
        let committed = account
            .committed
            .saturating_add(decoded_texture_bytes(width, height));
        let estimate = Estimate {
            texture_bytes: committed,
            ..account.model_estimate
        };
        match estimate.check(&account.model) {
            Ok(()) => {
                account.committed = committed;
                Ok(())
            }
            Err(over) => {
                account.refused.get_or_insert_with(|| over.clone());
                Err(over)
            }
        }
    }

    /// The first refusal, if any texture was refused: the loader fails the load with it.
    pub fn refusal(&self) -> Option<OverBudget> {
        self.lock().refused.clone()
    }

    /// Bytes committed so far.
    pub fn committed(&self) -> u64 {
        self.lock().committed
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Account> {
        // The account holds plain numbers: a panic elsewhere cannot leave it half-written.
        self.account
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

/// Bytes a texture declared `width × height` takes once decoded: its base level (the image, or,
/// when it has more than [`MAX_TEXTURE_BASE_TEXELS`], the image halved until it fits) and every
/// level below, at 8 bytes (16-bit linear RGBA) a texel. Equal to
/// [`super::Texture::memory_bytes`] of the decoded texture.
pub fn decoded_texture_bytes(width: u32, height: u32) -> u64 {
    let (mut w, mut h) = (u64::from(width.max(1)), u64::from(height.max(1)));
    while w * h > MAX_TEXTURE_BASE_TEXELS {
        (w, h) = ((w / 2).max(1), (h / 2).max(1));
    }
    let mut texels = w * h;
    while w > 1 || h > 1 {
        (w, h) = ((w / 2).max(1), (h / 2).max(1));
        texels += w * h;
    }
    texels * TEXEL_BYTES
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::memory_budget::{BASE_BYTES, memory_bound};

    #[test]
    fn the_declared_size_gives_a_chain_of_halvings_down_to_one_texel() {
        // 4×2, then 2×1 and 1×1, at 8 bytes a texel.
        assert_eq!(decoded_texture_bytes(4, 2), 8 * (8 + 2 + 1));
        // 5×3, 2×1, 1×1: an odd side rounds down.
        assert_eq!(decoded_texture_bytes(5, 3), 8 * (15 + 2 + 1));
        // 8192² is halved once to a 4096² base before its chain.
        assert_eq!(
            decoded_texture_bytes(8192, 8192),
            decoded_texture_bytes(4096, 4096)
        );
        let chain_below = decoded_texture_bytes(4096, 4096) - 8 * 4096 * 4096;
        // The chain below takes a third of the base's texels, at 8 bytes.
        assert_eq!(chain_below / 8, (4096 * 4096 - 1) / 3);
    }

    #[test]
    fn textures_are_committed_until_the_bound_and_the_first_refusal_is_kept() {
        let ledger = TextureLedger::new(Path::new("many.gltf"));
        let room = memory_bound() - BASE_BYTES;
        let each = decoded_texture_bytes(4096, 4096);
        let fit = room / each;
        for _ in 0..fit {
            ledger.commit(4096, 4096).expect("within the bound");
        }
        assert_eq!(ledger.committed(), fit * each);
        assert!(ledger.refusal().is_none());
        let over = ledger
            .commit(4096, 4096)
            .expect_err("one more passes the bound");
        assert_eq!(over.estimate.texture_bytes, (fit + 1) * each);
        assert_eq!(
            ledger.committed(),
            fit * each,
            "a refused texture is not committed"
        );
        assert!(over.to_string().starts_with("many.gltf: "), "{over}");
        assert_eq!(ledger.refusal(), Some(over));
    }

    #[test]
    fn the_model_s_triangles_leave_less_room_for_textures() {
        let ledger = TextureLedger::new(Path::new("m.obj"));
        ledger
            .commit(1024, 1024)
            .expect("a small texture fits an empty model");
        ledger.count_model(Estimate {
            triangles: crate::memory_budget::MAX_TRIANGLES,
            objects: 1,
            ..Estimate::default()
        });
        assert!(ledger.commit(1024, 1024).is_err());
    }
}
