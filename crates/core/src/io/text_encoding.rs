//! The text encodings a file may come in before its format is read: a UTF-8 byte-order mark
//! (dropped, as editors on Windows write it), UTF-16 or UTF-32 text (refused with a message
//! that says so, where the readers would each have said something misleading about their
//! own syntax) and classic Mac OS line ends, a lone carriage return (each turned into a line
//! feed, byte for byte, so line numbers stay right). Binary files are left alone: a binary
//! STL (its size matches its count), and a binary PLY's body (only its header is text).

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
    if let Some(encoding) = wide_text(&bytes) {
        return Err(format!(
            "the file is {encoding} text (it starts with a {encoding} byte-order mark): only \
             ASCII or UTF-8 text is read; save it as UTF-8"
        ));
    }
    if bytes.starts_with(&UTF8_BOM) {
        return Ok(bytes[UTF8_BOM.len()..].to_vec());
    }
    Ok(bytes)
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
    let end = if ply {
        ply_text_end(&bytes)
    } else {
        bytes.len()
    };
    for i in 0..end {
        if bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n') {
            bytes[i] = b'\n';
        }
    }
    bytes
}

/// How much of a PLY file with lone-CR line ends is text: up to the end of its
/// `end_header` line, or all of it when the header says `format ascii`.
fn ply_text_end(bytes: &[u8]) -> usize {
    let key = b"\rend_header\r";
    let Some(at) = bytes.windows(key.len()).position(|w| w == key) else {
        return bytes.len(); // no header end: all is header, and its error says so
    };
    let header_end = at + key.len();
    let ascii = bytes[..header_end]
        .windows(b"format ascii".len())
        .any(|w| w == b"format ascii");
    if ascii {
        bytes.len()
    } else {
        header_end
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
}
