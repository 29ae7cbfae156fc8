//! VRML 1.0, Open Inventor ASCII and VRML 2.0: the byte `lexer`, the node-tree `parse`r
//! shared by both families (`fields`: every field name of the nodes it knows; `include`:
//! Inventor's `File` node), `vrml1` (the VRML 1.0 / Inventor state machine), `vrml2` (the
//! VRML 2.0 tree walk), `primitives` (Sphere, Cone, Cylinder) and `extrusion` (VRML 2.0's
//! Extrusion) tessellated, `bindings` (their index lists and bindings as `Bind`s) and
//! `vrml2_writer` (VRML 2.0 output); `far` builds shapes far from zero relative to the
//! scene's origin. [`read_tree`] runs a parse on a thread with a big stack.

mod bindings;
mod default_texcoords;
mod extrusion;
mod far;
mod fields;
mod include;
mod lexer;
mod parse;
mod primitives;
mod texture_transform;
mod vrml1;
mod vrml2;
mod vrml2_writer;

use crate::io::warning::{Warning, WarningKind};
use std::collections::HashSet;

pub(crate) use parse::Dialect;
pub use vrml2_writer::write_vrml2_to;

use std::path::Path;

use super::{ReadOptions, ReadOutcome, MAX_MODELS, MAX_TRIANGLES};
use crate::io::text::{PResult, ParseError};
use crate::mesh::Scene;

/// Limits on what a file may expand to, and once-per-key warnings.
#[derive(Default)]
pub(crate) struct Budget {
    models: usize,
    triangles: usize,
    copies: usize,
    visits: u64,
    max_visits: u64,
    warned: HashSet<String>,
}

impl Budget {
    pub(crate) fn spend(&mut self, triangles: usize, line: usize) -> PResult<()> {
        self.models += 1;
        self.triangles += triangles;
        if self.models > MAX_MODELS || self.triangles > MAX_TRIANGLES {
            return Err(ParseError::new(
                line,
                format!(
                    "the scene expands to more than {MAX_MODELS} shapes or {MAX_TRIANGLES} triangles (DEF/USE instancing?)"
                ),
            ));
        }
        Ok(())
    }

    /// Counts one node visited by the walk. A USE walks its node again, so a chain of DEFs
    /// each using the one before is walked quadratically often even when it makes few
    /// shapes; the walk is bounded by a multiple of the nodes parsed (design.md#vrml-budget).
    pub(crate) fn visit(&mut self, line: usize) -> PResult<()> {
        self.visits += 1;
        if self.visits > self.max_visits {
            return Err(ParseError::new(
                line,
                format!(
                    "the scene graph is walked more than {} times node by node: USEs of nodes \
                     that themselves USE others multiply the walk (a long DEF/USE chain?)",
                    self.max_visits
                ),
            ));
        }
        Ok(())
    }

    /// Counts one copy made by an `Array` or `MultipleCopy` node: nested copies multiply,
    /// and even copies of nothing take time, so their total is bounded like the models'.
    pub(crate) fn copy(&mut self, line: usize) -> PResult<()> {
        self.copies += 1;
        if self.copies > MAX_MODELS {
            return Err(ParseError::new(
                line,
                format!("the scene makes more than {MAX_MODELS} copies (nested Array or MultipleCopy nodes?)"),
            ));
        }
        Ok(())
    }

    /// A node skipped, said once per `key`.
    pub(crate) fn warn_once(&mut self, warnings: &mut Vec<Warning>, key: &str, message: String) {
        if self.warned.insert(key.to_string()) {
            warnings.push(Warning::new(WarningKind::SkippedNode, message));
        }
    }
}

/// What a scene-graph reader (VRML 1.0/Inventor or VRML 2.0) carries while it walks: the
/// models made so far, the warnings, and the expansion budget; the origin of far shapes,
/// once one is met, and (VRML 2.0) the world transform in f64.
pub(crate) struct Ctx<'w> {
    pub(crate) models: Vec<crate::mesh::Model>,
    pub(crate) warnings: &'w mut Vec<Warning>,
    pub(crate) budget: Budget,
    pub(crate) origin: Option<glam::DVec3>,
    pub(crate) exact: glam::DMat4,
}

/// Node visits allowed per node parsed, and at least (design.md#vrml-budget).
const VISITS_PER_NODE: u64 = 64;
const MIN_VISITS: u64 = 4_000_000;

impl<'w> Ctx<'w> {
    /// A walk of a tree of `nodes` parsed nodes.
    pub(crate) fn new(warnings: &'w mut Vec<Warning>, nodes: usize) -> Self {
        let budget = Budget {
            max_visits: (nodes as u64)
                .saturating_mul(VISITS_PER_NODE)
                .max(MIN_VISITS),
            ..Budget::default()
        };
        Self {
            models: Vec::new(),
            warnings,
            budget,
            origin: None,
            exact: glam::DMat4::IDENTITY,
        }
    }
}

/// Stack for parsing: the node nesting limit (`parse::MAX_DEPTH`) times the deepest
/// recursion per level, with a wide margin, whatever thread the caller runs on.
const PARSE_STACK: usize = 256 << 20;

/// Parses and walks the node tree of `bytes` (read from `path`: `File` nodes are relative to
/// its folder) on a thread with a known, large stack (the recursion is bounded by
/// `parse::MAX_DEPTH`, but callers' threads may have small stacks).
pub(crate) fn read_tree(
    bytes: &[u8],
    path: &Path,
    dialect: Dialect,
    options: ReadOptions,
) -> PResult<ReadOutcome> {
    std::thread::scope(|s| {
        match std::thread::Builder::new()
            .name("scene-parser".into())
            .stack_size(PARSE_STACK)
            .spawn_scoped(s, || parse_tree(bytes, path, dialect, options))
        {
            Ok(handle) => handle
                .join()
                .unwrap_or_else(|_| Err(ParseError::new(1, "internal error: the parser panicked"))),
            Err(_) => parse_tree(bytes, path, dialect, options),
        }
    })
}

fn parse_tree(
    bytes: &[u8],
    path: &Path,
    dialect: Dialect,
    options: ReadOptions,
) -> PResult<ReadOutcome> {
    let mut parser = parse::Parser::new(bytes, dialect);
    parser.lenient = options.lenient;
    parser.origin = Some(path.to_path_buf());
    parser.including = path.canonicalize().into_iter().collect();
    let roots = parser.parse_file()?;
    let mut warnings = std::mem::take(&mut parser.warnings);
    let nodes = parser.nodes_parsed();
    let models = match dialect {
        Dialect::Vrml1 => vrml1::read(&roots, &mut warnings, nodes),
        Dialect::Vrml2 => vrml2::read(&roots, &mut warnings, nodes),
    }?;
    // The tree (at most MAX_DEPTH deep) is dropped here, on the big stack.
    drop(roots);
    Ok(ReadOutcome {
        scene: Scene { models },
        warnings,
        progressive: None,
        material_libraries: Vec::new(),
    })
}
