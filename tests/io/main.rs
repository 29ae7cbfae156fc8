//! Reading and writing files: every format's syntax and geometry node, errors with file and
//! line, round trips through our writers, far (georeferenced) coordinates kept, real
//! Inventor models and their triangle counts against Coin's, the primitives' texture coordinates under a texture, VTK reading our VRML
//! output, materials and texture wrapping carried from input to output by the binary, and glTF
//! read and written (checked by the Khronos validator).

#[path = "../support/mod.rs"]
mod support;

mod coin_counts;
mod errors;
mod formats;
mod georef;
mod georef_scenes;
mod georef_shapes;
mod gltf;
mod gltf_carry;
mod gltf_far_tree;
mod gltf_rules;
mod gltf_tree;
mod gltf_write;
mod hostile;
mod hostile_formats;
mod inventor_data;
mod mtl_text;
mod nodes;
mod obj_materials;
mod parse;
mod ply;
mod primitive_texcoords;
mod roundtrip;
mod speed;
mod texture_wrap;
mod tiled_text;
mod vrml_independent;
mod warnings;
