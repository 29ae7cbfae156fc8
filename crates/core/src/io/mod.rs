//! Reading and writing scenes. One module per format; all readers produce the same `Scene`.
//!
//! Entry points: [`read_scene`] (format from the header, the file name's extension or the
//! content; gzip handled here; a progressive mesh gives its full meshes and the record),
//! [`write_scene`] (format from the output's extension) and [`write_vrml2`] (all writers go
//! through [`replace::replace_file`]: a temporary file, then a rename); [`parse_bytes`] /
//! [`parse_str`] read from memory. Submodules: `vrml` (VRML 1.0, Open Inventor and VRML 2.0:
//! lexer, node trees, both families' semantics, the VRML 2.0 writer), `text` (the line-named
//! error and number parsing every text reader shares), `shape_to_model` (shape to model),
//! `triangulate` (ear clipping), `ply`, `obj`, `stl`, `off` (those formats' readers and
//! writers), `texture_image` (PNG/JPEG texture files decoded to RGBA), `progressive_file`
//! (the binary `.pm` file of a progressive mesh, `--progressive`: its own reader and writer),
//! `replace` (how every output replaces its file), `mtl` (an OBJ's material libraries: read
//! by [`read_scene`], which knows the OBJ's folder, and written beside an OBJ output) and
//! `texture_path` (texture names re-expressed for the folder a scene is written to:
//! [`rebase_textures`], which every writer's caller applies first), `losses` (what an output
//! format cannot hold, said before writing), `gltf` (glTF 2.0 `.gltf`/`.glb`, read and
//! written) and `data_uri` (the `data:` URIs glTF embeds buffers and images in), `source`
//! (the bytes the PLY and STL parsers read, in memory or streamed, so tiling's `stream`
//! reads run the same parsers), `warning` (readers' warnings, typed by kind) and
//! `file_limits` (regular files only, byte limits, references kept in the model's folder),
//! `origin` (far coordinates: the f64 origin readers pick, the digits writers print).

pub mod data_uri;
pub mod file_limits;
pub(crate) mod gltf;
pub mod losses;
pub(crate) mod mtl;
pub mod obj;
pub mod off;
pub mod origin;
pub mod ply;
pub mod progressive_file;
pub mod replace;
mod shape_to_model;
mod source;
pub mod stl;
pub(crate) mod stream;
mod text;
mod text_encoding;
pub mod texture_image;
pub mod texture_path;
pub(crate) mod triangulate;
mod vrml;
pub mod warning;

use std::path::{Path, PathBuf};

use crate::mesh::progressive::ProgressiveScene;
use crate::mesh::{Attribute, Scene};
use text::ParseError;

pub use obj::write_obj;
pub use off::write_off;
pub use ply::write_ply;
pub use stl::write_stl;
pub use texture_path::{rebase_textures, rebased};
pub use vrml::write_vrml2_to;
pub use warning::{Warning, WarningKind};

/// What went wrong reading a scene: always names the file, and the line where there is one.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The file could not be opened or read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// The text is not what the format allows at this line.
    #[error("{file}:{line}: {message}")]
    Syntax {
        /// The file.
        file: PathBuf,
        /// The line, counted from 1.
        line: usize,
        /// What is wrong there.
        message: String,
    },
    /// The file is of a kind or variant this program does not read.
    #[error("{file}: {message}")]
    Unsupported {
        /// The file.
        file: PathBuf,
        /// What it is, and what to do about it.
        message: String,
    },
    /// A binary file's fixed-size record (binary STL), counted from 1.
    #[error("{file}: record {record}: {message}")]
    Record {
        /// The file.
        file: PathBuf,
        /// The record, counted from 1.
        record: usize,
        /// What is wrong with it.
        message: String,
    },
    /// A binary file's byte offset (a progressive mesh, a GLB), counted from 0.
    #[error("{file}: byte {offset}: {message}")]
    Binary {
        /// The file.
        file: PathBuf,
        /// The byte offset, counted from 0.
        offset: usize,
        /// What is wrong there.
        message: String,
    },
}

/// What went wrong writing a scene.
#[derive(Debug, thiserror::Error)]
#[error("{file}: {source}")]
pub struct WriteError {
    /// The file that could not be written.
    pub file: PathBuf,
    /// What the system said.
    #[source]
    pub source: std::io::Error,
}

/// A parsed scene and the warnings met on the way (one per kind of skipped node, etc.).
#[derive(Debug, Clone, Default)]
pub struct ReadOutcome {
    /// The models read, in file order.
    pub scene: Scene,
    /// Typed (kind, file, line, count); [`warning::grouped`] orders them for printing.
    pub warnings: Vec<Warning>,
    /// Set when the file is a progressive mesh (`FILE.pm`); `scene` is then its full meshes.
    pub progressive: Option<ProgressiveScene>,
    /// The material libraries an OBJ names (`mtllib`), as written, relative to its folder;
    /// [`read_scene`] has applied them, [`parse_bytes`] has not (it reads no other file).
    pub material_libraries: Vec<String>,
}

/// Most models one file may expand to (DEF/USE instancing can multiply them).
pub const MAX_MODELS: usize = 1_000_000;
/// Most triangles one file may expand to.
pub const MAX_TRIANGLES: usize = 200_000_000;

/// A file format, as far as the file name's extension tells.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// VRML 2.0 (`.wrl`, `.vrml`).
    Vrml2,
    /// PLY (`.ply`).
    Ply,
    /// Wavefront OBJ (`.obj`), with its MTL.
    Obj,
    /// STL (`.stl`).
    Stl,
    /// OFF (`.off`).
    Off,
    /// glTF 2.0 as JSON (`.gltf`) or binary (`.glb`); both are read from either extension.
    Gltf,
    /// glTF 2.0 binary (`.glb`).
    Glb,
}

impl Format {
    /// The format a file name's extension names (`.gz` looked through), if any.
    pub fn from_path(path: &Path) -> Option<Self> {
        let ext = |p: &Path| {
            p.extension()
                .and_then(|e| e.to_str())
                .map(|e| e.to_ascii_lowercase())
        };
        let mut e = ext(path)?;
        if e == "gz" {
            e = ext(Path::new(path.file_stem()?))?;
        }
        Some(match e.as_str() {
            "wrl" | "vrml" => Self::Vrml2,
            "ply" => Self::Ply,
            "obj" => Self::Obj,
            "stl" => Self::Stl,
            "off" => Self::Off,
            "gltf" => Self::Gltf,
            "glb" => Self::Glb,
            _ => return None,
        })
    }
}

/// How strictly a scene file is read.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReadOptions {
    /// An unknown field of a known VRML / Inventor node is a warning (its value skipped)
    /// instead of an error (`--lenient`).
    pub lenient: bool,
}

/// Reads a VRML 1.0, VRML 2.0, Open Inventor ASCII, PLY, OBJ, STL, OFF or glTF file (optionally
/// gzipped); an OBJ's material libraries are read from its folder and applied (see `mtl`).
pub fn read_scene(path: &Path) -> Result<ReadOutcome, ReadError> {
    read_scene_with(path, ReadOptions::default())
}

/// [`read_scene`] with `options`.
pub fn read_scene_with(path: &Path, options: ReadOptions) -> Result<ReadOutcome, ReadError> {
    let io_err = |source| ReadError::Io {
        file: path.to_path_buf(),
        source,
    };
    let bytes = file_limits::read_regular(path).map_err(io_err)?;
    let format = Format::from_path(path);
    // A glTF material's name is its own, not an OBJ's `usemtl`: no MTL library applies.
    let gltf = matches!(format, Some(Format::Gltf | Format::Glb)) || gltf::is_glb(&bytes);
    let mut outcome = parse_bytes_with(bytes, path, format, options)?;
    if !gltf {
        mtl::apply_materials(&mut outcome, path)?;
    }
    texture_path::drop_outside_textures(&mut outcome, path);
    Ok(outcome)
}

/// Reads a scene from memory; `file_name` is used in messages, and its extension says the
/// format when the content does not.
pub fn parse_bytes(bytes: Vec<u8>, file_name: &Path) -> Result<ReadOutcome, ReadError> {
    parse_bytes_with(
        bytes,
        file_name,
        Format::from_path(file_name),
        ReadOptions::default(),
    )
}

/// Reads a scene from text (tests, tools); `file_name` is used in messages.
pub fn parse_str(text: &str, file_name: &str) -> Result<ReadOutcome, ReadError> {
    parse_bytes(text.as_bytes().to_vec(), Path::new(file_name))
}

/// Reads a scene from memory; every warning that names no file of its own names `path`.
fn parse_bytes_with(
    bytes: Vec<u8>,
    path: &Path,
    by_name: Option<Format>,
    options: ReadOptions,
) -> Result<ReadOutcome, ReadError> {
    let mut outcome = parse_any(bytes, path, by_name, options)?;
    for w in &mut outcome.warnings {
        w.file.get_or_insert_with(|| path.to_path_buf());
    }
    Ok(outcome)
}

fn parse_any(
    bytes: Vec<u8>,
    path: &Path,
    by_name: Option<Format>,
    options: ReadOptions,
) -> Result<ReadOutcome, ReadError> {
    let bytes = gunzip(bytes, path)?;
    if bytes.starts_with(&progressive_file::MAGIC) {
        let pm = progressive_file::parse_progressive(&bytes, path)?;
        let models = pm.models.iter().map(|m| m.original()).collect();
        return Ok(ReadOutcome {
            scene: Scene { models },
            warnings: Vec::new(),
            progressive: Some(pm),
            material_libraries: Vec::new(),
        });
    }
    let glb = gltf::is_glb(&bytes);
    let binary_stl = stl::is_binary(&bytes);
    let bytes = text_encoding::drop_byte_order_mark(bytes, glb || binary_stl)
        .map_err(|message| syntax(path, ParseError::new(1, message)))?;
    let gltf_by_name = matches!(by_name, Some(Format::Gltf | Format::Glb));
    if glb || gltf_by_name {
        return gltf::read_gltf(&bytes, path);
    }
    let ply_by_name = by_name == Some(Format::Ply);
    let ply = bytes.starts_with(b"ply") && matches!(bytes.get(3), Some(b'\n' | b'\r'));
    let bytes = text_encoding::mac_line_ends(bytes, ply || ply_by_name, binary_stl);
    if ply || ply_by_name {
        let (scene, warnings) = ply::read_ply(&bytes).map_err(|e| syntax(path, e))?;
        return Ok(outcome(scene, warnings));
    }
    let first_line_end = bytes
        .iter()
        .position(|&b| matches!(b, b'\n' | b'\r'))
        .unwrap_or(bytes.len());
    let header = String::from_utf8_lossy(&bytes[..first_line_end]);
    let header = header.trim_end();
    let vrml_family = ["#VRML V1.0 ascii", "#VRML V2.0 utf8", "#Inventor"]
        .iter()
        .any(|h| header.starts_with(h));
    if !vrml_family {
        if let Some(read) = parse_mesh_format(&bytes, path, by_name)? {
            return Ok(read);
        }
    }
    let dialect = vrml_dialect(header, &bytes, path)?;
    vrml::read_tree(&bytes, path, dialect, options).map_err(|e| syntax(path, e))
}

/// A parse error at a line of `file`.
fn syntax(file: &Path, e: ParseError) -> ReadError {
    ReadError::Syntax {
        file: file.to_path_buf(),
        line: e.line,
        message: e.message,
    }
}

/// A scene read by one of the readers that take no options.
fn outcome(scene: Scene, warnings: Vec<Warning>) -> ReadOutcome {
    ReadOutcome {
        scene,
        warnings,
        progressive: None,
        material_libraries: Vec::new(),
    }
}

/// The bytes decompressed when they are a gzip stream, as they are otherwise.
fn gunzip(bytes: Vec<u8>, path: &Path) -> Result<Vec<u8>, ReadError> {
    if !bytes.starts_with(&[0x1f, 0x8b]) {
        return Ok(bytes);
    }
    file_limits::gunzip_limited(&bytes).map_err(|message| ReadError::Syntax {
        file: path.to_path_buf(),
        line: 1,
        message,
    })
}

/// An STL, OFF or OBJ file (by its name, else by its content); `None` when it is none of
/// them.
fn parse_mesh_format(
    bytes: &[u8],
    path: &Path,
    by_name: Option<Format>,
) -> Result<Option<ReadOutcome>, ReadError> {
    let sniffed = by_name.filter(|&f| f != Format::Vrml2).or_else(|| {
        if stl::is_binary(bytes) || stl::starts_with_solid(bytes) {
            Some(Format::Stl)
        } else if off::looks_like_off(bytes) {
            Some(Format::Off)
        } else if obj::looks_like_obj(bytes) {
            Some(Format::Obj)
        } else {
            None
        }
    });
    let (scene, warnings) = match sniffed {
        Some(Format::Obj) => return obj::read_obj(bytes).map(Some).map_err(|e| syntax(path, e)),
        Some(Format::Off) => off::read_off(bytes).map_err(|e| syntax(path, e))?,
        Some(Format::Stl) => stl::read_stl(bytes).map_err(|e| stl_error(path, e))?,
        Some(_) => (Scene::default(), Vec::new()),
        None => return Ok(None),
    };
    Ok(Some(outcome(scene, warnings)))
}

/// The VRML family dialect the first line (`header`) names; an error naming what it found
/// when it names none.
fn vrml_dialect(header: &str, bytes: &[u8], path: &Path) -> Result<vrml::Dialect, ReadError> {
    Ok(if header.starts_with("#VRML V1.0 ascii") {
        vrml::Dialect::Vrml1
    } else if header.starts_with("#VRML V2.0 utf8") {
        vrml::Dialect::Vrml2
    } else if header.starts_with("#Inventor") && header.contains("binary") {
        return Err(ReadError::Unsupported {
            file: path.to_path_buf(),
            message: "binary Inventor is not supported (convert it with ivcat)".into(),
        });
    } else if header.starts_with("#Inventor V2.") || header.starts_with("#Inventor V1.0 ascii") {
        vrml::Dialect::Vrml1
    } else if bytes.iter().all(|b| b.is_ascii_whitespace()) {
        return Err(syntax(
            path,
            ParseError::new(
                1,
                "the file is empty: expected a '#VRML V1.0 ascii', '#VRML V2.0 utf8' or '#Inventor V2.1 ascii' header",
            ),
        ));
    } else {
        // Control and non-ASCII bytes shown escaped: a binary file's start, not noise.
        let shown: String = header
            .chars()
            .take(40)
            .flat_map(char::escape_default)
            .collect();
        return Err(syntax(
            path,
            ParseError::new(
                1,
                format!(
                    "not a VRML, Open Inventor, PLY, OBJ, STL, OFF or glTF file: expected a '#VRML V1.0 ascii', '#VRML V2.0 utf8' or '#Inventor V2.1 ascii' header, found '{shown}'"
                ),
            ),
        ));
    })
}

/// An STL reader's error as a [`ReadError`] naming `file`.
fn stl_error(file: &Path, e: stl::StlError) -> ReadError {
    let file = file.to_path_buf();
    match e {
        stl::StlError::Line(e) => ReadError::Syntax {
            file,
            line: e.line,
            message: e.message,
        },
        stl::StlError::Header(message) => ReadError::Syntax {
            file,
            line: 1,
            message,
        },
        stl::StlError::Record { record, message } => ReadError::Record {
            file,
            record,
            message,
        },
    }
}

/// Writes `scene` to `path` in the format its extension names: `.ply`, `.obj`, `.stl`, `.off`,
/// `.gltf`, `.glb`;
/// `.wrl` and anything else give VRML 2.0. Always via a temporary file and a rename. Texture
/// names are written as they are: a scene read from another folder is given to
/// [`rebase_textures`] first. An OBJ may come with an MTL file beside it (see `mtl`).
pub fn write_scene(scene: &Scene, path: &Path) -> Result<(), WriteError> {
    match Format::from_path(path) {
        Some(Format::Ply) => write_ply(scene, path),
        Some(Format::Obj) => write_obj(scene, path),
        Some(Format::Stl) => write_stl(scene, path),
        Some(Format::Off) => write_off(scene, path),
        Some(Format::Gltf | Format::Glb) => gltf::write_gltf(scene, path),
        Some(Format::Vrml2) | None => write_vrml2(scene, path),
    }
}

/// True when the scene has models and every one has a texture coordinate pair per vertex:
/// OFF and PLY hold all models in one vertex list, so they write pairs for all or none.
pub(crate) fn all_textured(scene: &Scene) -> bool {
    !scene.models.is_empty()
        && scene.models.iter().all(|m| {
            m.texcoords
                .as_ref()
                .is_some_and(|t| t.len() == m.positions.len())
        })
}

/// True when every model of a non-empty `scene` has one colour per triangle (PLY and OFF
/// write them on the face records then).
pub(crate) fn all_face_colored(scene: &Scene) -> bool {
    !scene.models.is_empty()
        && scene.models.iter().all(
            |m| matches!(&m.colors, Some(Attribute::PerFace(c)) if c.len() == m.triangles.len()),
        )
}

/// `m`'s triangles as they must be written by the formats that store world positions (PLY,
/// OBJ, STL, OFF): when the model's transform mirrors, the transformed triangles would face
/// inwards, so their winding is reversed to stay counter-clockwise seen from outside.
pub(crate) fn outward_triangles(m: &crate::mesh::Model) -> impl Iterator<Item = [u32; 3]> + '_ {
    let flip = m.transform.determinant() < 0.0;
    m.triangles
        .iter()
        .map(move |t| if flip { [t[0], t[2], t[1]] } else { *t })
}

/// Writes `scene` as VRML 2.0 to `path` via a temporary file in the same folder and a rename.
pub fn write_vrml2(scene: &Scene, path: &Path) -> Result<(), WriteError> {
    write_atomically(path, |w| write_vrml2_to(w, scene))
}

/// Writes through `write` into `path` with [`replace::replace_file`] (a temporary file and a
/// rename; on any error `path` is left as it was), naming `path` in the error.
pub(crate) fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> Result<(), WriteError> {
    replace::replace_file(path, write).map_err(|source| WriteError {
        file: path.to_path_buf(),
        source,
    })
}
