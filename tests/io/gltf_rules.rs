//! glTF 2.0's accessor, buffer view and container rules (issue 56): sparse POSITION
//! accessors are read; integer POSITION without `KHR_mesh_quantization`, a byteStride that
//! is not a multiple of 4, `asset.version` 1.0, a GLB whose header miscounts its length and
//! an image that is neither a uri nor a bufferView with its mimeType are refused, naming the
//! file and the JSON path or GLB byte offset at fault.

use base64::Engine;
use serde_json::{json, Value};

use crate::hostile::glb_with;

/// One triangle placed by one node, with `edit` applied to the JSON.
fn triangle(edit: impl FnOnce(&mut Value)) -> Vec<u8> {
    glb_with(json!([{ "mesh": 0 }]), json!([0]), 1, edit)
}

/// The error reading `bytes` as `name`, which must fail.
fn error(bytes: Vec<u8>, name: &str) -> String {
    match decimate_core::io::parse_bytes(bytes, std::path::Path::new(name)) {
        Ok(_) => panic!("{name} was read"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn the_unchanged_triangle_reads() {
    let out = decimate_core::io::parse_bytes(triangle(|_| {}), "t.glb".as_ref()).unwrap();
    assert_eq!(out.scene.triangle_count(), 1);
}

#[test]
fn a_sparse_position_accessor_is_read() {
    // Vertex 2 moved from (0 1 0) to (0 2 0) by a sparse substitution in a second buffer.
    let mut data = vec![2u8, 0, 0, 0];
    for v in [0f32, 2., 0.] {
        data.extend(v.to_le_bytes());
    }
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&data)
    );
    let bytes = triangle(|j| {
        j["buffers"]
            .as_array_mut()
            .unwrap()
            .push(json!({ "uri": uri, "byteLength": 16 }));
        let views = j["bufferViews"].as_array_mut().unwrap();
        views.push(json!({ "buffer": 1, "byteOffset": 0, "byteLength": 4 }));
        views.push(json!({ "buffer": 1, "byteOffset": 4, "byteLength": 12 }));
        j["accessors"][0]["max"] = json!([1, 2, 0]);
        j["accessors"][0]["sparse"] = json!({
            "count": 1,
            "indices": { "bufferView": 2, "componentType": 5121 },
            "values": { "bufferView": 3 }
        });
    });
    let out = decimate_core::io::parse_bytes(bytes, "sparse.glb".as_ref()).unwrap();
    let m = &out.scene.models[0];
    let mut ys: Vec<f32> = m.positions.iter().map(|p| p.y).collect();
    ys.sort_by(f32::total_cmp);
    assert_eq!(ys, [0.0, 0.0, 2.0], "the substituted vertex");
}

#[test]
fn integer_positions_need_the_quantization_extension() {
    let e = error(
        triangle(|j| {
            j["accessors"][0]["componentType"] = json!(5123);
            j["accessors"][0]["max"] = json!([1, 1, 0]);
        }),
        "short.glb",
    );
    assert!(
        e.starts_with("short.glb:")
            && e.contains("meshes[0].primitives[0].attributes.POSITION")
            && e.contains("KHR_mesh_quantization"),
        "{e}"
    );
}

#[test]
fn a_byte_stride_of_13_is_refused() {
    let e = error(
        triangle(|j| j["bufferViews"][0]["byteStride"] = json!(13)),
        "stride.glb",
    );
    assert!(
        e.starts_with("stride.glb:") && e.contains("bufferViews[0].byteStride: 13"),
        "{e}"
    );
}

#[test]
fn asset_version_1_is_refused() {
    let e = error(
        triangle(|j| j["asset"]["version"] = json!("1.0")),
        "old.glb",
    );
    assert!(
        e.starts_with("old.glb:") && e.contains("asset.version: '1.0'"),
        "{e}"
    );
}

#[test]
fn a_glb_header_length_that_is_too_small_is_refused_at_byte_8() {
    let mut bytes = triangle(|_| {});
    let short = (bytes.len() as u32 - 8).to_le_bytes();
    bytes[8..12].copy_from_slice(&short);
    let e = error(bytes, "len.glb");
    assert!(e.starts_with("len.glb: byte 8: the GLB header says"), "{e}");
}

#[test]
fn an_image_that_is_no_uri_or_a_buffer_view_without_a_mime_type_is_refused() {
    // A bufferView image without its mimeType (the coverage fuzzer's crash: the gltf crate
    // panicked on it), and an image with neither a uri nor a bufferView.
    let cases = [
        (
            json!({ "bufferView": 0 }),
            "images[0]: a bufferView image needs a mimeType",
        ),
        (
            json!({ "name": "nothing" }),
            "images[0]: give either a uri or a bufferView",
        ),
    ];
    for (image, want) in cases {
        let e = error(triangle(|j| j["images"] = json!([image])), "image.glb");
        assert!(e.starts_with("image.glb:") && e.contains(want), "{e}");
    }
}
