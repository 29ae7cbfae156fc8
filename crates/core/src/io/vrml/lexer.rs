//! The byte lexer shared by the VRML 1.0 / Open Inventor ASCII and VRML 2.0 parsers.
//!
//! Both families share lexical rules: `#` comments to the end of the line, commas as
//! whitespace, double-quoted strings with backslash escapes, numbers (decimal, exponent,
//! `0x` hexadecimal), words (node, field and DEF names), and the punctuation `{ } [ ] ( ) |`.
//! Every token carries the 1-based line it starts on. Tokens are spans into the source; numbers
//! are parsed from their bytes without allocating.

pub use crate::io::text::{parse_f32, parse_f64, parse_int, PResult, ParseError};

/// What a token is; its text is the source span `start..end`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tok {
    Word,
    Number,
    Str,
    LBrace,
    RBrace,
    LBracket,
    RBracket,
    LParen,
    RParen,
    Pipe,
    Eof,
}

/// One token: kind, byte span in the source and the line it starts on.
#[derive(Debug, Clone, Copy)]
pub struct Token {
    pub kind: Tok,
    pub start: usize,
    pub end: usize,
    pub line: usize,
}

/// A lexer over the whole file, with one token of look-ahead.
pub struct Lexer<'a> {
    src: &'a [u8],
    pos: usize,
    line: usize,
    peeked: Option<Token>,
}

fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | b'\n' | b',' | 0x0b | 0x0c)
}

/// A control byte that is not whitespace (NUL, escape, delete...): never part of a text
/// file's tokens.
fn is_control(b: u8) -> bool {
    (b < 0x20 || b == 0x7f) && !is_space(b)
}

/// True when the byte at `i` ends a line: `\n`, or a `\r` not followed by `\n` (old Mac
/// files end lines with `\r` alone).
fn ends_line(src: &[u8], i: usize) -> bool {
    match src[i] {
        b'\n' => true,
        b'\r' => src.get(i + 1) != Some(&b'\n'),
        _ => false,
    }
}

fn is_special(b: u8) -> bool {
    matches!(
        b,
        b'{' | b'}' | b'[' | b']' | b'(' | b')' | b'|' | b'"' | b'#'
    ) || is_space(b)
}

impl<'a> Lexer<'a> {
    pub fn new(src: &'a [u8]) -> Self {
        Self {
            src,
            pos: 0,
            line: 1,
            peeked: None,
        }
    }

    /// The source bytes of a token.
    pub fn bytes(&self, t: &Token) -> &'a [u8] {
        &self.src[t.start..t.end]
    }

    /// The text of a token (lossy for non-UTF-8 bytes), for names and messages.
    pub fn text(&self, t: &Token) -> String {
        String::from_utf8_lossy(self.bytes(t)).into_owned()
    }

    /// How a token reads in an error message: `'{'`, `'Separator'`, `end of file`.
    pub fn describe(&self, t: &Token) -> String {
        match t.kind {
            Tok::Eof => "end of file".into(),
            Tok::Str => {
                let s = self.text(t);
                let short: String = s.chars().take(40).collect();
                if short.len() < s.len() {
                    format!("string {short}...")
                } else {
                    format!("string {s}")
                }
            }
            _ => {
                let s = self.text(t);
                let short: String = s.chars().take(40).collect();
                format!("'{short}'")
            }
        }
    }

    /// The next token without consuming it.
    pub fn peek(&mut self) -> PResult<Token> {
        if let Some(t) = self.peeked {
            return Ok(t);
        }
        let t = self.scan()?;
        self.peeked = Some(t);
        Ok(t)
    }

    /// Consumes and returns the next token.
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> PResult<Token> {
        if let Some(t) = self.peeked.take() {
            return Ok(t);
        }
        self.scan()
    }

    /// The line of the last position scanned (for end-of-file messages).
    pub fn line(&self) -> usize {
        self.line
    }

    fn scan(&mut self) -> PResult<Token> {
        self.skip_blanks();
        let src = self.src;
        let n = src.len();
        let start = self.pos;
        let line = self.line;
        let tok = |kind, end| Token {
            kind,
            start,
            end,
            line,
        };
        if start >= n {
            return Ok(tok(Tok::Eof, start));
        }
        let b = src[start];
        let single = match b {
            b'{' => Some(Tok::LBrace),
            b'}' => Some(Tok::RBrace),
            b'[' => Some(Tok::LBracket),
            b']' => Some(Tok::RBracket),
            b'(' => Some(Tok::LParen),
            b')' => Some(Tok::RParen),
            b'|' => Some(Tok::Pipe),
            _ => None,
        };
        let (kind, end) = if let Some(kind) = single {
            (kind, start + 1)
        } else if b == b'"' {
            (Tok::Str, self.string_end(start)?)
        } else if let Some(end) = self.number_end(start) {
            (Tok::Number, end)
        } else {
            (Tok::Word, self.word_end(start)?)
        };
        self.pos = end;
        Ok(tok(kind, end))
    }

    /// Moves past whitespace and `#` comments, counting lines.
    #[inline]
    fn skip_blanks(&mut self) {
        let src = self.src;
        let n = src.len();
        loop {
            while self.pos < n && is_space(src[self.pos]) {
                if ends_line(src, self.pos) {
                    self.line += 1;
                }
                self.pos += 1;
            }
            if self.pos < n && src[self.pos] == b'#' {
                while self.pos < n && !matches!(src[self.pos], b'\n' | b'\r') {
                    self.pos += 1;
                }
                continue;
            }
            break;
        }
    }

    /// The end (past the closing quote) of the string opening at `start`; its line breaks
    /// are counted.
    fn string_end(&mut self, start: usize) -> PResult<usize> {
        let src = self.src;
        let line = self.line;
        let mut p = start + 1;
        loop {
            if p >= src.len() {
                return Err(ParseError::new(
                    line,
                    "unterminated string: expected a closing '\"' before the end of the file",
                ));
            }
            match src[p] {
                b'"' => return Ok(p + 1),
                b'\\' => p += 2,
                _ => {
                    if ends_line(src, p) {
                        self.line += 1;
                    }
                    p += 1
                }
            }
        }
    }

    /// The end of the number starting at `start`, if one does (decimal or `0x` hex).
    #[inline]
    fn number_end(&self, start: usize) -> Option<usize> {
        let src = self.src;
        let n = src.len();
        let b = src[start];
        let next = |i: usize| src.get(i).copied().unwrap_or(0);
        let number_start = b.is_ascii_digit()
            || (matches!(b, b'+' | b'-' | b'.') && next(start + 1).is_ascii_digit())
            || (matches!(b, b'+' | b'-')
                && next(start + 1) == b'.'
                && next(start + 2).is_ascii_digit());
        if !number_start {
            return None;
        }
        let mut p = start;
        if b == b'0' && matches!(next(start + 1), b'x' | b'X') {
            p += 2;
            while p < n && src[p].is_ascii_hexdigit() {
                p += 1;
            }
        } else {
            while p < n && matches!(src[p], b'0'..=b'9' | b'.' | b'e' | b'E' | b'+' | b'-') {
                p += 1;
            }
        }
        Some(p)
    }

    /// The end of the word starting at `start`; a control byte in it is an error.
    #[inline]
    fn word_end(&self, start: usize) -> PResult<usize> {
        let src = self.src;
        let mut p = start;
        while p < src.len() && !is_special(src[p]) {
            if is_control(src[p]) {
                return Err(ParseError::new(
                    self.line,
                    format!(
                        "control byte 0x{:02x} outside a string: the file is damaged or is not text",
                        src[p]
                    ),
                ));
            }
            p += 1;
        }
        Ok(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<(Tok, String, usize)> {
        let mut l = Lexer::new(src.as_bytes());
        let mut out = Vec::new();
        loop {
            let t = l.next().unwrap();
            if t.kind == Tok::Eof {
                return out;
            }
            out.push((t.kind, l.text(&t), t.line));
        }
    }

    #[test]
    fn tokens_lines_and_commas() {
        let k = kinds(
            "#VRML V1.0 ascii\nSeparator {\n point [ 1 -2.5e1, .5 ] # c\n DEF a+0 \"x\\\"y\" }",
        );
        let want = [
            (Tok::Word, "Separator", 2),
            (Tok::LBrace, "{", 2),
            (Tok::Word, "point", 3),
            (Tok::LBracket, "[", 3),
            (Tok::Number, "1", 3),
            (Tok::Number, "-2.5e1", 3),
            (Tok::Number, ".5", 3),
            (Tok::RBracket, "]", 3),
            (Tok::Word, "DEF", 4),
            (Tok::Word, "a+0", 4),
            (Tok::Str, "\"x\\\"y\"", 4),
            (Tok::RBrace, "}", 4),
        ];
        assert_eq!(k.len(), want.len());
        for (a, b) in k.iter().zip(want) {
            assert_eq!((a.0, a.1.as_str(), a.2), b);
        }
    }

    #[test]
    fn carriage_returns_alone_end_lines_and_comments() {
        let k = kinds("#Inventor V2.1 ascii\rSeparator {\r\n Cube { }\r}\r");
        let lines: Vec<_> = k.iter().map(|t| (t.1.as_str(), t.2)).collect();
        assert_eq!(
            lines,
            [
                ("Separator", 2),
                ("{", 2),
                ("Cube", 3),
                ("{", 3),
                ("}", 3),
                ("}", 4)
            ]
        );
    }

    #[test]
    fn control_bytes_outside_strings_are_errors() {
        let mut l = Lexer::new(b"Separator {\n Cu\0be { } }");
        l.next().unwrap();
        l.next().unwrap();
        let e = l.next().unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.message.contains("control byte 0x00"), "{}", e.message);
        let mut l = Lexer::new(b"Info { string \"a\0b\" }");
        for _ in 0..4 {
            l.next().unwrap();
        }
    }

    #[test]
    fn numbers() {
        assert_eq!(parse_int(b"0xff0000ff"), Some(0xff0000ff));
        assert_eq!(parse_int(b"-1"), Some(-1));
        assert_eq!(parse_int(b"1.5"), None);
        assert_eq!(parse_f32(b"-2.5e1"), Some(-25.0));
        assert_eq!(parse_f32(b"1.2.3"), None);
    }

    #[test]
    fn unterminated_string_is_an_error() {
        let mut l = Lexer::new(b"Info {\n string \"abc");
        l.next().unwrap();
        l.next().unwrap();
        l.next().unwrap();
        let e = l.next().unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.message.contains("unterminated string"));
    }
}
