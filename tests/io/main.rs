//! Reading and writing files: every format's syntax, errors with file and line, round trips
//! through our writers, real Inventor models, VTK reading our VRML output, and materials
//! and texture wrapping carried from input to output by the binary, glTF read and written
//! (checked by the Khronos validator).

#[path = "../support/mod.rs"]
mod support;

mod errors;
mod formats;
mod gltf;
mod inventor_data;
mod obj_materials;
mod parse;
mod ply;
mod roundtrip;
mod speed;
mod texture_wrap;
mod vrml_independent;
