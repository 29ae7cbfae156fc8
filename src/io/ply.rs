//! PLY (Stanford polygon format): a reader for ASCII and binary (little / big endian) files and
//! a binary little-endian writer.
//!
//! Read: `element vertex` with `x y z` (float or double, any other properties skipped) and
//! optional `red green blue` (uchar, becoming per-vertex colours), `element face` with a
//! `vertex_indices` / `vertex_index` list (any integer count and index types); polygons are
//! triangulated like VRML faces. Other elements are skipped. The result is one model.
//! Write: one binary little-endian file of all models, transforms baked in.
pub fn read_ply(_b: &[u8]) -> super::lexer::PResult<(crate::mesh::Scene, Vec<String>)> {
    Err(super::lexer::ParseError::new(1, "todo"))
}
pub fn write_ply(_s: &crate::mesh::Scene, p: &std::path::Path) -> Result<(), super::WriteError> {
    Err(super::WriteError {
        file: p.into(),
        source: std::io::Error::other("todo"),
    })
}
