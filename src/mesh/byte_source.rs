//! A file read forward through one buffer, for the binary model readers: records are handed out
//! as slices of the buffer, and the offset of every byte in the file is known, so that an error
//! can say where it lies.

use std::fs::File;
use std::io::{Read, Take};
use std::path::Path;

use crate::input_file::{MAX_MODEL_BYTES, open_bounded};

/// Bytes read ahead at a time: large enough that a read costs little per byte, small enough to
/// stay in the cache of one core.
pub const BLOCK: usize = 1 << 18;

/// A model file read forward: the source the binary readers' parallel paths take.
pub type ModelSource = ByteSource<Take<File>>;

/// A reader with a buffer that hands out contiguous slices.
///
/// Invariant: `start <= end <= buf.len()`; `buf[start..end]` are the next unread bytes of the
/// file, the first of them at file offset `offset`.
pub struct ByteSource<R> {
    reader: R,
    buf: Vec<u8>,
    start: usize,
    end: usize,
    offset: u64,
}

impl ByteSource<Take<File>> {
    /// The model file at `path` (a regular file of at most [`MAX_MODEL_BYTES`]) from its
    /// start, and its size in bytes. The reader stops one byte past the cap: a file that grew
    /// while it was read leaves its limit at 0.
    pub fn open_model(path: &Path) -> std::io::Result<(Self, u64)> {
        let file = open_bounded(path, MAX_MODEL_BYTES, "a model file")?;
        let size = file.get_ref().metadata()?.len();
        Ok((ByteSource::new(file), size))
    }

    /// The next `n` bytes (fewer when the file or its limit ends first) in a vector of their
    /// own, consumed: those buffered are copied, the rest read straight into the vector (fresh
    /// zeroed pages, never filled by hand) in pieces read in parallel, so that two cores share
    /// the copying and the page faults.
    pub fn take_vec(&mut self, n: usize) -> std::io::Result<Vec<u8>> {
        let buffered = (self.end - self.start).min(n);
        let limit = self.reader.limit();
        let rest = ((n - buffered) as u64).min(limit) as usize;
        let mut out = vec![0u8; buffered + rest];
        crate::huge_pages::advise(&mut out);
        out[..buffered].copy_from_slice(&self.buf[self.start..self.start + buffered]);
        self.consume(buffered);
        // All that was buffered is consumed (or nothing more is read): the file stands at
        // `offset`.
        let (file, from) = (self.reader.get_ref(), self.offset);
        let read = read_in_pieces(file, from, &mut out[buffered..], TAKE_PIECE)?;
        out.truncate(buffered + read);
        self.advance_file(read)?;
        self.offset += read as u64;
        Ok(out)
    }

    /// As [`ByteSource::ahead`], with the bytes not yet buffered read in parallel pieces, so
    /// that two cores share the copy from the page cache: for blocks of megabytes, which a
    /// binary reader decodes in parallel.
    pub fn ahead_in_parallel(&mut self, min: usize) -> std::io::Result<&[u8]> {
        if self.end - self.start < min {
            self.buf.copy_within(self.start..self.end, 0);
            self.end -= self.start;
            self.start = 0;
            if self.buf.len() < min.max(BLOCK) {
                self.buf.resize(min.max(BLOCK), 0);
            }
            let want = ((min - self.end) as u64).min(self.reader.limit()) as usize;
            // Every buffered byte has been read: the file stands just past them.
            let from = self.offset + self.end as u64;
            let out = &mut self.buf[self.end..self.end + want];
            let read = read_in_pieces(self.reader.get_ref(), from, out, PARALLEL_PIECE)?;
            self.advance_file(read)?;
            self.end += read;
        }
        Ok(&self.buf[self.start..self.end])
    }

    /// Moves the file and its limit on by `read` bytes, read at their offsets.
    fn advance_file(&mut self, read: usize) -> std::io::Result<()> {
        use std::io::{Seek, SeekFrom};
        self.reader.get_mut().seek(SeekFrom::Current(read as i64))?;
        let limit = self.reader.limit();
        self.reader.set_limit(limit - read as u64);
        Ok(())
    }
}

/// Reads `out` from `file` at offset `from` in pieces of `piece` bytes, read in parallel; how
/// many bytes were read before the first piece the file's end cut short.
fn read_in_pieces(file: &File, from: u64, out: &mut [u8], piece: usize) -> std::io::Result<usize> {
    use std::os::unix::fs::FileExt;

    use rayon::prelude::*;

    let pieces: Vec<std::io::Result<usize>> = out
        .par_chunks_mut(piece)
        .enumerate()
        .map(|(k, out)| {
            let mut done = 0;
            while done < out.len() {
                match file.read_at(&mut out[done..], from + (k * piece + done) as u64) {
                    Ok(0) => break,
                    Ok(got) => done += got,
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(e),
                }
            }
            Ok(done)
        })
        .collect();
    let mut read = 0;
    for (k, got) in pieces.into_iter().enumerate() {
        let got = got?;
        read += got;
        if got < piece.min(out.len() - k * piece) {
            break;
        }
    }
    Ok(read)
}

/// Bytes one task of [`ByteSource::ahead_in_parallel`] reads.
const PARALLEL_PIECE: usize = 1 << 20;

/// Bytes one task of [`ByteSource::take_vec`] reads.
const TAKE_PIECE: usize = 1 << 22;

impl<R: Read> ByteSource<R> {
    /// A source reading `reader` from file offset 0.
    pub fn new(reader: R) -> ByteSource<R> {
        ByteSource {
            reader,
            buf: vec![0; BLOCK],
            start: 0,
            end: 0,
            offset: 0,
        }
    }

    /// File offset of the next unread byte.
    pub fn offset(&self) -> u64 {
        self.offset
    }

    /// The unread bytes buffered, at least `min` of them unless the file ends first (then all
    /// that is left, possibly none). `min` may exceed [`BLOCK`]: the buffer grows.
    pub fn ahead(&mut self, min: usize) -> std::io::Result<&[u8]> {
        if self.end - self.start < min {
            self.fill(min)?;
        }
        Ok(&self.buf[self.start..self.end])
    }

    /// Marks `n` buffered bytes as read.
    ///
    /// # Panics
    /// If fewer than `n` bytes are buffered (a caller bug).
    #[inline]
    pub fn consume(&mut self, n: usize) {
        assert!(
            n <= self.end - self.start,
            "consumed more than was buffered"
        );
        self.start += n;
        self.offset += n as u64;
    }

    /// The inner reader (to ask how much of its limit is left).
    pub fn get_ref(&self) -> &R {
        &self.reader
    }

    /// Reads until `min` bytes are buffered or the file ends.
    fn fill(&mut self, min: usize) -> std::io::Result<()> {
        self.buf.copy_within(self.start..self.end, 0);
        self.end -= self.start;
        self.start = 0;
        if self.buf.len() < min.max(BLOCK) {
            self.buf.resize(min.max(BLOCK), 0);
        }
        while self.end < min {
            match self.reader.read(&mut self.buf[self.end..]) {
                Ok(0) => break,
                Ok(n) => self.end += n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        Ok(())
    }
}

/// The unread bytes as a plain reader (for a line reader over a text body).
impl<R: Read> Read for ByteSource<R> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let ahead = self.ahead(1)?;
        let n = ahead.len().min(out.len());
        out[..n].copy_from_slice(&ahead[..n]);
        self.consume(n);
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slices_come_in_order_with_their_offsets_and_a_short_end_is_all_there_is() {
        let bytes: Vec<u8> = (0..=255)
            .cycle()
            .take(BLOCK + 100)
            .map(|b| b as u8)
            .collect();
        let mut source = ByteSource::new(bytes.as_slice());
        assert_eq!(&source.ahead(3).unwrap()[..3], &[0u8, 1, 2]);
        source.consume(3);
        assert_eq!(source.offset(), 3);
        let far = source.ahead(BLOCK).unwrap()[..BLOCK].to_vec();
        assert_eq!(far, bytes[3..BLOCK + 3]);
        source.consume(BLOCK);
        assert_eq!(source.ahead(1000).unwrap().len(), 97);
        assert_eq!(source.offset(), BLOCK as u64 + 3);
        let mut rest = Vec::new();
        std::io::Read::read_to_end(&mut source, &mut rest).unwrap();
        assert_eq!(rest, bytes[BLOCK + 3..]);
        assert!(source.ahead(1).unwrap().is_empty());
    }
}
