//! The text encodings a file may come in before its format is read: a UTF-8 byte-order mark
//! (dropped, as editors on Windows write it), UTF-16 or UTF-32 text (refused with a message
//! that says so, where the readers would each have said something misleading about their
//! own syntax) and classic Mac OS line ends, a lone carriage return (each turned into a line
//! feed, byte for byte, so line numbers stay right). Binary files are left alone: a binary
//! STL (its size matches its count), and a binary PLY's body (only its header is text).
//!
//! Files read whole go through [`drop_byte_order_mark`] and [`mac_line_ends`]; tiling's
//! streamed reads decide the same from the file's first bytes ([`read_head`],
//! [`streamed_text`]) and turn lone carriage returns into line feeds as they read
//! ([`LoneCrToLf`]), so both kinds of read give the same counts and the same refusals.

use std::io::{BufRead, Read};

/// The UTF-8 byte-order mark.
const UTF8_BOM: [u8; 3] = [0xEF, 0xBB, 0xBF];

/// What a byte-order mark says the text is, when it is not UTF-8.
fn wide_text(bytes: &[u8]) -> Option<&'static str> {
    // UTF-32 LE begins like UTF-16 LE: look for it first.
    if bytes.starts_with(&[0xFF, 0xFE, 0, 0]) || bytes.starts_with(&[0, 0, 0xFE, 0xFF]) {
        Some("UTF-32")
    } else if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
        Some("UTF-16")
    } else {
        None
    }
}

/// Drops a UTF-8 byte-order mark and refuses UTF-16 and UTF-32 text (the error message);
/// `binary` files (a binary STL, whose 80-byte header may hold anything) are returned as
/// they are.
pub(super) fn drop_byte_order_mark(bytes: Vec<u8>, binary: bool) -> Result<Vec<u8>, String> {
    if binary {
        return Ok(bytes);
    }
    match mark_length(&bytes)? {
        0 => Ok(bytes),
        n => Ok(bytes[n..].to_vec()),
    }
}

/// A text file that is no model (an OBJ's `.mtl`) taken as a model's text is: the mark
/// dropped, lone carriage returns turned into line feeds; an error for UTF-16 and UTF-32.
pub(super) fn plain_text(bytes: Vec<u8>) -> Result<Vec<u8>, String> {
    Ok(mac_line_ends(
        drop_byte_order_mark(bytes, false)?,
        false,
        false,
    ))
}

/// The length of the UTF-8 byte-order mark `bytes` start with (0 without one); an error
/// for UTF-16 and UTF-32 text.
fn mark_length(bytes: &[u8]) -> Result<usize, String> {
    if let Some(encoding) = wide_text(bytes) {
        return Err(format!(
            "the file is {encoding} text (it starts with a {encoding} byte-order mark): only \
             ASCII or UTF-8 text is read; save it as UTF-8"
        ));
    }
    Ok(if bytes.starts_with(&UTF8_BOM) {
        UTF8_BOM.len()
    } else {
        0
    })
}

/// Whether the first line ends with a lone carriage return (classic Mac OS line ends).
fn lone_cr_lines(bytes: &[u8]) -> bool {
    let Some(end) = bytes.iter().position(|&b| b == b'\n' || b == b'\r') else {
        return false;
    };
    bytes[end] == b'\r' && bytes.get(end + 1) != Some(&b'\n')
}

/// Turns lone carriage returns into line feeds when the first line ends with one: in the
/// whole file, or for a PLY file (`ply`) in its header only, unless the header says the
/// body is ASCII too. `binary` files are left alone.
pub(super) fn mac_line_ends(mut bytes: Vec<u8>, ply: bool, binary: bool) -> Vec<u8> {
    if binary || !lone_cr_lines(&bytes) {
        return bytes;
    }
    let end = match ply {
        true => ply_text_end(&bytes).unwrap_or(bytes.len()),
        false => bytes.len(),
    };
    let next = bytes.get(end).copied();
    lone_crs_to_line_feeds(&mut bytes[..end], next);
    bytes
}

/// Turns each carriage return of `text` not followed by a line feed into one; `next` is the
/// byte after `text`, if any.
fn lone_crs_to_line_feeds(text: &mut [u8], next: Option<u8>) {
    let n = text.len();
    for i in 0..n {
        let after = if i + 1 < n { Some(text[i + 1]) } else { next };
        if text[i] == b'\r' && after != Some(b'\n') {
            text[i] = b'\n';
        }
    }
}

/// The `end_header` line of a PLY file with lone-CR line ends.
const PLY_HEADER_END: &[u8] = b"\rend_header\r";

/// How much of a PLY file with lone-CR line ends is text: up to the end of its
/// `end_header` line; `None` (all of it) when the header says `format ascii` or has no end
/// (then its error says so).
fn ply_text_end(bytes: &[u8]) -> Option<usize> {
    let key = PLY_HEADER_END;
    let at = bytes.windows(key.len()).position(|w| w == key)?;
    let header_end = at + key.len();
    let ascii = bytes[..header_end]
        .windows(b"format ascii".len())
        .any(|w| w == b"format ascii");
    (!ascii).then_some(header_end)
}

/// The most a streamed read looks at before it decides how to read its text: a PLY
/// header's limit (`ply::MAX_HEADER`) and some.
const HEAD_LIMIT: usize = 17 << 20;

/// Whether `head`, a streamed file's first bytes, tell how its text is read: they hold the
/// first line's end and, after a carriage return, the byte after it; for a PLY file (by its
/// name, `ply_by_name`, or its first word) with lone-CR line ends, also its header's end.
fn head_decides(head: &[u8], ply_by_name: bool) -> bool {
    let text = match mark_length(head) {
        Ok(n) => &head[n..],
        Err(_) => return true,
    };
    let Some(end) = text.iter().position(|&b| b == b'\n' || b == b'\r') else {
        return false;
    };
    if text[end] == b'\n' {
        return true;
    }
    if end + 1 == text.len() {
        return false;
    }
    let ply = ply_by_name || text.starts_with(b"ply");
    !ply || !lone_cr_lines(text)
        || text
            .windows(PLY_HEADER_END.len())
            .any(|w| w == PLY_HEADER_END)
}

/// A streamed file's first bytes: as many as [`streamed_text`] needs to decide (at most
/// [`HEAD_LIMIT`], fewer at the end of the file). Each read doubles what is held, so the
/// looking is linear in the bytes read.
pub(super) fn read_head(file: &mut impl Read, ply_by_name: bool) -> std::io::Result<Vec<u8>> {
    let mut head = Vec::new();
    let mut want = 1 << 16;
    while !head_decides(&head, ply_by_name) && head.len() < HEAD_LIMIT {
        let had = head.len();
        let got = file
            .by_ref()
            .take((want - had) as u64)
            .read_to_end(&mut head)?;
        if got < want - had {
            break; // the end of the file
        }
        want = (want * 2).min(HEAD_LIMIT);
    }
    Ok(head)
}

/// How a streamed read takes the text its file starts with (`head`, from [`read_head`]):
/// how many bytes of a byte-order mark to skip, and in how many bytes after them lone
/// carriage returns become line feeds (0: none; `u64::MAX`: the whole file), the same as
/// [`drop_byte_order_mark`] and [`mac_line_ends`] do for a file read whole. A PLY file is
/// one by its name (`ply_by_name`) or its first word; `binary` as there; an error for
/// UTF-16 and UTF-32 text.
pub(super) fn streamed_text(
    head: &[u8],
    ply_by_name: bool,
    binary: bool,
) -> Result<(usize, u64), String> {
    if binary {
        return Ok((0, 0));
    }
    let skip = mark_length(head)?;
    let text = &head[skip..];
    if !lone_cr_lines(text) {
        return Ok((skip, 0));
    }
    let end = match ply_by_name || text.starts_with(b"ply") {
        true => ply_text_end(text).map_or(u64::MAX, |e| e as u64),
        false => u64::MAX,
    };
    Ok((skip, end))
}

/// A reader that turns lone carriage returns into line feeds in the first bytes it reads
/// (see [`streamed_text`]), looking one byte ahead where a read ends on a carriage return;
/// after them it hands reads straight on.
pub(super) struct LoneCrToLf<R> {
    inner: R,
    /// Bytes still to convert.
    left: u64,
}

impl<R: BufRead> LoneCrToLf<R> {
    pub(super) fn new(inner: R, left: u64) -> Self {
        Self { inner, left }
    }
}

impl<R: BufRead> Read for LoneCrToLf<R> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        if self.left == 0 {
            return self.inner.read(out);
        }
        let n = {
            let buf = self.inner.fill_buf()?;
            let n = buf.len().min(out.len());
            out[..n].copy_from_slice(&buf[..n]);
            n
        };
        self.inner.consume(n);
        let text = n.min(usize::try_from(self.left).unwrap_or(usize::MAX));
        if text == 0 {
            return Ok(n);
        }
        let next = match out.get(text) {
            Some(&b) if text < n => Some(b),
            _ if out[text - 1] == b'\r' => self.inner.fill_buf()?.first().copied(),
            _ => None,
        };
        lone_crs_to_line_feeds(&mut out[..text], next);
        self.left -= text as u64;
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_utf8_mark_is_dropped_and_wide_text_refused() {
        let text = b"\xEF\xBB\xBFv 0 0 0\n".to_vec();
        assert_eq!(drop_byte_order_mark(text, false).unwrap(), b"v 0 0 0\n");
        let wide = b"\xFF\xFEv\x00".to_vec();
        let err = drop_byte_order_mark(wide.clone(), false).unwrap_err();
        assert!(err.contains("UTF-16"), "{err}");
        assert_eq!(drop_byte_order_mark(wide.clone(), true).unwrap(), wide);
    }

    #[test]
    fn lone_carriage_returns_become_line_feeds_but_not_in_a_binary_ply_body() {
        let obj = b"v 0 0 0\rv 1 0 0\r".to_vec();
        assert_eq!(mac_line_ends(obj, false, false), b"v 0 0 0\nv 1 0 0\n");
        let crlf = b"v 0 0 0\r\nv\r".to_vec();
        assert_eq!(mac_line_ends(crlf.clone(), false, false), crlf);
        let ply = b"ply\rformat binary_little_endian 1.0\rend_header\r\r\r".to_vec();
        let read = mac_line_ends(ply, true, false);
        assert_eq!(
            read,
            b"ply\nformat binary_little_endian 1.0\nend_header\n\r\r".to_vec()
        );
        let ascii = b"ply\rformat ascii 1.0\rend_header\r0\r".to_vec();
        assert_eq!(
            mac_line_ends(ascii, true, false),
            b"ply\nformat ascii 1.0\nend_header\n0\n"
        );
    }

    /// The bytes a streamed read hands its parser: the head decided on, the mark skipped,
    /// lone carriage returns converted, the file read one byte at a time.
    fn streamed(bytes: &[u8], ply_by_name: bool) -> Result<Vec<u8>, String> {
        let mut file = bytes;
        let head = read_head(&mut file, ply_by_name).unwrap();
        let (skip, convert) = streamed_text(&head, ply_by_name, false)?;
        let rest = std::io::BufReader::with_capacity(1, head[skip..].chain(file));
        let mut out = Vec::new();
        LoneCrToLf::new(rest, convert)
            .read_to_end(&mut out)
            .unwrap();
        Ok(out)
    }

    #[test]
    fn a_streamed_read_sees_the_bytes_a_whole_read_sees() {
        let ply = b"ply\rformat binary_little_endian 1.0\rend_header\r\r\r\n\r".to_vec();
        let ascii = b"\xEF\xBB\xBFply\rformat ascii 1.0\rend_header\r0\r\r\n\r".to_vec();
        let obj = b"\xEF\xBB\xBFv 0 0 0\rv 1 0 0\r\nv\r\r".to_vec();
        let cases = [
            (ply, true),
            (ascii, false),
            (obj.clone(), false),
            (b"v 0\r\nv 1\r".to_vec(), false),
            (b"v 0\r".to_vec(), false),
            (b"\r".to_vec(), false),
            (Vec::new(), false),
        ];
        for (bytes, ply_by_name) in cases {
            let ply = ply_by_name || bytes.windows(3).any(|w| w == b"ply");
            let whole = drop_byte_order_mark(bytes.clone(), false).unwrap();
            let whole = mac_line_ends(whole, ply, false);
            assert_eq!(streamed(&bytes, ply_by_name).unwrap(), whole, "{bytes:?}");
        }
        let err = streamed(b"\xFF\xFEv\x00", false).unwrap_err();
        assert!(err.contains("UTF-16"), "{err}");
        // A long first line is looked at whole, past the first read's 64 KiB.
        let long = [vec![b' '; 100_000], obj].concat();
        assert!(streamed(&long, false).unwrap().ends_with(b"v\n\n"));
    }
}
