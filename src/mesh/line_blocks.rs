//! A text file's whole lines, a block at a time, read ahead on a thread of its own: while one
//! block is parsed (on every core) the next is copied out of the file, so neither waits for
//! the other. Blocks grow from [`FIRST_BLOCK`] bytes to the block size asked for, so that a
//! small file's parse starts after a short read. Two buffers take turns, so a block's pages
//! are faulted in once, not once a block.

use std::io::{self, Read, Take};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};

/// Bytes of the first block read (less when the block size asked for is less): small, since
/// nothing is parsed until it is read. (At 4 MiB the 2.4 MB Stanford bunny was read whole
/// before its parse began, about a tenth of loading it.)
const FIRST_BLOCK: usize = 1 << 18;

/// Why reading the blocks stopped early: the file could not be read, or the caller refused a
/// block.
#[derive(Debug)]
pub enum Stop<E> {
    Io(io::Error),
    Refused(E),
}

/// Calls `each` with the text of `file` (as far as its limit) in order, in blocks of whole
/// lines (the last block may end without `\n`) of about `block` bytes at most (more when a
/// line is longer), each read while the one before is handed to `each`. The first error
/// stops the reading. Empty text gives no block.
pub fn for_each_line_block<R: Read + Send, E>(
    file: &mut Take<R>,
    block: usize,
    mut each: impl FnMut(&[u8]) -> Result<(), E>,
) -> Result<(), Stop<E>> {
    std::thread::scope(|scope| {
        let (full_tx, full_rx) = sync_channel(1);
        let (empty_tx, empty_rx) = sync_channel(2);
        for _ in 0..2 {
            let _ = empty_tx.send(Vec::new());
        }
        scope.spawn(move || read_ahead(file, block.max(1), empty_rx, full_tx));
        // Leaving early drops both channels' ends here, which stops the reader.
        for text in full_rx {
            let text = text.map_err(Stop::Io)?;
            each(&text).map_err(Stop::Refused)?;
            let _ = empty_tx.send(text);
        }
        Ok(())
    })
}

/// The reader's side: fills each buffer `empty` hands back with the next block of whole lines
/// and sends it to `full`, until the file ends, an error (sent too), or the other side leaves.
fn read_ahead<R: Read>(
    file: &mut Take<R>,
    block: usize,
    empty: Receiver<Vec<u8>>,
    full: SyncSender<io::Result<Vec<u8>>>,
) {
    // The start of a line cut by the last block's end: it begins the next block.
    let mut carry = Vec::new();
    let mut size = FIRST_BLOCK.min(block);
    while let Ok(mut text) = empty.recv() {
        text.clear();
        text.append(&mut carry);
        // Read until the block holds a whole line, or the file ends (or reaches its limit).
        let end = loop {
            let from = text.len();
            let room = text.capacity();
            text.reserve(size);
            if text.capacity() > room {
                // Blocks grow to megabytes: in 2 MiB pages they are faulted in 512 times less
                // often (only whole 2 MiB pages inside the buffer are asked for).
                crate::huge_pages::advise(text.spare_capacity_mut());
            }
            match file.by_ref().take(size as u64).read_to_end(&mut text) {
                Err(e) => {
                    let _ = full.send(Err(e));
                    return;
                }
                // Fewer bytes than asked: the file ended.
                Ok(read) if read < size || file.limit() == 0 => break true,
                Ok(_) if memchr::memchr(b'\n', &text[from..]).is_some() => break false,
                Ok(_) => {}
            }
        };
        if !end {
            let whole = memchr::memrchr(b'\n', &text).map_or(0, |at| at + 1);
            carry.extend_from_slice(&text[whole..]);
            text.truncate(whole);
        }
        size = (size * 2).min(block);
        if text.is_empty() || full.send(Ok(text)).is_err() || end {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The blocks `text` is cut into, read `block` bytes at a time.
    fn blocks(text: &[u8], block: usize) -> Vec<Vec<u8>> {
        let mut file = text.take(u64::MAX);
        let mut out = Vec::new();
        for_each_line_block(&mut file, block, |b| {
            out.push(b.to_vec());
            Ok::<(), ()>(())
        })
        .unwrap();
        out
    }

    #[test]
    fn blocks_are_whole_lines_that_join_to_the_text() {
        let text: Vec<u8> = (0..5000)
            .flat_map(|i| format!("v {i} {} 0.5\n", i * 7).into_bytes())
            .chain(*b"last line")
            .collect();
        for block in [1, 2, 7, 64, 1000, 1 << 20, 1 << 30] {
            let cut = blocks(&text, block);
            assert_eq!(cut.concat(), text, "{block}");
            for b in &cut[..cut.len() - 1] {
                assert_eq!(b.last(), Some(&b'\n'), "{block}");
            }
            if block >= text.len() {
                assert_eq!(cut.len(), 1);
            }
        }
        assert!(blocks(b"", 8).is_empty());
        // One line longer than a block stays whole.
        assert_eq!(
            blocks(b"abcdefgh\nij", 2),
            [b"abcdefgh\n".to_vec(), b"ij".to_vec()]
        );
    }

    #[test]
    fn a_refused_block_stops_the_reading() {
        let text = b"a\nb\nc\nd\n".repeat(1000);
        let mut file = (&text[..]).take(u64::MAX);
        let mut seen = 0;
        let stop = for_each_line_block(&mut file, 16, |_| {
            seen += 1;
            if seen == 3 { Err("no") } else { Ok(()) }
        });
        assert!(matches!(stop, Err(Stop::Refused("no"))));
        assert_eq!(seen, 3);
    }
}
