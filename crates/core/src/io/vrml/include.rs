//! Inventor's `File` node: the nodes of another file, named relative to the including
//! file's folder, read in place of the node's children. Cycles and nesting deeper than
//! [`MAX_INCLUDE_DEPTH`] are refused; errors inside the included file name it and the line
//! of the `File` node.

use std::path::Path;
use std::rc::Rc;

use super::lexer::{PResult, ParseError};
use super::parse::{Node, Parser};

/// Deepest chain of files including files; a deeper one is refused as a likely cycle
/// through different names.
pub const MAX_INCLUDE_DEPTH: usize = 16;

impl Parser<'_> {
    /// The top-level nodes of the file a `File` node names.
    pub(super) fn include(&mut self, node: &Node) -> PResult<Vec<Rc<Node>>> {
        let line = node.line_of("name");
        let fail = |message: String| Err(ParseError::new(line, message));
        let Some(name) = node.strings("name").first().filter(|n| !n.is_empty()) else {
            return fail("'File' needs a file name in 'name'".into());
        };
        let folder = self
            .origin
            .as_deref()
            .and_then(Path::parent)
            .unwrap_or(Path::new(""));
        let path = match crate::io::file_limits::resolve_reference(folder, name) {
            Ok(path) => path,
            Err(why) => return fail(format!("'File' name {why}")),
        };
        let canonical = match path.canonicalize() {
            Ok(c) => c,
            Err(e) => return fail(format!("cannot read included file {}: {e}", path.display())),
        };
        if self.including.contains(&canonical) {
            return fail(format!(
                "included file {} includes itself (directly or through other files)",
                path.display()
            ));
        }
        if self.including.len() >= MAX_INCLUDE_DEPTH {
            return fail(format!(
                "files included more than {MAX_INCLUDE_DEPTH} deep at {}",
                path.display()
            ));
        }
        // Only a regular file: a device or a pipe (/dev/zero) could be endless.
        if !canonical.is_file() {
            return fail(format!(
                "included file {} is not a regular file",
                path.display()
            ));
        }
        let bytes = match crate::io::file_limits::read_regular(&canonical) {
            Ok(b) => b,
            Err(e) => return fail(format!("cannot read included file {}: {e}", path.display())),
        };
        let header_end = bytes
            .iter()
            .position(|&b| matches!(b, b'\n' | b'\r'))
            .unwrap_or(bytes.len());
        let header = String::from_utf8_lossy(&bytes[..header_end]);
        let ascii = header.starts_with("#Inventor V2.") || header.starts_with("#VRML V1.0 ascii");
        if !ascii || header.contains("binary") {
            return fail(format!(
                "included file {} is not Open Inventor ASCII or VRML 1.0 (binary Inventor can be converted with ivcat)",
                path.display()
            ));
        }
        let mut sub = Parser::new(&bytes, self.dialect);
        sub.origin = Some(path.clone());
        sub.including = self.including.clone();
        sub.including.push(canonical);
        sub.lenient = self.lenient;
        sub.depth = self.depth;
        let roots = sub.parse_file().map_err(|e| {
            ParseError::new(
                line,
                format!(
                    "in included file {}: line {}: {}",
                    path.display(),
                    e.line,
                    e.message
                ),
            )
        })?;
        self.included_nodes += sub.nodes_parsed();
        self.warnings.extend(sub.warnings.into_iter().map(|mut w| {
            w.message = format!("{}: {}", path.display(), w.message);
            w.file = Some(w.file.take().unwrap_or_else(|| path.to_path_buf()));
            w
        }));
        Ok(roots)
    }
}
