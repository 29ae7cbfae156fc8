//! Where the PLY and STL parsers take their bytes from: a file already in memory (the
//! ordinary read) or a file streamed through a buffer (tiling's reads, `io::stream`). Both
//! sit behind one trait, so each format has one parser for both kinds of read.

use std::io::Read;

/// Bytes read so far, and a way to get more.
pub(crate) trait Input {
    /// The bytes at hand; positions into them stay valid until [`Input::more`].
    fn bytes(&self) -> &[u8];

    /// Appends more from the file and drops the bytes before `keep`: `Some(dropped)` (every
    /// position moves down by `dropped`) when more came, `None` (nothing dropped) at the end.
    fn more(&mut self, keep: usize) -> std::io::Result<Option<usize>>;
}

/// A file read whole: nothing more ever comes.
impl Input for &[u8] {
    #[inline]
    fn bytes(&self) -> &[u8] {
        self
    }

    #[inline]
    fn more(&mut self, _keep: usize) -> std::io::Result<Option<usize>> {
        Ok(None)
    }
}

/// Bytes read per refill: large enough that reads are a small part of the time.
const CHUNK: usize = 1 << 20;

/// A file read a chunk at a time; only the bytes a parser still needs are held.
pub(crate) struct Streamed<R> {
    reader: R,
    buf: Vec<u8>,
}

impl<R: Read> Streamed<R> {
    pub(crate) fn new(reader: R) -> Self {
        Self {
            reader,
            buf: Vec::new(),
        }
    }
}

impl<R: Read> Input for Streamed<R> {
    fn bytes(&self) -> &[u8] {
        &self.buf
    }

    fn more(&mut self, keep: usize) -> std::io::Result<Option<usize>> {
        let len = self.buf.len();
        self.buf.resize(len + CHUNK, 0);
        let read = loop {
            match self.reader.read(&mut self.buf[len..]) {
                Ok(n) => break n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => {
                    self.buf.truncate(len);
                    return Err(e);
                }
            }
        };
        self.buf.truncate(len + read);
        if read == 0 {
            return Ok(None);
        }
        let keep = keep.min(len);
        self.buf.drain(..keep);
        Ok(Some(keep))
    }
}

/// Helpers for the readers' tests: streams fed a byte at a time, triangles compared.
#[cfg(test)]
pub(crate) mod testing {
    use std::io::Read;

    /// A reader that gives one byte per read: streams through it cross every refill boundary.
    pub(crate) struct OneByte<'a>(pub &'a [u8]);

    impl Read for OneByte<'_> {
        fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
            match (self.0.split_first(), out.first_mut()) {
                (Some((&b, rest)), Some(o)) => {
                    *o = b;
                    self.0 = rest;
                    Ok(1)
                }
                _ => Ok(0),
            }
        }
    }

    /// The triangles of `scene` as sorted position triples, the way a stream hands them on.
    pub(crate) fn sorted_triangles(scene: &crate::mesh::Scene) -> Vec<[[u32; 3]; 3]> {
        let mut out: Vec<[[u32; 3]; 3]> = scene
            .models
            .iter()
            .flat_map(|m| {
                m.triangles.iter().map(|t| {
                    t.map(|i| {
                        let p = m.transform.transform_point3(m.positions[i as usize]);
                        p.to_array().map(f32::to_bits)
                    })
                })
            })
            .collect();
        out.sort();
        out
    }

    /// Streamed triangles as sorted bit triples, to compare with [`sorted_triangles`].
    pub(crate) fn sorted_bits(triangles: Vec<[[f32; 3]; 3]>) -> Vec<[[u32; 3]; 3]> {
        let mut out: Vec<[[u32; 3]; 3]> = triangles
            .into_iter()
            .map(|t| t.map(|p| p.map(f32::to_bits)))
            .collect();
        out.sort();
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streamed_keeps_what_is_asked_and_ends() {
        let mut s = Streamed::new(&b"abcdef"[..]);
        assert_eq!(s.more(0).unwrap(), Some(0));
        assert_eq!(s.bytes(), b"abcdef");
        assert_eq!(s.more(4).unwrap(), None);
        assert_eq!(s.bytes(), b"abcdef", "nothing is dropped at the end");
    }
}
