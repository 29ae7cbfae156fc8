//! `data:` URIs (RFC 2397): how a glTF file embeds buffers and images in its JSON, and how a
//! `Model::texture` holds an image that has no file of its own (one embedded in a `.glb`).
//! [`parse`] gives the media type and the bytes; [`encode`] makes a base64 URI.

use base64::Engine as _;

/// A decoded `data:` URI: its media type (`image/png`, empty when not given) and bytes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DataUri {
    /// The media type, `image/png`; empty when the URI gives none.
    pub media_type: String,
    /// The decoded payload.
    pub bytes: Vec<u8>,
}

/// True when `uri` is a `data:` URI (case-insensitive scheme).
pub fn is_data_uri(uri: &str) -> bool {
    uri.get(..5)
        .is_some_and(|s| s.eq_ignore_ascii_case("data:"))
}

/// Decodes a `data:[<media type>][;base64],<data>` URI; `None` when `uri` is not one.
/// Without `;base64` the data is percent-encoded text.
pub fn parse(uri: &str) -> Option<Result<DataUri, String>> {
    if !is_data_uri(uri) {
        return None;
    }
    let rest = &uri[5..];
    let Some((header, data)) = rest.split_once(',') else {
        return Some(Err("a data: URI without ',' before its data".into()));
    };
    let (media_type, base64) = match header.strip_suffix(";base64") {
        Some(m) => (m, true),
        None => (header, false),
    };
    let media_type = media_type
        .split(';')
        .next()
        .unwrap_or_default()
        .to_ascii_lowercase();
    let bytes = if base64 {
        let data: String = data.chars().filter(|c| !c.is_ascii_whitespace()).collect();
        match base64::engine::general_purpose::STANDARD.decode(data.trim_end_matches('=')) {
            Ok(b) => b,
            Err(_) => match base64::engine::general_purpose::STANDARD_NO_PAD
                .decode(data.trim_end_matches('='))
            {
                Ok(b) => b,
                Err(e) => return Some(Err(format!("a data: URI's base64 is damaged: {e}"))),
            },
        }
    } else {
        percent_decode(data)
    };
    Some(Ok(DataUri { media_type, bytes }))
}

/// A base64 `data:` URI holding `bytes` of `media_type`.
pub fn encode(media_type: &str, bytes: &[u8]) -> String {
    format!(
        "data:{media_type};base64,{}",
        base64::engine::general_purpose::STANDARD.encode(bytes)
    )
}

/// `%XX` escapes decoded into bytes; a `%` not followed by two hex digits is kept as it is.
pub fn percent_decode(s: &str) -> Vec<u8> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%' && i + 2 < b.len() {
            if let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(b[i]);
        i += 1;
    }
    out
}

/// The media type of an image by its first bytes: PNG or JPEG, the two glTF core allows.
pub fn image_media_type(bytes: &[u8]) -> Option<&'static str> {
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        Some("image/png")
    } else if bytes.starts_with(&[0xff, 0xd8, 0xff]) {
        Some("image/jpeg")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_and_percent_encoded_uris_decode_to_their_bytes() {
        let uri = encode("image/png", b"\x89PNG\r\n\x1a\nrest");
        let d = parse(&uri).unwrap().unwrap();
        assert_eq!(d.media_type, "image/png");
        assert_eq!(d.bytes, b"\x89PNG\r\n\x1a\nrest");
        let t = parse("data:,a%20b%2").unwrap().unwrap();
        assert_eq!(t.media_type, "");
        assert_eq!(t.bytes, b"a b%2");
        assert!(parse("image.png").is_none());
        assert!(parse("data:application/octet-stream;base64,@@@")
            .unwrap()
            .is_err());
        assert!(parse("data:no-comma").unwrap().is_err());
    }

    #[test]
    fn images_are_told_by_their_first_bytes() {
        assert_eq!(image_media_type(b"\x89PNG\r\n\x1a\n.."), Some("image/png"));
        assert_eq!(
            image_media_type(&[0xff, 0xd8, 0xff, 0xe0]),
            Some("image/jpeg")
        );
        assert_eq!(image_media_type(b"GIF89a"), None);
    }
}
