//! The node-tree parser shared by VRML 1.0 / Open Inventor and VRML 2.0.
//!
//! It turns tokens into a tree of [`Node`]s with typed field values for the fields the
//! readers use (see [`field_kind`]); every other field is skipped by structure. Node kinds the
//! readers do not know are skipped by structure (iteratively, so depth cannot overflow the
//! stack) and give one warning per kind. DEF/USE share nodes through `Rc`; a USE of a name
//! not yet defined is an error. Nesting of known nodes is limited to [`MAX_DEPTH`].
//! Semantics (state, transforms, shapes) live in `vrml1.rs` and `vrml2.rs`.

use crate::io::warning::{Warning, WarningKind};
use std::collections::{HashMap, HashSet};
use std::path::PathBuf;
use std::rc::Rc;

use super::fields;
pub use super::fields::Dialect;
use super::lexer::{parse_f32, parse_f64, parse_int, Lexer, PResult, ParseError, Tok, Token};

/// Deepest nesting of nodes accepted; deeper files are rejected rather than overflowing.
pub const MAX_DEPTH: usize = 256;

/// The kind of the node standing for a `USE name` reference: its `line` is the USE's, its
/// `def` the name, its one child the node `DEF name` defined. Readers walk through it
/// ([`Node::target`]) and name both lines in errors met inside ([`ParseError::used_at`]).
pub const USE_KIND: &str = "USE";

/// `e`, met inside the node `DEF name` (line `def_line`) where `USE name` at `use_line`
/// placed it: reported at the USE, naming the DEF and the line inside.
pub fn used_at(e: ParseError, use_line: usize, name: &str, def_line: usize) -> ParseError {
    ParseError::new(
        use_line,
        format!(
            "in 'USE {name}' (DEF {name} at line {def_line}): line {}: {}",
            e.line, e.message
        ),
    )
}

/// A parsed field value.
#[derive(Debug, Clone)]
pub enum Value {
    Floats(Vec<f32>),
    /// A coordinate field with a far value (see `io::origin`): its numbers as f32 (what
    /// [`Node::floats`] gives) and as f64.
    Far(Vec<f32>, Vec<f64>),
    Ints(Vec<i32>),
    Bool(bool),
    Word(String),
    Strings(Vec<String>),
    Node(Option<Rc<Node>>),
    Nodes(Vec<Rc<Node>>),
}

/// One field of a node: name, the line its value starts on, the value.
#[derive(Debug, Clone)]
pub struct Field {
    pub name: String,
    pub line: usize,
    pub value: Value,
}

/// One node of the scene graph.
#[derive(Debug, Clone)]
pub struct Node {
    pub kind: String,
    /// The DEF name, if the node was defined with one.
    pub def: Option<String>,
    pub line: usize,
    pub fields: Vec<Field>,
    /// VRML 1.0 / Inventor inline children, in file order.
    pub children: Vec<Rc<Self>>,
    /// True when the node was skipped by structure (its fields and children are empty).
    pub skipped: bool,
}

impl Node {
    pub fn field(&self, name: &str) -> Option<&Field> {
        self.fields.iter().find(|f| f.name == name)
    }
    pub fn floats(&self, name: &str) -> Option<&[f32]> {
        match &self.field(name)?.value {
            Value::Floats(v) | Value::Far(v, _) => Some(v),
            _ => None,
        }
    }
    /// A coordinate field's numbers in f64, when one of them is far from zero.
    pub fn far(&self, name: &str) -> Option<&[f64]> {
        match &self.field(name)?.value {
            Value::Far(_, v) => Some(v),
            _ => None,
        }
    }
    /// A field's numbers in f64: as read when far, else its f32 values widened.
    pub fn exact(&self, name: &str) -> Option<Vec<f64>> {
        match &self.field(name)?.value {
            Value::Far(_, v) => Some(v.clone()),
            Value::Floats(v) => Some(v.iter().map(|&x| f64::from(x)).collect()),
            _ => None,
        }
    }
    pub fn ints(&self, name: &str) -> Option<&[i32]> {
        match &self.field(name)?.value {
            Value::Ints(v) => Some(v),
            _ => None,
        }
    }
    pub fn int(&self, name: &str) -> Option<i32> {
        self.ints(name).and_then(|v| v.first().copied())
    }
    pub fn float(&self, name: &str) -> Option<f32> {
        self.floats(name).and_then(|v| v.first().copied())
    }
    pub fn boolean(&self, name: &str) -> Option<bool> {
        match &self.field(name)?.value {
            Value::Bool(b) => Some(*b),
            _ => None,
        }
    }
    pub fn word(&self, name: &str) -> Option<&str> {
        match &self.field(name)?.value {
            Value::Word(w) => Some(w),
            _ => None,
        }
    }
    /// The strings of an SFString / MFString field (quotes removed, escapes resolved).
    pub fn strings(&self, name: &str) -> &[String] {
        match self.field(name).map(|f| &f.value) {
            Some(Value::Strings(v)) => v,
            _ => &[],
        }
    }
    /// An SFNode field's node, looking through a `USE` (see [`Node::target`]).
    pub fn node(&self, name: &str) -> Option<&Rc<Self>> {
        self.node_or_use(name).map(|n| n.target())
    }
    /// An SFNode field's node as written: a `USE` reference stays one.
    pub fn node_or_use(&self, name: &str) -> Option<&Rc<Self>> {
        match &self.field(name)?.value {
            Value::Node(n) => n.as_ref(),
            Value::Nodes(v) => v.first(),
            _ => None,
        }
    }
    /// For a `USE name` reference (kind [`USE_KIND`]), the node `DEF name` defined; any
    /// other node itself.
    pub fn target(self: &Rc<Self>) -> &Rc<Self> {
        match self.children.first() {
            Some(t) if self.kind == USE_KIND => t,
            _ => self,
        }
    }
    pub fn nodes(&self, name: &str) -> &[Rc<Self>] {
        match self.field(name).map(|f| &f.value) {
            Some(Value::Nodes(v)) => v,
            Some(Value::Node(Some(n))) => std::slice::from_ref(n),
            _ => &[],
        }
    }
    /// The line of a field's value, or the node's line when the field is absent.
    pub fn line_of(&self, name: &str) -> usize {
        self.field(name).map_or(self.line, |f| f.line)
    }
}

/// How a field's value is read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldKind {
    /// Any number of floats, bracketed or not (SFFloat, SFVec3f, MFVec3f, SFRotation...).
    Floats,
    /// Floats that place geometry (points, translations, matrices), also kept in f64 when
    /// one of them is far from zero.
    Coords,
    /// Any number of integers, bracketed or not (MFInt32 with -1 separators, SFInt32).
    Ints,
    Bool,
    /// An enum name or an Inventor bit mask `( A | B )`.
    Word,
    /// SFString or MFString: `"text"` or `[ "a", "b" ]`.
    Strings,
    /// SFNode: a node, `USE name` or `NULL`.
    Node,
    /// MFNode: `[ nodes ]` or a single node.
    Nodes,
}

/// The typed fields the readers use; `None` means skip by structure.
pub fn field_kind(dialect: Dialect, node: &str, field: &str) -> Option<FieldKind> {
    match dialect {
        Dialect::Vrml1 => vrml1_field_kind(node, field),
        Dialect::Vrml2 => vrml2_field_kind(node, field),
    }
}

/// [`field_kind`] for VRML 1.0 and Open Inventor.
fn vrml1_field_kind(node: &str, field: &str) -> Option<FieldKind> {
    use FieldKind::*;
    Some(match (node, field) {
        ("Coordinate3", "point") => Coords,
        ("Normal", "vector") => Floats,
        ("Material", "diffuseColor") => Floats,
        ("BaseColor", "rgb") => Floats,
        ("MaterialBinding" | "NormalBinding" | "TextureCoordinateBinding", "value") => Word,
        ("ShapeHints", "vertexOrdering" | "shapeType" | "faceType" | "hints") => Word,
        ("ShapeHints", "creaseAngle") => Floats,
        ("Transform", "translation" | "center") => Coords,
        ("Transform", "rotation" | "scaleFactor" | "scaleOrientation") => Floats,
        ("Translation", "translation") => Coords,
        ("Rotation" | "Rotor" | "Pendulum", "rotation") => Floats,
        ("Scale", "scaleFactor") => Floats,
        ("RotationXYZ", "axis") => Word,
        ("RotationXYZ", "angle") => Floats,
        ("MatrixTransform", "matrix") => Coords,
        ("Switch" | "Blinker", "whichChild") => Ints,
        (
            "IndexedFaceSet" | "IndexedTriangleStripSet" | "IndexedTriangleMesh",
            "coordIndex" | "materialIndex" | "normalIndex" | "textureCoordIndex",
        ) => Ints,
        ("TextureCoordinate2", "point") => Floats,
        ("FaceSet" | "TriangleStripSet", "startIndex" | "numVertices") => Ints,
        ("QuadMesh", "startIndex" | "verticesPerColumn" | "verticesPerRow") => Ints,
        (
            "IndexedFaceSet"
            | "IndexedTriangleStripSet"
            | "IndexedTriangleMesh"
            | "FaceSet"
            | "TriangleStripSet"
            | "QuadMesh",
            "vertexProperty",
        ) => Node,
        ("VertexProperty", "vertex") => Coords,
        ("VertexProperty", "normal" | "texCoord") => Floats,
        ("VertexProperty", "orderedRGBA") => Ints,
        ("VertexProperty", "materialBinding" | "normalBinding") => Word,
        ("Cube", "width" | "height" | "depth") => Floats,
        ("Sphere", "radius") => Floats,
        ("Cone", "bottomRadius" | "height") => Floats,
        ("Cylinder", "radius" | "height") => Floats,
        ("Cone" | "Cylinder", "parts") => Word,
        ("Complexity", "value") => Floats,
        ("Complexity", "type") => Word,
        ("File", "name") => Strings,
        ("Array", "numElements1" | "numElements2" | "numElements3") => Ints,
        ("Array", "separation1" | "separation2" | "separation3") => Floats,
        ("Array", "origin") => Word,
        ("MultipleCopy", "matrix") => Coords,
        ("Texture2", "filename") => Strings,
        ("Texture2", "wrapS" | "wrapT") => Word,
        ("Texture2Transform", "translation" | "rotation" | "scaleFactor" | "center") => Floats,
        ("ResetTransform", "whatToReset") => Word,
        _ => return None,
    })
}

/// [`field_kind`] for VRML 2.0.
fn vrml2_field_kind(node: &str, field: &str) -> Option<FieldKind> {
    use FieldKind::*;
    Some(match (node, field) {
        ("Transform", "translation" | "center") => Coords,
        ("Transform", "rotation" | "scale" | "scaleOrientation") => Floats,
        ("Transform" | "Group" | "Collision" | "Anchor" | "Billboard", "children") => Nodes,
        ("Switch", "choice") => Nodes,
        ("Switch", "whichChoice") => Ints,
        ("LOD", "level") => Nodes,
        ("Shape", "appearance" | "geometry") => Node,
        ("Appearance", "material" | "texture" | "textureTransform") => Node,
        ("TextureTransform", "center" | "rotation" | "scale" | "translation") => Floats,
        ("ImageTexture", "url") => Strings,
        ("ImageTexture", "repeatS" | "repeatT") => Bool,
        ("Material", "diffuseColor") => Floats,
        ("IndexedFaceSet", "coord" | "color" | "normal" | "texCoord") => Node,
        ("IndexedFaceSet", "coordIndex" | "colorIndex" | "normalIndex" | "texCoordIndex") => Ints,
        ("IndexedFaceSet", "colorPerVertex" | "normalPerVertex" | "ccw" | "solid" | "convex") => {
            Bool
        }
        ("IndexedFaceSet", "creaseAngle") => Floats,
        ("Coordinate", "point") => Coords,
        ("Color", "color") => Floats,
        ("Normal", "vector") => Floats,
        ("TextureCoordinate", "point") => Floats,
        ("Box", "size") => Floats,
        ("Sphere", "radius") => Floats,
        ("Cone", "bottomRadius" | "height") => Floats,
        ("Cone", "side" | "bottom") => Bool,
        ("Cylinder", "radius" | "height") => Floats,
        ("Cylinder", "side" | "top" | "bottom") => Bool,
        ("Extrusion", "spine") => Coords,
        ("Extrusion", "crossSection" | "orientation" | "scale") => Floats,
        ("Extrusion", "creaseAngle") => Floats,
        ("Extrusion", "beginCap" | "endCap" | "ccw" | "convex" | "solid") => Bool,
        ("ElevationGrid", "color" | "normal" | "texCoord") => Node,
        ("ElevationGrid", "height") => Coords,
        ("ElevationGrid", "xSpacing" | "zSpacing" | "creaseAngle") => Floats,
        ("ElevationGrid", "xDimension" | "zDimension") => Ints,
        ("ElevationGrid", "ccw" | "solid" | "colorPerVertex" | "normalPerVertex") => Bool,
        _ => return None,
    })
}

/// Inventor node kits (and the draggers and manipulators, which are kits): their parts are
/// fields holding nodes, walked by `vrml1` in the kit's order. `NodeKitListPart` holds a
/// kit's `childList`.
pub fn is_kit(kind: &str) -> bool {
    kind.ends_with("Kit")
        || kind.ends_with("Dragger")
        || kind.ends_with("Manip")
        || kind == "NodeKitListPart"
}

/// VRML 1.0 / Open Inventor node kinds whose fields are parsed.
const VRML1_KNOWN: [&str; 45] = [
    "Separator",
    "TransformSeparator",
    "Group",
    "Switch",
    "Blinker",
    "LOD",
    "LevelOfDetail",
    "Selection",
    "Annotation",
    "WWWAnchor",
    "Array",
    "MultipleCopy",
    "Transform",
    "MatrixTransform",
    "Translation",
    "Rotation",
    "Rotor",
    "Pendulum",
    "Scale",
    "RotationXYZ",
    "ResetTransform",
    "Coordinate3",
    "Normal",
    "TextureCoordinate2",
    "Texture2",
    "Texture2Transform",
    "Material",
    "BaseColor",
    "MaterialBinding",
    "NormalBinding",
    "TextureCoordinateBinding",
    "ShapeHints",
    "IndexedFaceSet",
    "IndexedTriangleStripSet",
    "FaceSet",
    "TriangleStripSet",
    "QuadMesh",
    "VertexProperty",
    "Cube",
    "Sphere",
    "Cone",
    "Cylinder",
    "Complexity",
    "IndexedTriangleMesh",
    "File",
];

/// VRML 2.0 node kinds whose fields are parsed.
const VRML2_KNOWN: [&str; 23] = [
    "Transform",
    "Group",
    "Collision",
    "Anchor",
    "Billboard",
    "Switch",
    "LOD",
    "Shape",
    "Appearance",
    "Material",
    "IndexedFaceSet",
    "Coordinate",
    "Color",
    "Normal",
    "TextureCoordinate",
    "ImageTexture",
    "TextureTransform",
    "Box",
    "Sphere",
    "Cone",
    "Cylinder",
    "ElevationGrid",
    "Extrusion",
];

/// Node kinds whose fields are parsed (the rest are skipped by structure).
fn is_known(dialect: Dialect, kind: &str) -> bool {
    match dialect {
        Dialect::Vrml1 => is_kit(kind) || VRML1_KNOWN.contains(&kind),
        Dialect::Vrml2 => VRML2_KNOWN.contains(&kind),
    }
}

/// Node kinds that are skipped without a warning: they carry nothing a mesh needs.
fn is_ignorable(dialect: Dialect, kind: &str) -> bool {
    match dialect {
        Dialect::Vrml1 => matches!(
            kind,
            "Info"
                | "Label"
                | "PerspectiveCamera"
                | "OrthographicCamera"
                | "DirectionalLight"
                | "PointLight"
                | "SpotLight"
                | "ComplexityEnvironment"
                | "Environment"
                | "DrawStyle"
                | "LightModel"
                | "TextureCoordinatePlane"
                | "TextureCoordinateDefault"
                | "FontStyle"
                | "Font"
                | "PickStyle"
                | "EventCallback"
                | "Callback"
                | "IndexedLineSet"
                | "LineSet"
                | "PointSet"
                | "ProfileCoordinate2"
                | "LinearProfile"
                | "NurbsProfile"
        ),
        Dialect::Vrml2 => matches!(
            kind,
            "WorldInfo"
                | "Viewpoint"
                | "NavigationInfo"
                | "Background"
                | "Fog"
                | "DirectionalLight"
                | "PointLight"
                | "SpotLight"
                | "TimeSensor"
                | "TouchSensor"
                | "ProximitySensor"
                | "VisibilitySensor"
                | "PlaneSensor"
                | "SphereSensor"
                | "CylinderSensor"
                | "PositionInterpolator"
                | "OrientationInterpolator"
                | "ColorInterpolator"
                | "ScalarInterpolator"
                | "CoordinateInterpolator"
                | "NormalInterpolator"
                | "Script"
                | "Sound"
                | "AudioClip"
                | "IndexedLineSet"
                | "PointSet"
                | "FontStyle"
        ),
    }
}

/// Inventor writes unnamed shared nodes as `DEF +0 ...`: names may look like numbers.
fn is_name(t: &Token) -> bool {
    matches!(t.kind, Tok::Word | Tok::Number)
}

/// The parser: lexer, dialect, DEF table, nesting depth and warnings.
pub struct Parser<'a> {
    lex: Lexer<'a>,
    pub(super) dialect: Dialect,
    defs: HashMap<String, Rc<Node>>,
    pub(super) depth: usize,
    /// The file being parsed (its folder is where `File` nodes' names start), if any.
    pub origin: Option<PathBuf>,
    /// The files that include this one, outermost first, to refuse cycles (see `include`).
    pub including: Vec<PathBuf>,
    warned: HashSet<String>,
    pub(super) warnings: Vec<Warning>,
    /// Unknown fields of known nodes are warnings, not errors (`--lenient`).
    pub lenient: bool,
    /// Node kinds skipped as unknown, in order of first appearance: (kind, first line, count).
    unknown: Vec<(String, usize, usize)>,
    unknown_at: HashMap<String, usize>,
    /// Nodes parsed whose kind the reader knows or knowingly ignores.
    recognised: usize,
    /// Nodes parsed from the files that `File` nodes include.
    pub(super) included_nodes: usize,
}

impl<'a> Parser<'a> {
    /// Nodes parsed so far, known or skipped as unknown, included files' too.
    pub fn nodes_parsed(&self) -> usize {
        self.recognised + self.included_nodes + self.unknown.iter().map(|u| u.2).sum::<usize>()
    }

    pub fn new(src: &'a [u8], dialect: Dialect) -> Self {
        Self {
            lex: Lexer::new(src),
            dialect,
            defs: HashMap::new(),
            depth: 0,
            origin: None,
            including: Vec::new(),
            warned: HashSet::new(),
            warnings: Vec::new(),
            lenient: false,
            unknown: Vec::new(),
            unknown_at: HashMap::new(),
            recognised: 0,
            included_nodes: 0,
        }
    }

    fn warn_once(&mut self, kind: WarningKind, line: usize, key: &str, message: String) {
        if self.warned.insert(key.to_string()) {
            self.warnings.push(Warning::new(kind, message).at(line));
        }
    }

    fn unexpected(&self, t: &Token, expected: &str) -> ParseError {
        ParseError::new(
            t.line,
            format!("expected {expected}, found {}", self.lex.describe(t)),
        )
    }

    fn is_word(&self, t: &Token, w: &[u8]) -> bool {
        t.kind == Tok::Word && self.lex.bytes(t) == w
    }

    /// Counts a node of a kind the reader does not know (skipped with its children).
    fn count_unknown(&mut self, kind: &str, line: usize) {
        match self.unknown_at.get(kind) {
            Some(&i) => self.unknown[i].2 += 1,
            None => {
                self.unknown_at.insert(kind.to_string(), self.unknown.len());
                self.unknown.push((kind.to_string(), line, 1));
            }
        }
    }

    /// One warning per unknown node kind, with how many were skipped; an error when no node
    /// of the file was one the declared format has (a wrong header over another body).
    fn finish_unknown(&mut self) -> PResult<()> {
        if let (0, Some((kind, line, _))) = (self.recognised, self.unknown.first()) {
            let format = match self.dialect {
                Dialect::Vrml1 => "VRML 1.0 / Open Inventor",
                Dialect::Vrml2 => "VRML 2.0",
            };
            return Err(ParseError::new(
                *line,
                format!(
                    "no node of this file is a {format} node (the first is '{kind}'): does the header name the file's format?"
                ),
            ));
        }
        for (kind, line, count) in std::mem::take(&mut self.unknown) {
            let (noun, why) = match kind.as_str() {
                "Inline" | "WWWInline" => ("node(s)", ": inlined files are not read"),
                "Text2" | "Text3" | "AsciiText" | "Text" => {
                    ("shape(s)", ": text is not tessellated")
                }
                k if k.contains("Nurbs") => ("shape(s)", ": NURBS are not tessellated"),
                _ => ("unsupported node(s)", ""),
            };
            self.warnings.push(
                Warning::new(
                    WarningKind::SkippedNode,
                    format!("{count} '{kind}' {noun} skipped, the first at line {line}{why}"),
                )
                .at(line)
                .times(count),
            );
        }
        Ok(())
    }

    /// Parses the whole file: a sequence of top-level nodes (and VRML 2.0 statements).
    pub fn parse_file(&mut self) -> PResult<Vec<Rc<Node>>> {
        let mut out = Vec::new();
        loop {
            let t = self.lex.peek()?;
            match t.kind {
                Tok::Eof => {
                    self.finish_unknown()?;
                    return Ok(out);
                }
                Tok::Word => {
                    if let Some(n) = self.parse_statement()? {
                        out.push(n);
                    }
                }
                _ => {
                    self.lex.next()?;
                    return Err(self.unexpected(&t, "a node name"));
                }
            }
        }
    }

    /// A node, `DEF name node`, `USE name`, or (VRML 2.0) PROTO/EXTERNPROTO/ROUTE, which are
    /// skipped (returning `None`).
    fn parse_statement(&mut self) -> PResult<Option<Rc<Node>>> {
        let t = self.lex.next()?;
        if t.kind != Tok::Word {
            return Err(self.unexpected(&t, "a node name"));
        }
        let word = self.lex.bytes(&t);
        match word {
            b"DEF" => self.parse_def().map(Some),
            b"USE" => self.parse_use().map(Some),
            b"PROTO" | b"EXTERNPROTO" if self.dialect == Dialect::Vrml2 => self.skip_proto(t),
            b"ROUTE" if self.dialect == Dialect::Vrml2 => self.skip_route(t),
            _ => Ok(Some(self.parse_node_body(t, None)?)),
        }
    }

    /// `DEF name Node { … }`, after `DEF`: the node, remembered by its name.
    fn parse_def(&mut self) -> PResult<Rc<Node>> {
        let name_tok = self.lex.next()?;
        if !is_name(&name_tok) {
            return Err(self.unexpected(&name_tok, "a name after 'DEF'"));
        }
        let name = self.lex.text(&name_tok);
        let kind_tok = self.lex.next()?;
        if kind_tok.kind != Tok::Word {
            return Err(self.unexpected(&kind_tok, &format!("a node name after 'DEF {name}'")));
        }
        let node = self.parse_node_body(kind_tok, Some(name.clone()))?;
        self.defs.insert(name, node.clone());
        Ok(node)
    }

    /// `USE name`, after `USE`: a node standing for the DEF's.
    fn parse_use(&mut self) -> PResult<Rc<Node>> {
        let name_tok = self.lex.next()?;
        if !is_name(&name_tok) {
            return Err(self.unexpected(&name_tok, "a name after 'USE'"));
        }
        let name = self.lex.text(&name_tok);
        match self.defs.get(&name) {
            Some(n) => Ok(Rc::new(Node {
                kind: USE_KIND.into(),
                def: Some(name),
                line: name_tok.line,
                fields: Vec::new(),
                children: vec![n.clone()],
                skipped: n.skipped,
            })),
            None => Err(ParseError::new(
                name_tok.line,
                format!("USE of undefined name '{name}' (no DEF {name} before it)"),
            )),
        }
    }

    /// `PROTO` / `EXTERNPROTO` (token `t`): skipped, with a warning once.
    fn skip_proto(&mut self, t: Token) -> PResult<Option<Rc<Node>>> {
        let what = self.lex.text(&t);
        self.warn_once(
            WarningKind::SkippedNode,
            t.line,
            &what,
            format!(
                "line {}: {what} declarations are not supported; skipped",
                t.line
            ),
        );
        let name_tok = self.lex.next()?;
        if name_tok.kind != Tok::Word {
            return Err(self.unexpected(&name_tok, &format!("a name after '{what}'")));
        }
        let open = self.lex.next()?;
        if open.kind != Tok::LBracket {
            return Err(self.unexpected(&open, "'[' to start the interface"));
        }
        self.skip_balanced(open)?;
        if what == "PROTO" {
            let body = self.lex.next()?;
            if body.kind != Tok::LBrace {
                return Err(self.unexpected(&body, "'{' to start the PROTO body"));
            }
            self.skip_balanced(body)?;
        } else {
            self.skip_value()?;
        }
        // A later instance of the prototype is an unknown node, skipped by structure.
        Ok(None)
    }

    /// `ROUTE a TO b` (token `t`): skipped, with a warning once.
    fn skip_route(&mut self, t: Token) -> PResult<Option<Rc<Node>>> {
        self.warn_once(
            WarningKind::SkippedNode,
            t.line,
            "ROUTE",
            format!("line {}: ROUTE statements are ignored", t.line),
        );
        for expected in ["a source after 'ROUTE'", "'TO'", "a destination after 'TO'"] {
            let w = self.lex.next()?;
            if w.kind != Tok::Word {
                return Err(self.unexpected(&w, expected));
            }
        }
        Ok(None)
    }

    /// Parses `{ ... }` after a node's kind name.
    fn parse_node_body(&mut self, kind_tok: Token, def: Option<String>) -> PResult<Rc<Node>> {
        let kind = self.lex.text(&kind_tok);
        let open = self.lex.next()?;
        if open.kind != Tok::LBrace {
            return Err(self.unexpected(&open, &format!("'{{' after '{kind}'")));
        }
        if !is_known(self.dialect, &kind) {
            return self.skip_node(kind, def, kind_tok.line, open);
        }
        self.recognised += 1;
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(ParseError::new(
                kind_tok.line,
                format!("nodes nested deeper than {MAX_DEPTH} levels"),
            ));
        }
        let mut node = Node {
            kind,
            def,
            line: kind_tok.line,
            fields: Vec::new(),
            children: Vec::new(),
            skipped: false,
        };
        self.parse_members(&mut node)?;
        self.depth -= 1;
        if node.kind == "File" {
            node.children = self.include(&node)?;
        }
        Ok(Rc::new(node))
    }

    /// A node of a kind whose fields are not parsed, after its `{` (`open`): skipped by
    /// structure, counted as unknown unless it is one that carries nothing a mesh needs.
    fn skip_node(
        &mut self,
        kind: String,
        def: Option<String>,
        line: usize,
        open: Token,
    ) -> PResult<Rc<Node>> {
        if is_ignorable(self.dialect, &kind) {
            self.recognised += 1;
        } else {
            self.count_unknown(&kind, line);
        }
        self.skip_balanced(open)?;
        Ok(Rc::new(Node {
            kind,
            def,
            line,
            fields: Vec::new(),
            children: Vec::new(),
            skipped: true,
        }))
    }

    /// A known node's fields and children, up to its closing `}`.
    fn parse_members(&mut self, node: &mut Node) -> PResult<()> {
        loop {
            let t = self.lex.peek()?;
            match t.kind {
                Tok::RBrace => {
                    self.lex.next()?;
                    return Ok(());
                }
                Tok::Eof => {
                    return Err(ParseError::new(
                        self.lex.line(),
                        format!(
                            "unexpected end of file: expected '}}' to close '{}' opened at line {}",
                            node.kind, node.line
                        ),
                    ))
                }
                Tok::Word => self.parse_member(node, t)?,
                _ => {
                    self.lex.next()?;
                    return Err(
                        self.unexpected(&t, &format!("a field name or '}}' in '{}'", node.kind))
                    );
                }
            }
        }
    }

    /// One member starting with the word `t` (peeked): a field, a VRML 1.0 child node
    /// (plain, DEF or USE), or a VRML 2.0 statement inside a node.
    fn parse_member(&mut self, node: &mut Node, t: Token) -> PResult<()> {
        let v1 = self.dialect == Dialect::Vrml1;
        if v1 && (self.is_word(&t, b"DEF") || self.is_word(&t, b"USE")) {
            if let Some(c) = self.parse_statement()? {
                node.children.push(c);
            }
            return Ok(());
        }
        if !v1
            && (self.is_word(&t, b"ROUTE")
                || self.is_word(&t, b"PROTO")
                || self.is_word(&t, b"EXTERNPROTO"))
        {
            self.parse_statement()?;
            return Ok(());
        }
        self.lex.next()?;
        if self.is_word(&t, b"~") {
            return Ok(());
        }
        if v1 && self.lex.peek()?.kind == Tok::LBrace {
            let child = self.parse_node_body(t, None)?;
            node.children.push(child);
            return Ok(());
        }
        self.parse_field(node, t)
    }

    /// Parses the value of field `name_tok` (already consumed) into `node`.
    fn parse_field(&mut self, node: &mut Node, name_tok: Token) -> PResult<()> {
        let name = self.lex.text(&name_tok);
        let Some(kind) = field_kind(self.dialect, &node.kind, &name) else {
            return self.skip_untyped_field(node, &name_tok, name);
        };
        let first = self.lex.peek()?;
        if self.is_word(&first, b"~") {
            // Inventor writes a field marked ignored without a value as `name ~`.
            self.lex.next()?;
            node.fields.retain(|f| f.name != name);
            return Ok(());
        }
        let line = first.line;
        let value = match kind {
            FieldKind::Floats => {
                Value::Floats(self.parse_numbers(&name, "a number", Self::float_of)?)
            }
            FieldKind::Coords => {
                let both = self.parse_numbers(&name, "a number", Self::coordinate_of)?;
                let floats = both.iter().map(|&(f, _)| f).collect();
                if both.iter().any(|&(_, d)| d.abs() >= crate::io::origin::FAR) {
                    Value::Far(floats, both.into_iter().map(|(_, d)| d).collect())
                } else {
                    Value::Floats(floats)
                }
            }
            FieldKind::Ints => {
                Value::Ints(self.parse_numbers(&name, "an integer", Self::int_of)?)
            }
            FieldKind::Bool => self.parse_bool(&name)?,
            FieldKind::Word => Value::Word(self.parse_word(&name)?),
            FieldKind::Strings => Value::Strings(self.parse_strings(&name)?),
            FieldKind::Node => self.parse_node_value(&name)?,
            FieldKind::Nodes => self.parse_nodes_value(&name)?,
        };
        node.fields.retain(|f| f.name != name);
        // Inventor marks ignored fields with a trailing `~`: the value does not apply.
        let t = self.lex.peek()?;
        if self.is_word(&t, b"~") {
            self.lex.next()?;
            return Ok(());
        }
        node.fields.push(Field { name, line, value });
        Ok(())
    }

    /// A field the readers do not use (`name`, token `name_tok`): a kit's part is parsed,
    /// anything else is checked against the node's field list and skipped by structure.
    fn skip_untyped_field(
        &mut self,
        node: &mut Node,
        name_tok: &Token,
        name: String,
    ) -> PResult<()> {
        if is_kit(&node.kind) {
            return self.parse_kit_field(node, name);
        }
        if !fields::is_field_of(self.dialect, &node.kind, &name) {
            self.unknown_field(node, name_tok, &name)?;
        }
        if node.kind == "Texture2" && name == "image" {
            // Only images in files are read: say so rather than lose the texture silently.
            self.warn_once(
                WarningKind::SkippedAttribute,
                name_tok.line,
                "Texture2 image",
                format!(
                    "line {}: Texture2's inline 'image' ignored (only image files are read); its shapes are untextured",
                    name_tok.line
                ),
            );
        }
        // VRML 2.0 "IS" in PROTO bodies never reaches here (bodies are skipped).
        self.skip_value()
    }

    /// An SFBool: `TRUE` / `FALSE` (or 1 / 0).
    fn parse_bool(&mut self, name: &str) -> PResult<Value> {
        let t = self.lex.next()?;
        let b = self.lex.bytes(&t);
        match (t.kind, b) {
            (Tok::Word, b"TRUE") | (Tok::Number, b"1") => Ok(Value::Bool(true)),
            (Tok::Word, b"FALSE") | (Tok::Number, b"0") => Ok(Value::Bool(false)),
            _ => Err(self.unexpected(&t, &format!("TRUE or FALSE for '{name}'"))),
        }
    }

    /// An SFNode: a node or `NULL`.
    fn parse_node_value(&mut self, name: &str) -> PResult<Value> {
        let t = self.lex.peek()?;
        if self.is_word(&t, b"NULL") {
            self.lex.next()?;
            Ok(Value::Node(None))
        } else if t.kind == Tok::Word {
            Ok(Value::Node(self.parse_statement()?))
        } else {
            self.lex.next()?;
            Err(self.unexpected(&t, &format!("a node or NULL for '{name}'")))
        }
    }

    /// An MFNode: `[ nodes ]` or a single node.
    fn parse_nodes_value(&mut self, name: &str) -> PResult<Value> {
        let t = self.lex.peek()?;
        let mut nodes = Vec::new();
        if t.kind == Tok::LBracket {
            self.lex.next()?;
            loop {
                let t = self.lex.peek()?;
                match t.kind {
                    Tok::RBracket => {
                        self.lex.next()?;
                        break;
                    }
                    Tok::Word => {
                        if let Some(n) = self.parse_statement()? {
                            nodes.push(n);
                        }
                    }
                    _ => {
                        self.lex.next()?;
                        return Err(self.unexpected(&t, &format!("a node or ']' in '{name}'")));
                    }
                }
            }
        } else if t.kind == Tok::Word {
            if let Some(n) = self.parse_statement()? {
                nodes.push(n);
            }
        } else {
            self.lex.next()?;
            return Err(self.unexpected(&t, &format!("'[' or a node for '{name}'")));
        }
        Ok(Value::Nodes(nodes))
    }

    /// A field of a node kit: a part (a node, `DEF`/`USE`, or `NULL`) kept as an SFNode
    /// value, or any other value skipped by structure.
    fn parse_kit_field(&mut self, node: &mut Node, name: String) -> PResult<()> {
        let t = self.lex.peek()?;
        let line = t.line;
        let part = if self.is_word(&t, b"DEF") || self.is_word(&t, b"USE") {
            self.parse_statement()?
        } else if t.kind == Tok::Word {
            // A node type is followed by '{'; any other word is an enum value.
            self.lex.next()?;
            if self.lex.peek()?.kind != Tok::LBrace {
                return Ok(());
            }
            Some(self.parse_node_body(t, None)?)
        } else {
            return self.skip_value();
        };
        node.fields.retain(|f| f.name != name);
        node.fields.push(Field {
            name,
            line,
            value: Value::Node(part),
        });
        Ok(())
    }

    /// A field name that `node`'s kind does not have: an error naming the field and the
    /// fields there are, or (lenient) a warning, once per node kind and field name.
    fn unknown_field(&mut self, node: &Node, t: &Token, name: &str) -> PResult<()> {
        let known = fields::fields_of(self.dialect, &node.kind).join(", ");
        let message = format!(
            "'{}' has no field '{name}' (its fields: {known})",
            node.kind
        );
        if !self.lenient {
            return Err(ParseError::new(
                t.line,
                format!("{message}; --lenient skips it with a warning"),
            ));
        }
        let key = format!("{}.{name}", node.kind);
        self.warn_once(
            WarningKind::SkippedAttribute,
            t.line,
            &key,
            format!("line {}: {message}; its value skipped", t.line),
        );
        Ok(())
    }

    /// `"text"` or `[ "a", "b" ]` (commas are whitespace to the lexer).
    fn parse_strings(&mut self, name: &str) -> PResult<Vec<String>> {
        let t = self.lex.next()?;
        match t.kind {
            Tok::Str => Ok(vec![self.string_of(&t)]),
            Tok::LBracket => {
                let mut out = Vec::new();
                loop {
                    let t = self.lex.next()?;
                    match t.kind {
                        Tok::Str => out.push(self.string_of(&t)),
                        Tok::RBracket => return Ok(out),
                        _ => {
                            return Err(self.unexpected(&t, &format!("a string or ']' in '{name}'")))
                        }
                    }
                }
            }
            _ => Err(self.unexpected(&t, &format!("a string for '{name}'"))),
        }
    }

    /// A string token's text without its quotes, `\x` read as `x`.
    fn string_of(&self, t: &Token) -> String {
        let b = self.lex.bytes(t);
        let inner = b.get(1..b.len().saturating_sub(1)).unwrap_or_default();
        let mut out = Vec::with_capacity(inner.len());
        let mut escaped = false;
        for &c in inner {
            if c == b'\\' && !escaped {
                escaped = true;
            } else {
                out.push(c);
                escaped = false;
            }
        }
        String::from_utf8_lossy(&out).into_owned()
    }

    fn parse_word(&mut self, name: &str) -> PResult<String> {
        let t = self.lex.next()?;
        match t.kind {
            Tok::Word => Ok(self.lex.text(&t)),
            Tok::LParen => {
                // Inventor bit mask: ( A | B ).
                let mut out = String::new();
                loop {
                    let t = self.lex.next()?;
                    match t.kind {
                        Tok::RParen => return Ok(out),
                        Tok::Pipe => out.push('|'),
                        Tok::Word => out.push_str(&self.lex.text(&t)),
                        _ => return Err(self.unexpected(&t, "a name, '|' or ')'")),
                    }
                }
            }
            _ => Err(self.unexpected(&t, &format!("a value name for '{name}'"))),
        }
    }

    /// Numbers, bracketed or not; brackets may be empty. `what` names one element in
    /// errors ("a number", "an integer"); `convert` checks and converts each.
    fn parse_numbers<T>(
        &mut self,
        name: &str,
        what: &str,
        convert: fn(&Self, &Token, &str) -> PResult<T>,
    ) -> PResult<Vec<T>> {
        let mut out = Vec::new();
        let first = self.lex.peek()?;
        if first.kind == Tok::LBracket {
            self.lex.next()?;
            loop {
                let t = self.lex.next()?;
                match t.kind {
                    Tok::Number => out.push(convert(self, &t, name)?),
                    Tok::RBracket => return Ok(out),
                    _ => return Err(self.unexpected(&t, &format!("{what} or ']' in '{name}'"))),
                }
            }
        }
        if first.kind != Tok::Number {
            self.lex.next()?;
            return Err(self.unexpected(&first, &format!("{what} for '{name}'")));
        }
        while self.lex.peek()?.kind == Tok::Number {
            let t = self.lex.next()?;
            out.push(convert(self, &t, name)?);
        }
        Ok(out)
    }

    fn float_of(&self, t: &Token, name: &str) -> PResult<f32> {
        match parse_f32(self.lex.bytes(t)) {
            Some(v) if v.is_finite() => Ok(v),
            Some(_) => Err(ParseError::new(
                t.line,
                format!(
                    "number {} in '{name}' is not finite in 32-bit floating point",
                    self.lex.describe(t)
                ),
            )),
            None => Err(self.unexpected(t, &format!("a number in '{name}'"))),
        }
    }

    /// A number of a coordinate field, as [`Self::float_of`] reads it and as an f64.
    fn coordinate_of(&self, t: &Token, name: &str) -> PResult<(f32, f64)> {
        let bytes = self.lex.bytes(t);
        match parse_f64(bytes) {
            Some(d) => {
                let f = nearest_f32(d, bytes);
                match f.is_finite() {
                    true => Ok((f, d)),
                    false => self.float_of(t, name).map(|f| (f, d)),
                }
            }
            None => self.float_of(t, name).map(|f| (f, f64::from(f))),
        }
    }

    fn int_of(&self, t: &Token, name: &str) -> PResult<i32> {
        match parse_int(self.lex.bytes(t)) {
            // Hexadecimal values up to 0xffffffff (packed colours) keep their bits.
            Some(v) if (i32::MIN as i64..=u32::MAX as i64).contains(&v) => Ok(v as i32),
            Some(_) => Err(ParseError::new(
                t.line,
                format!(
                    "integer {} in '{name}' is out of range",
                    self.lex.describe(t)
                ),
            )),
            None => Err(self.unexpected(t, &format!("an integer in '{name}'"))),
        }
    }

    /// Skips one field value of unknown type by its structure.
    fn skip_value(&mut self) -> PResult<()> {
        let t = self.lex.next()?;
        match t.kind {
            Tok::LBracket | Tok::LParen => self.skip_balanced(t),
            Tok::Number => {
                while self.lex.peek()?.kind == Tok::Number {
                    self.lex.next()?;
                }
                Ok(())
            }
            Tok::Str => {
                while self.lex.peek()?.kind == Tok::Str {
                    self.lex.next()?;
                }
                Ok(())
            }
            Tok::Word => {
                if self.is_word(&t, b"DEF") {
                    let name_tok = self.lex.next()?;
                    let kind_tok = self.lex.next()?;
                    if !is_name(&name_tok) || kind_tok.kind != Tok::Word {
                        return Err(self.unexpected(&kind_tok, "a name and a node after 'DEF'"));
                    }
                    let name = self.lex.text(&name_tok);
                    let node = self.parse_node_body(kind_tok, Some(name.clone()))?;
                    self.defs.insert(name, node);
                    return Ok(());
                }
                if self.is_word(&t, b"USE") {
                    let n = self.lex.next()?;
                    if !is_name(&n) {
                        return Err(self.unexpected(&n, "a name after 'USE'"));
                    }
                    return Ok(());
                }
                if self.is_word(&t, b"IS") {
                    self.lex.next()?;
                    return Ok(());
                }
                if self.lex.peek()?.kind == Tok::LBrace {
                    self.parse_node_body(t, None)?;
                }
                Ok(())
            }
            _ => Err(self.unexpected(&t, "a field value")),
        }
    }

    /// Skips tokens up to the bracket matching `open` (already consumed), without recursion.
    /// DEF names met inside are registered as skipped nodes so later USEs still resolve.
    fn skip_balanced(&mut self, open: Token) -> PResult<()> {
        let mut stack: Vec<(Tok, usize)> = vec![(open.kind, open.line)];
        let mut prev_def = false;
        while let Some(&(top, top_line)) = stack.last() {
            let t = self.lex.next()?;
            if prev_def && is_name(&t) {
                let name = self.lex.text(&t);
                self.defs.entry(name).or_insert_with(|| {
                    Rc::new(Node {
                        kind: "<skipped>".into(),
                        def: None,
                        line: t.line,
                        fields: Vec::new(),
                        children: Vec::new(),
                        skipped: true,
                    })
                });
            }
            prev_def = self.is_word(&t, b"DEF");
            match t.kind {
                Tok::LBrace | Tok::LBracket | Tok::LParen => stack.push((t.kind, t.line)),
                Tok::RBrace | Tok::RBracket | Tok::RParen => {
                    let want = match top {
                        Tok::LBrace => Tok::RBrace,
                        Tok::LBracket => Tok::RBracket,
                        _ => Tok::RParen,
                    };
                    if t.kind != want {
                        let close = match want {
                            Tok::RBrace => "'}'",
                            Tok::RBracket => "']'",
                            _ => "')'",
                        };
                        return Err(self.unexpected(
                            &t,
                            &format!("{close} to close the one opened at line {top_line}"),
                        ));
                    }
                    stack.pop();
                }
                Tok::Eof => {
                    let close = match top {
                        Tok::LBrace => "'}'",
                        Tok::LBracket => "']'",
                        _ => "')'",
                    };
                    return Err(ParseError::new(
                        self.lex.line(),
                        format!(
                            "unexpected end of file: expected {close} to close the one opened at line {top_line}"
                        ),
                    ));
                }
                _ => {}
            }
        }
        Ok(())
    }
}

/// The f32 nearest the number `bytes` spell, from its nearest f64 `d`: rounding `d` gives
/// the same f32 unless `d` lies exactly halfway between two f32s (the number may then be on
/// either side), or outside f32's normal range; those are parsed again, as f32.
fn nearest_f32(d: f64, bytes: &[u8]) -> f32 {
    // f64 keeps 29 more mantissa bits than f32: halfway is 1 followed by 28 zeros.
    const DROPPED: u64 = (1 << 29) - 1;
    const HALF: u64 = 1 << 28;
    let normal = (f64::from(f32::MIN_POSITIVE)..f64::from(f32::MAX)).contains(&d.abs());
    if d == 0.0 || (normal && d.to_bits() & DROPPED != HALF) {
        d as f32
    } else {
        parse_f32(bytes).unwrap_or(d as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coordinates_read_through_f64_give_the_f32_a_direct_parse_gives() {
        // Just above and just below the point halfway between 1 and the next f32, whose
        // nearest f64 is that halfway point: rounding it alone would give 1 both times.
        for s in [
            "1.0000000596046447753906251",
            "1.0000000596046447753906249",
            "0.35",
            "-1200000.35",
            "1e-40",
            "3.4028235e38",
            "0",
            "-0",
        ] {
            let b = s.as_bytes();
            let d = parse_f64(b).unwrap();
            assert_eq!(
                nearest_f32(d, b).to_bits(),
                parse_f32(b).unwrap().to_bits(),
                "{s}"
            );
        }
    }
}
