//! A reader's warnings, typed: what kind of thing was not read as written (which says whether
//! data was lost), the file, the line and how many times, with the sentence printed for it.
//! The command line prints them grouped by kind ([`grouped`]); `-q` keeps those that lose data.

use std::fmt;
use std::path::PathBuf;

/// What a warning is about. The order is the order they are printed in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum WarningKind {
    /// Nodes, shapes, primitives or statements of a kind the reader does not read, skipped.
    SkippedNode,
    /// Faces, facets or lines of a file left out (too few corners, past the last face).
    SkippedFaces,
    /// An attribute (texture coordinates, colours, a field's value, a texture, an extension)
    /// not kept.
    SkippedAttribute,
    /// A material library, or a statement in one, not applied.
    SkippedMaterial,
    /// Something read in full but worth saying (no `endsolid`, an empty solid, a point cloud,
    /// meshes copied through to a glTF output, animations shown at rest).
    Note,
}

impl WarningKind {
    /// True when part of the file is not in the scene: `-q` still prints such warnings.
    pub fn loses_data(self) -> bool {
        self != Self::Note
    }
}

/// One warning of a reader.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// What kind of warning: whether it means data was lost, and how it is grouped.
    pub kind: WarningKind,
    /// The file it is about when known (an included file, a material library); the file
    /// being read otherwise.
    pub file: Option<PathBuf>,
    /// The line of the first occurrence, when the reader knows it.
    pub line: Option<usize>,
    /// How many times it occurred (1 unless the sentence counts them).
    pub count: usize,
    /// The sentence printed for it.
    pub message: String,
}

impl Warning {
    pub(crate) fn new(kind: WarningKind, message: impl Into<String>) -> Self {
        Self {
            kind,
            file: None,
            line: None,
            count: 1,
            message: message.into(),
        }
    }

    /// The same warning, at `line`.
    pub(crate) fn at(mut self, line: usize) -> Self {
        self.line = Some(line);
        self
    }

    /// The same warning, `count` times.
    pub(crate) fn times(mut self, count: usize) -> Self {
        self.count = count;
        self
    }

    /// True when part of the file is not in the scene.
    pub fn loses_data(&self) -> bool {
        self.kind.loses_data()
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// `warnings` grouped by kind (in [`WarningKind`]'s order), in file order within a kind.
pub fn grouped(warnings: &[Warning]) -> Vec<&Warning> {
    let mut out: Vec<&Warning> = warnings.iter().collect();
    out.sort_by_key(|w| w.kind);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grouping_keeps_file_order_within_a_kind() {
        let w = |k, m: &str| Warning::new(k, m);
        let list = [
            w(WarningKind::Note, "n1"),
            w(WarningKind::SkippedAttribute, "a1"),
            w(WarningKind::SkippedNode, "s1"),
            w(WarningKind::SkippedAttribute, "a2"),
        ];
        let order: Vec<&str> = grouped(&list).iter().map(|w| w.message.as_str()).collect();
        assert_eq!(order, ["s1", "a1", "a2", "n1"]);
        assert!(!list[0].loses_data() && list[1].loses_data());
    }
}
