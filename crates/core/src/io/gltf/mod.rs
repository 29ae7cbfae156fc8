//! glTF 2.0, JSON (`.gltf`) and binary (`.glb`): `read` walks a file's default scene into a
//! `Scene` (one model per triangle primitive and node, the node tree kept), `write` writes a
//! `Scene` back (the node tree as read, or one node per model), `accessor` decodes the typed
//! arrays both read from buffers, `copy_through` carries what a `Scene` does not hold (skins, morph
//! targets, animations, points and lines, cameras, lights, `extras`) through unchanged,
//! `exact` reads node transforms in f64 for far (georeferenced) scenes.

mod accessor;
mod copy_through;
mod exact;
mod read;
mod write;

pub use copy_through::carried_kinds;
pub use read::read_gltf;
pub use write::{image_losses, write_gltf};

/// True when `bytes` start like a binary glTF file.
pub fn is_glb(bytes: &[u8]) -> bool {
    bytes.starts_with(b"glTF")
}
