//! A glTF's node tree written back as glTF keeps its nodes' transforms to the digit, far
//! translations included (georeferenced files put them there, see
//! docs/design.md#far-coordinates): a TRS node's translation, rotation and scale, a matrix
//! node's matrix, and a far parent above a near child. The output's JSON is read by the
//! test itself. In f32 a translation of 7654321.123 comes back as 7654321.0.

use std::process::Command;

use serde_json::{json, Value};

use super::gltf::{assert_valid, scratch, wavy_grid_arrays, Doc, UINT};

/// A wavy 8 x 8 grid of unit squares as a new mesh of `d` (128 triangles); its index.
fn grid_mesh(d: &mut Doc) -> usize {
    let n = 8u32;
    let (pos, idx) = wavy_grid_arrays(n, 0.7);
    let position = d.positions(&pos);
    let bytes: Vec<u8> = idx.iter().flat_map(|i| i.to_le_bytes()).collect();
    let indices = d.accessor(&bytes, UINT, "SCALAR", idx.len(), false);
    let prim = json!({ "attributes": { "POSITION": position }, "indices": indices });
    d.push("meshes", json!({ "primitives": [prim] }))
}

/// The numbers of a JSON array.
fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap_or_else(|| panic!("not a number: {x}")))
        .collect()
}

/// Asserts that `got` (a JSON array) holds `want`, each within `tolerance`.
fn assert_near(what: &str, got: &Value, want: &[f64], tolerance: f64) {
    let got = numbers(got);
    assert_eq!(got.len(), want.len(), "{what}: {got:?}");
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() <= tolerance, "{what}: {got:?}, not {want:?}");
    }
}

#[test]
fn far_node_translations_and_matrices_come_back_to_the_digit() {
    let dir = scratch("far-tree");
    let mut d = Doc::new();
    let mesh = grid_mesh(&mut d);
    let translation = [1234567.891, 7654321.123, 0.0];
    let rotation = [0.0, 0.0, 0.6, 0.8];
    let scale = [1.0, 1.0, 2.5];
    let mut matrix = [0.0; 16];
    [0, 5, 10, 15].iter().for_each(|&k| matrix[k] = 1.0);
    matrix[12..15].copy_from_slice(&[-2345678.912, 0.3, 8765432.1]);
    let parent = [4321098.765, -1.0e6 - 0.017, 12.5];
    let child = [0.1, 0.2, 0.3];
    d.json["nodes"] = json!([
        { "name": "trs", "mesh": mesh, "translation": translation, "rotation": rotation,
          "scale": scale },
        { "name": "matrix", "mesh": mesh, "matrix": matrix },
        { "name": "parent", "translation": parent, "children": [3] },
        { "name": "child", "mesh": mesh, "translation": child },
    ]);
    d.json["scenes"][0]["nodes"] = json!([0, 1, 2]);
    std::fs::write(dir.join("in.gltf"), d.gltf_embedded()).unwrap();

    let o = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(["in.gltf", "nogui", "-p", "50", "-o", "out.gltf"])
        .current_dir(&dir)
        .output()
        .expect("runs decimate");
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{said}");
    let text = std::fs::read(dir.join("out.gltf")).unwrap();
    let out: Value = serde_json::from_slice(&text).expect("the output is JSON");
    let nodes = out["nodes"].as_array().expect("nodes");
    let node = |name: &str| {
        nodes
            .iter()
            .find(|n| n["name"] == name)
            .unwrap_or_else(|| panic!("no node '{name}' in {nodes:?}"))
    };
    let trs = node("trs");
    assert_near("trs translation", &trs["translation"], &translation, 1e-6);
    // Written as read: 0.6 and 2.5, not the f32 0.6000000238.
    assert_near("trs rotation", &trs["rotation"], &rotation, 1e-12);
    assert_near("trs scale", &trs["scale"], &scale, 1e-12);
    assert_near("matrix", &node("matrix")["matrix"], &matrix, 1e-6);
    assert_near("parent", &node("parent")["translation"], &parent, 1e-6);
    assert_near("child", &node("child")["translation"], &child, 1e-12);
    // One mesh, decimated once: 81 positions to 40, as many triangles as the run says.
    let meshes = out["meshes"].as_array().expect("meshes");
    assert_eq!(meshes.len(), 1, "{meshes:?}");
    let primitive = &meshes[0]["primitives"][0];
    let count =
        |a: &Value| out["accessors"][a.as_u64().expect("an index") as usize]["count"].clone();
    assert_eq!(count(&primitive["attributes"]["POSITION"]), 40);
    let total = said
        .lines()
        .find_map(|l| l.split_once("triangles 128 -> ")?.1.split(';').next())
        .and_then(|n| n.parse::<u64>().ok())
        .unwrap_or_else(|| panic!("no total: {said}"));
    assert_eq!(count(&primitive["indices"]), 3 * total);
    assert_valid(&[&dir.join("out.gltf")]);
}
