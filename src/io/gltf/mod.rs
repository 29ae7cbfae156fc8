//! glTF 2.0, JSON (`.gltf`) and binary (`.glb`): `read` walks a file's default scene into a
//! `Scene` (one model per triangle primitive and node), `write` writes a `Scene` back (one
//! node per model), `accessor` decodes the typed arrays both read from buffers.

mod accessor;
mod read;
mod write;

pub use read::read_gltf;
pub use write::write_gltf;

/// True when `bytes` start like a binary glTF file.
pub fn is_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(b"glTF")
}
