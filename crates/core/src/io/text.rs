//! What every text reader (VRML, Inventor, PLY, OBJ, MTL, OFF, STL) shares: the error that
//! names a line, number parsing straight from a token's bytes, and the logical lines and
//! words of the line-oriented formats.

use std::borrow::Cow;

/// A lexical or syntax error at a line (the file name is added by the caller).
#[derive(Debug, Clone, PartialEq)]
pub struct ParseError {
    pub line: usize,
    pub message: String,
}

impl ParseError {
    pub fn new(line: usize, message: impl Into<String>) -> Self {
        Self {
            line,
            message: message.into(),
        }
    }
}

pub type PResult<T> = Result<T, ParseError>;

/// Parses a float token's bytes; `None` when malformed.
pub fn parse_f32(bytes: &[u8]) -> Option<f32> {
    // std parses f32 correctly rounded; the span is ASCII, so the UTF-8 check is cheap.
    let s = std::str::from_utf8(bytes).ok()?;
    if bytes.len() > 2 && bytes[0] == b'0' && matches!(bytes[1], b'x' | b'X') {
        return parse_int(bytes).map(|v| v as f32);
    }
    s.parse::<f32>().ok()
}

/// As [`parse_f32`], to an f64: coordinates, which may be far from zero (see `io::origin`).
pub fn parse_f64(bytes: &[u8]) -> Option<f64> {
    let s = std::str::from_utf8(bytes).ok()?;
    if bytes.len() > 2 && bytes[0] == b'0' && matches!(bytes[1], b'x' | b'X') {
        return parse_int(bytes).map(|v| v as f64);
    }
    s.parse::<f64>().ok()
}

/// Parses an integer token's bytes (decimal with sign, or `0x` hexadecimal); `None` when
/// malformed or beyond 64 bits.
pub fn parse_int(bytes: &[u8]) -> Option<i64> {
    let (neg, digits) = match bytes.first()? {
        b'-' => (true, &bytes[1..]),
        b'+' => (false, &bytes[1..]),
        _ => (false, bytes),
    };
    if digits.is_empty() {
        return None;
    }
    let mut v: i64 = 0;
    if digits.len() > 2 && digits[0] == b'0' && matches!(digits[1], b'x' | b'X') {
        for &d in &digits[2..] {
            let x = (d as char).to_digit(16)? as i64;
            v = v.checked_mul(16)?.checked_add(x)?;
        }
    } else {
        for &d in digits {
            if !d.is_ascii_digit() {
                return None;
            }
            v = v.checked_mul(10)?.checked_add((d - b'0') as i64)?;
        }
    }
    Some(if neg { -v } else { v })
}

/// Logical lines of a text file: `(line number of its first physical line, text)`, with
/// `#` comments cut off and, when `continuation` is set, lines ending in `\` joined to the
/// next. Borrowed unless joined.
pub(crate) struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: usize,
    continuation: bool,
}

impl<'a> Lines<'a> {
    pub(crate) fn new(bytes: &'a [u8], continuation: bool) -> Self {
        Self {
            bytes,
            pos: 0,
            line: 0,
            continuation,
        }
    }

    /// The line number of the last line read (for end-of-file messages).
    pub(crate) fn last_line(&self) -> usize {
        self.line.max(1)
    }

    pub(crate) fn physical(&mut self) -> Option<&'a [u8]> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let rest = &self.bytes[self.pos..];
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        self.pos += end + 1;
        self.line += 1;
        let mut text = &rest[..end];
        if let Some(hash) = text.iter().position(|&b| b == b'#') {
            text = &text[..hash];
        }
        Some(text)
    }
}

fn trim_end(mut s: &[u8]) -> &[u8] {
    while let [rest @ .., last] = s {
        if last.is_ascii_whitespace() {
            s = rest;
        } else {
            break;
        }
    }
    s
}

impl<'a> Iterator for Lines<'a> {
    type Item = (usize, Cow<'a, [u8]>);

    fn next(&mut self) -> Option<Self::Item> {
        let first = self.physical()?;
        let start = self.line;
        if !self.continuation || trim_end(first).last() != Some(&b'\\') {
            return Some((start, Cow::Borrowed(first)));
        }
        Some((start, Cow::Owned(join_continued(first, || self.physical()))))
    }
}

/// A line ending in `\` (`first`) joined with the physical lines `next` gives after it, each
/// `\` becoming a space, up to the first line that does not end in one.
fn join_continued<T: AsRef<[u8]>>(first: T, mut next: impl FnMut() -> Option<T>) -> Vec<u8> {
    let mut joined = Vec::new();
    let mut cur = first;
    loop {
        let t = trim_end(cur.as_ref());
        match t.split_last() {
            Some((b'\\', body)) => {
                joined.extend_from_slice(body);
                joined.push(b' ');
                match next() {
                    Some(n) => cur = n,
                    None => break,
                }
            }
            _ => {
                joined.extend_from_slice(cur.as_ref());
                break;
            }
        }
    }
    joined
}

/// [`Lines`] of a file streamed through a buffer (tiling's OBJ read): the same comments and
/// continuations, each line owned.
pub(crate) struct StreamedLines<R> {
    input: R,
    line: usize,
    continuation: bool,
    failed: bool,
}

impl<R: std::io::BufRead> StreamedLines<R> {
    pub(crate) fn new(input: R, continuation: bool) -> Self {
        Self {
            input,
            line: 0,
            continuation,
            failed: false,
        }
    }

    fn physical(&mut self) -> std::io::Result<Option<Vec<u8>>> {
        let mut text = Vec::new();
        if self.input.read_until(b'\n', &mut text)? == 0 {
            return Ok(None);
        }
        self.line += 1;
        if text.last() == Some(&b'\n') {
            text.pop();
        }
        if let Some(hash) = text.iter().position(|&b| b == b'#') {
            text.truncate(hash);
        }
        Ok(Some(text))
    }

    fn failure(&mut self, e: std::io::Error) -> ParseError {
        self.failed = true;
        ParseError::new(self.line + 1, format!("the file could not be read: {e}"))
    }
}

impl<R: std::io::BufRead> Iterator for StreamedLines<R> {
    type Item = PResult<(usize, Vec<u8>)>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let first = match self.physical() {
            Ok(first) => first?,
            Err(e) => return Some(Err(self.failure(e))),
        };
        let start = self.line;
        if !self.continuation || trim_end(&first).last() != Some(&b'\\') {
            return Some(Ok((start, first)));
        }
        let mut error = None;
        let joined = join_continued(first, || {
            self.physical().unwrap_or_else(|e| {
                error = Some(e);
                None
            })
        });
        match error {
            Some(e) => Some(Err(self.failure(e))),
            None => Some(Ok((start, joined))),
        }
    }
}

/// The whitespace-separated words of a line.
pub(crate) fn words(s: &[u8]) -> impl Iterator<Item = &[u8]> {
    s.split(|b| b.is_ascii_whitespace())
        .filter(|w| !w.is_empty())
}

/// A word for messages (at most 40 characters).
pub(crate) fn shown(w: &[u8]) -> String {
    String::from_utf8_lossy(w).chars().take(40).collect()
}

/// Parses a finite number or fails naming what it was for.
pub(crate) fn number(w: Option<&[u8]>, line: usize, what: &str) -> PResult<f32> {
    finite(w, line, what, parse_f32, f32::is_finite)
}

/// As [`number`], to an f64: a coordinate, which may be far from zero.
pub(crate) fn coordinate(w: Option<&[u8]>, line: usize, what: &str) -> PResult<f64> {
    finite(w, line, what, parse_f64, f64::is_finite)
}

/// Three coordinates as positions relative to the origin `recentre` picks; one too large for
/// an f32 even relative to it is an error like any number that is not finite.
pub(crate) fn relative_point(
    recentre: &mut super::origin::Recentre,
    p: [f64; 3],
    line: usize,
) -> PResult<[f32; 3]> {
    let r = recentre.relative(p);
    if r.iter().all(|c| c.is_finite()) {
        Ok(r)
    } else {
        Err(ParseError::new(
            line,
            format!(
                "a vertex ({} {} {}) is too large for 32-bit floats",
                p[0], p[1], p[2]
            ),
        ))
    }
}

fn finite<T: Copy>(
    w: Option<&[u8]>,
    line: usize,
    what: &str,
    parse: fn(&[u8]) -> Option<T>,
    is_finite: fn(T) -> bool,
) -> PResult<T> {
    let w = w.ok_or_else(|| ParseError::new(line, format!("missing {what}")))?;
    match parse(w) {
        Some(v) if is_finite(v) => Ok(v),
        Some(_) => Err(ParseError::new(
            line,
            format!("{what} is not a finite number ('{}')", shown(w)),
        )),
        None => Err(ParseError::new(
            line,
            format!("expected a number for {what}, found '{}'", shown(w)),
        )),
    }
}
