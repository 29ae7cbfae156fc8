//! Tiling's reads of meshes too big to hold: PLY (ASCII, binary little and big endian), STL
//! (binary and ASCII), OBJ and OFF hand each triangle's three positions to a callback as they
//! are read, through a buffer, never building a `Scene`. The parsing is the ordinary readers'
//! (`ply::stream_ply`, `stl::stream_stl`, `obj::stream_obj`, `off::stream_off`), fed by
//! `source::Streamed`.
//!
//! Memory: STL holds nothing; PLY, OBJ and OFF hold the vertex positions only (12 bytes a
//! vertex, about 6 bytes a triangle on a closed mesh), since their faces index them (OFF also
//! the colours and texture coordinates its vertex lines carry). Polygons are
//! fanned into triangles from their first corner. Positions are read as `f32` relative to
//! the origin a `Recentre` picks (doubles are rounded once), so a position is the same bits
//! wherever it is read again, and far files (see `io::origin`) keep their precision.

use std::io::{BufReader, Read};
use std::path::Path;

use super::origin::Recentre;
use super::source::Streamed;
use super::text::ParseError;
use super::text_encoding::{self, LoneCrToLf};
use super::ReadError;

/// One triangle: three positions, counter-clockwise seen from the front.
pub type Corners = [[f32; 3]; 3];

/// Buffer of the OBJ line reader: large enough that reads are a small part of the time.
const BUFFER: usize = 1 << 20;

/// Calls `triangle` with every triangle of the PLY, STL, OBJ or OFF file at `path` (the
/// extension says which; PLY also by its first bytes), in file order, its positions
/// relative to the origin `recentre` picks (or has picked). Text is taken as a file read
/// whole takes it (`text_encoding`): a UTF-8 byte-order mark dropped, UTF-16 and UTF-32
/// refused, lone carriage returns read as line ends.
pub fn for_each_triangle(
    path: &Path,
    recentre: &mut Recentre,
    triangle: &mut dyn FnMut(Corners),
) -> Result<(), ReadError> {
    let io_error = |source| ReadError::Io {
        file: path.to_path_buf(),
        source,
    };
    let syntax = |e: ParseError| ReadError::Syntax {
        file: path.to_path_buf(),
        line: e.line,
        message: e.message,
    };
    // Only a regular file: a FIFO would block, a device never end. No byte limit: tiling
    // is for files bigger than memory, and streams them.
    let (mut file, len) = super::file_limits::open_regular(path).map_err(io_error)?;
    let by_name = super::Format::from_path(path);
    let ply_by_name = by_name == Some(super::Format::Ply);
    let head = text_encoding::read_head(&mut file, ply_by_name).map_err(io_error)?;
    let binary_stl = super::stl::is_binary_of_size(&head, len);
    let (skip, convert) = text_encoding::streamed_text(&head, ply_by_name, binary_stl)
        .map_err(|message| syntax(ParseError::new(1, message)))?;
    let kind = if head[skip..].starts_with(b"ply") {
        super::Format::Ply
    } else {
        match by_name {
            Some(
                f @ (super::Format::Ply
                | super::Format::Stl
                | super::Format::Obj
                | super::Format::Off),
            ) => f,
            _ => {
                return Err(ReadError::Unsupported {
                    file: path.to_path_buf(),
                    message: "tiling streams PLY, STL, OBJ and OFF files only; convert it first \
                              (decimate FILE nogui -p 0 -o FILE.ply)"
                        .into(),
                })
            }
        }
    };
    let mut start = std::io::Cursor::new(head);
    start.set_position(skip as u64);
    let r = LoneCrToLf::new(BufReader::with_capacity(BUFFER, start.chain(file)), convert);
    let len = len.saturating_sub(skip as u64);
    let len_usize = usize::try_from(len).unwrap_or(usize::MAX);
    match kind {
        super::Format::Ply => {
            super::ply::stream_ply(Streamed::new(r), len_usize, recentre, triangle).map_err(syntax)
        }
        super::Format::Stl => super::stl::stream_stl(Streamed::new(r), len, recentre, triangle)
            .map_err(|e| super::stl_error(path, e)),
        super::Format::Off => {
            let input = BufReader::with_capacity(BUFFER, r);
            super::off::stream_off(input, len_usize, recentre, triangle).map_err(syntax)
        }
        _ => super::obj::stream_obj(BufReader::with_capacity(BUFFER, r), recentre, triangle)
            .map_err(syntax),
    }
}
