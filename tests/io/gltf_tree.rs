//! glTF through `decimate`, as a glTF user sees it: the node tree comes back as it went in
//! (names, parents and children, local TRS or matrix), a mesh three nodes place is
//! decimated once and written once, skinned and morphed meshes come back byte for byte with
//! their skin, targets and animation, and a texture image that cannot be written is named
//! in a warning. Outputs are read back with the gltf crate and pass the Khronos validator.

use std::path::Path;
use std::process::Command;

use decimate_core::io::read_scene;
use glam::{Mat4, Quat, Vec3};
use serde_json::{json, Value};

use super::gltf::{assert_valid, scratch, Doc, FLOAT, UBYTE, UINT};

/// A flat `n × n` grid of unit squares in the xy plane, as a new mesh of `d` (POSITION
/// with its bounds, indexed by unsigned ints), named `name`; its index.
fn grid_mesh(d: &mut Doc, n: usize, name: &str) -> usize {
    let prim = grid_primitive(d, n);
    d.push("meshes", json!({ "name": name, "primitives": [prim] }))
}

/// The primitive of `grid_mesh`, with a wave in z so that every vertex can move.
fn grid_primitive(d: &mut Doc, n: usize) -> Value {
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f32, j as f32);
            pos.extend_from_slice(&[x, y, 0.1 * (x * 0.7).sin() * (y * 0.5).cos()]);
        }
    }
    let mut idx = Vec::new();
    for j in 0..n as u32 {
        for i in 0..n as u32 {
            let a = j * (n as u32 + 1) + i;
            let (b, c, e) = (a + 1, a + n as u32 + 2, a + n as u32 + 1);
            idx.extend_from_slice(&[a, b, c, a, c, e]);
        }
    }
    let position = d.positions(&pos);
    let bytes: Vec<u8> = idx.iter().flat_map(|i| i.to_le_bytes()).collect();
    let indices = d.accessor(&bytes, UINT, "SCALAR", idx.len(), false);
    json!({ "attributes": { "POSITION": position }, "indices": indices })
}

/// Runs `decimate ARGS` in `dir`; its stderr, after checking that it succeeded.
fn decimate(dir: &Path, args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("runs decimate");
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{args:?}: {stderr}");
    stderr
}

/// The JSON and binary chunks of a `.glb` file.
fn glb_parts(path: &Path) -> (Value, Vec<u8>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let word = |at: usize| {
        u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]) as usize
    };
    let json_len = word(12);
    let json = serde_json::from_slice(&bytes[20..20 + json_len]).expect("the JSON chunk parses");
    let bin = match bytes.len() > 20 + json_len + 8 {
        true => bytes[28 + json_len..28 + json_len + word(20 + json_len)].to_vec(),
        false => Vec::new(),
    };
    (json, bin)
}

/// The bytes of accessor `a` of a document (tightly packed views, as our files write).
fn accessor_bytes(json: &Value, bin: &[u8], a: &Value) -> Vec<u8> {
    let a = &json["accessors"][a.as_u64().expect("an accessor index") as usize];
    let view = &json["bufferViews"][a["bufferView"].as_u64().expect("a view") as usize];
    let size = match a["componentType"].as_u64() {
        Some(5120 | 5121) => 1,
        Some(5122 | 5123) => 2,
        _ => 4,
    };
    let width = match a["type"].as_str() {
        Some("SCALAR") => 1,
        Some("VEC2") => 2,
        Some("VEC3") => 3,
        Some("VEC4") => 4,
        Some("MAT4") => 16,
        t => panic!("type {t:?}"),
    };
    let at = |v: &Value| v.as_u64().unwrap_or(0) as usize;
    let start = at(&view["byteOffset"]) + at(&a["byteOffset"]);
    bin[start..start + at(&a["count"]) * size * width].to_vec()
}

/// The bytes of buffer view `v` of a document.
fn view_bytes(json: &Value, bin: &[u8], v: &Value) -> Vec<u8> {
    let view = &json["bufferViews"][v.as_u64().expect("a view index") as usize];
    let at = |key: &str| view[key].as_u64().unwrap_or(0) as usize;
    bin[at("byteOffset")..at("byteOffset") + at("byteLength")].to_vec()
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-4
}

#[test]
fn the_node_tree_comes_back_with_its_names_local_transforms_and_children() {
    let dir = scratch("tree");
    let mut d = Doc::new();
    let grid = grid_mesh(&mut d, 10, "grid");
    let turn = Quat::from_rotation_y(0.5);
    let arm =
        Mat4::from_rotation_translation(Quat::from_rotation_z(0.25), Vec3::new(0.0, 4.0, 0.0));
    d.json["nodes"] = json!([
        { "name": "root", "translation": [1, 2, 3], "rotation": turn.to_array(),
          "scale": [2, 2, 2], "children": [1, 3] },
        { "name": "arm", "matrix": arm.to_cols_array(), "children": [2] },
        { "name": "hand", "mesh": grid, "translation": [0.5, 0, 0] },
        { "name": "leaf" },
    ]);
    d.json["scenes"][0]["nodes"] = json!([0]);
    std::fs::write(dir.join("in.glb"), d.glb()).expect("writes");
    assert_valid(&[&dir.join("in.glb")]);
    let input = read_scene(&dir.join("in.glb"))
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    let world_in: Vec<Vec3> = {
        let m = &input.models[0];
        m.positions
            .iter()
            .map(|&p| m.transform.transform_point3(p))
            .collect()
    };
    for out in ["out.glb", "out.gltf"] {
        // Vertex removal never moves a vertex: every output vertex stands where one did.
        decimate(&dir, &["in.glb", "nogui", "-p", "50", "-o", out]);
        let path = dir.join(out);
        assert_valid(&[&path]);
        let bytes = std::fs::read(&path).expect("reads");
        let doc = gltf::Gltf::from_slice(&bytes)
            .unwrap_or_else(|e| panic!("{out}: {e}"))
            .document;
        let nodes: Vec<gltf::Node<'_>> = doc.nodes().collect();
        let names: Vec<Option<&str>> = nodes.iter().map(|n| n.name()).collect();
        assert_eq!(
            names,
            [Some("root"), Some("arm"), Some("hand"), Some("leaf")],
            "{out}"
        );
        let children = |n: &gltf::Node<'_>| n.children().map(|c| c.index()).collect::<Vec<_>>();
        assert_eq!(children(&nodes[0]), [1, 3]);
        assert_eq!(children(&nodes[1]), [2]);
        assert!(children(&nodes[2]).is_empty() && children(&nodes[3]).is_empty());
        let roots: Vec<usize> = doc
            .scenes()
            .next()
            .expect("a scene")
            .nodes()
            .map(|n| n.index())
            .collect();
        assert_eq!(roots, [0]);
        match nodes[0].transform() {
            gltf::scene::Transform::Decomposed {
                translation,
                rotation,
                scale,
            } => {
                assert_eq!(translation, [1.0, 2.0, 3.0]);
                assert_eq!(rotation, turn.to_array());
                assert_eq!(scale, [2.0, 2.0, 2.0]);
            }
            t => panic!("{out}: root's TRS became {t:?}"),
        }
        match nodes[1].transform() {
            gltf::scene::Transform::Matrix { matrix } => {
                assert_eq!(Mat4::from_cols_array_2d(&matrix), arm);
            }
            t => panic!("{out}: arm's matrix became {t:?}"),
        }
        assert!(
            nodes[2].mesh().is_some() && nodes[0].mesh().is_none() && nodes[3].mesh().is_none()
        );
        let back = read_scene(&path).unwrap_or_else(|e| panic!("{e}")).scene;
        assert_eq!(back.models.len(), 1);
        let m = &back.models[0];
        assert_eq!(m.name, "hand");
        assert!(
            m.triangles.len() < 150 && m.triangles.len() > 50,
            "{}",
            m.triangles.len()
        );
        for p in &m.positions {
            let w = m.transform.transform_point3(*p);
            assert!(
                world_in.iter().any(|&q| close(q, w)),
                "{out}: {w} is placed where no vertex was"
            );
        }
    }
}

#[test]
fn a_mesh_three_nodes_place_is_decimated_once_and_written_once() {
    let dir = scratch("instances");
    let mut d = Doc::new();
    let grid = grid_mesh(&mut d, 10, "grid");
    d.json["nodes"] = json!([
        { "name": "a", "mesh": grid },
        { "name": "b", "mesh": grid, "translation": [20, 0, 0] },
        { "name": "c", "mesh": grid, "translation": [0, 20, 0], "scale": [-1, 1, 1] },
    ]);
    d.json["scenes"][0]["nodes"] = json!([0, 1, 2]);
    std::fs::write(dir.join("in.glb"), d.glb()).expect("writes");
    let stderr = decimate(
        &dir,
        &["in.glb", "nogui", "-a", "qem", "-p", "50", "-o", "out.glb"],
    );
    // The summary: b and c say whose result they share, and the total counts the mesh once.
    assert_eq!(stderr.matches("instance of a").count(), 2, "{stderr}");
    let total = stderr
        .lines()
        .find(|l| l.starts_with("total"))
        .expect("a total line");
    assert!(
        total.starts_with(
            "total (each mesh once: 2 more instances not counted): vertices 121 -> 60, \
             triangles 200 -> "
        ),
        "{total}"
    );
    let path = dir.join("out.glb");
    assert_valid(&[&path]);
    let (json, _) = glb_parts(&path);
    assert_eq!(json["meshes"].as_array().map(Vec::len), Some(1), "one mesh");
    for n in 0..3 {
        assert_eq!(
            json["nodes"][n]["mesh"],
            json!(0),
            "node {n} places the mesh"
        );
    }
    let back = read_scene(&path).unwrap_or_else(|e| panic!("{e}")).scene;
    assert_eq!(back.models.len(), 3);
    let a = &back.models[0];
    assert_eq!(a.positions.len(), 60);
    for m in &back.models[1..] {
        assert_eq!(
            (&m.positions, &m.triangles),
            (&a.positions, &a.triangles),
            "{}",
            m.name
        );
    }
    let placed = |m: &decimate_core::mesh::Model| m.transform.transform_point3(m.positions[0]);
    assert!(close(
        placed(&back.models[1]) - placed(a),
        Vec3::new(20.0, 0.0, 0.0)
    ));
}

/// A skinned grid (every vertex bound to one joint that an animation moves) and a triangle
/// with a morph target, beside a plain grid, as one `.glb`.
fn skinned_and_morphed() -> Doc {
    let mut d = Doc::new();
    let mut skinned = grid_primitive(&mut d, 4);
    let n = 25;
    let joints = d.accessor(&[0u8; 4].repeat(n), UBYTE, "VEC4", n, false);
    let weights = d.floats(&[1.0, 0.0, 0.0, 0.0].repeat(n), "VEC4", 4);
    skinned["attributes"]["JOINTS_0"] = json!(joints);
    skinned["attributes"]["WEIGHTS_0"] = json!(weights);
    let body = d.push("meshes", json!({ "name": "body", "primitives": [skinned] }));
    let base = d.positions(&[0., 0., 0., 1., 0., 0., 0., 1., 0.]);
    let delta = d.positions(&[0., 0., 1., 0., 0., 0.5, 0., 0., 0.]);
    // A sparse target: zeros but for vertex 2, lifted by 0.75.
    let (si, sv) = (d.view(&[2]), d.view(&0.75f32.to_le_bytes().repeat(3)));
    let sparse = d.push(
        "accessors",
        json!({ "componentType": FLOAT, "count": 3, "type": "VEC3",
                "min": [0, 0, 0], "max": [0.75, 0.75, 0.75],
                "sparse": { "count": 1, "indices": { "bufferView": si, "componentType": UBYTE },
                            "values": { "bufferView": sv } } }),
    );
    let blob = d.push(
        "meshes",
        json!({ "name": "blob", "weights": [0.5, 0.0],
                "primitives": [{ "attributes": { "POSITION": base },
                                 "targets": [{ "POSITION": delta }, { "POSITION": sparse }] }] }),
    );
    let plain = grid_mesh(&mut d, 10, "plain");
    let ibm = d.floats(&Mat4::IDENTITY.to_cols_array(), "MAT4", 16);
    let times = d.floats(&[0.0, 1.0], "SCALAR", 1);
    d.json["accessors"][times]["min"] = json!([0.0]);
    d.json["accessors"][times]["max"] = json!([1.0]);
    let moves = d.floats(&[0., 0., 0., 0., 0., 2.], "VEC3", 3);
    let weights_over_time = d.floats(&[0.0, 0.0, 1.0, 0.5], "SCALAR", 1);
    d.json["nodes"] = json!([
        { "name": "armature", "children": [1, 2] },
        { "name": "body", "mesh": body, "skin": 0 },
        { "name": "bone" },
        { "name": "blob", "mesh": blob, "weights": [0.25, 0.0], "translation": [5, 0, 0] },
        { "name": "plain", "mesh": plain, "translation": [0, 10, 0] },
    ]);
    d.json["scenes"][0]["nodes"] = json!([0, 3, 4]);
    d.json["skins"] = json!([{ "joints": [2], "inverseBindMatrices": ibm, "skeleton": 0 }]);
    d.json["animations"] = json!([{
        "name": "wave",
        "samplers": [
            { "input": times, "output": moves },
            { "input": times, "output": weights_over_time },
        ],
        "channels": [
            { "sampler": 0, "target": { "node": 2, "path": "translation" } },
            { "sampler": 1, "target": { "node": 3, "path": "weights" } },
        ],
    }]);
    d.json["materials"] = json!([{
        "name": "skin-paint",
        "pbrMetallicRoughness": { "baseColorFactor": [1, 0.5, 0.5, 1] },
    }]);
    d.json["meshes"][body]["primitives"][0]["material"] = json!(0);
    d
}

#[test]
fn skinned_and_morphed_meshes_come_back_unchanged_with_their_skin_targets_and_animation() {
    let dir = scratch("skin");
    let d = skinned_and_morphed();
    std::fs::write(dir.join("in.glb"), d.glb()).expect("writes");
    assert_valid(&[&dir.join("in.glb")]);
    let stderr = decimate(
        &dir,
        &["in.glb", "nogui", "-a", "qem", "-p", "50", "-o", "out.glb"],
    );
    // One warning naming each mesh copied through.
    let warned = |what: &str| {
        stderr
            .lines()
            .filter(|l| l.contains("warning") && l.contains(what))
            .count()
    };
    assert_eq!(
        warned("mesh 0 'body' is skinned: copied through unchanged"),
        1,
        "{stderr}"
    );
    assert_eq!(
        warned("mesh 1 'blob' has morph targets: copied through unchanged"),
        1,
        "{stderr}"
    );
    let path = dir.join("out.glb");
    assert_valid(&[&path]);
    let (out, bin) = glb_parts(&path);
    let (src, src_bin) = (&d.json, &d.bin);
    let same = |a: &Value, b: &Value, what: &str| {
        assert_eq!(
            accessor_bytes(&out, &bin, a),
            accessor_bytes(src, src_bin, b),
            "{what}"
        );
    };
    // The nodes keep their indices: the skin's joint and the animation's targets still hold.
    assert_eq!(out["nodes"][1]["skin"], json!(0));
    assert_eq!(out["nodes"][3]["weights"], json!([0.25, 0.0]));
    let body = &out["meshes"][out["nodes"][1]["mesh"].as_u64().expect("body's mesh") as usize];
    let (p, q) = (&body["primitives"][0], &src["meshes"][0]["primitives"][0]);
    for key in ["POSITION", "JOINTS_0", "WEIGHTS_0"] {
        same(&p["attributes"][key], &q["attributes"][key], key);
    }
    same(&p["indices"], &q["indices"], "body's indices");
    let material = &out["materials"][p["material"].as_u64().expect("a material") as usize];
    assert_eq!(
        material["pbrMetallicRoughness"]["baseColorFactor"],
        json!([1.0, 0.5, 0.5, 1.0])
    );
    let skin = &out["skins"][0];
    assert_eq!(skin["joints"], json!([2]));
    assert_eq!(skin["skeleton"], json!(0));
    same(
        &skin["inverseBindMatrices"],
        &src["skins"][0]["inverseBindMatrices"],
        "inverse bind matrices",
    );
    let blob = &out["meshes"][out["nodes"][3]["mesh"].as_u64().expect("blob's mesh") as usize];
    assert_eq!(blob["weights"], json!([0.5, 0.0]));
    let (p, q) = (&blob["primitives"][0], &src["meshes"][1]["primitives"][0]);
    same(
        &p["attributes"]["POSITION"],
        &q["attributes"]["POSITION"],
        "blob's positions",
    );
    same(
        &p["targets"][0]["POSITION"],
        &q["targets"][0]["POSITION"],
        "the morph target",
    );
    let sparse = |json: &Value, bin: &[u8], p: &Value| {
        let a =
            &json["accessors"][p["targets"][1]["POSITION"].as_u64().expect("an index") as usize];
        assert!(a.get("bufferView").is_none(), "still sparse: {a}");
        let s = &a["sparse"];
        let idx = view_bytes(json, bin, &s["indices"]["bufferView"]);
        (
            s["count"].clone(),
            idx,
            view_bytes(json, bin, &s["values"]["bufferView"]),
        )
    };
    assert_eq!(
        sparse(&out, &bin, p),
        sparse(src, src_bin, q),
        "the sparse target"
    );
    let (anim, src_anim) = (&out["animations"][0], &src["animations"][0]);
    assert_eq!(anim["channels"], src_anim["channels"]);
    for s in 0..2 {
        for key in ["input", "output"] {
            same(
                &anim["samplers"][s][key],
                &src_anim["samplers"][s][key],
                "animation samplers",
            );
        }
    }
    // The plain grid beside them is decimated.
    let plain = &out["meshes"][out["nodes"][4]["mesh"].as_u64().expect("plain's mesh") as usize];
    let count = &out["accessors"]
        [plain["primitives"][0]["indices"].as_u64().expect("indices") as usize]["count"];
    assert!(
        count.as_u64().is_some_and(|c| c < 600 / 2 + 60),
        "plain has {count} corners"
    );
    // As .gltf the same travels in its .bin; another format keeps the rest pose, and says so.
    decimate(
        &dir,
        &["in.glb", "nogui", "-a", "qem", "-p", "50", "-o", "out.gltf"],
    );
    assert_valid(&[&dir.join("out.gltf")]);
    let text = std::fs::read(dir.join("out.gltf")).expect("reads");
    let text: Value = serde_json::from_slice(&text).expect("the .gltf parses");
    assert_eq!(
        (&text["skins"], &text["animations"]),
        (&out["skins"], &out["animations"])
    );
    let stderr = decimate(&dir, &["in.glb", "nogui", "-p", "50", "-o", "out.ply"]);
    assert!(
        stderr.contains("warning: out.ply: the source's skins, morph targets and animations"),
        "{stderr}"
    );
}

#[test]
fn a_texture_image_a_glb_cannot_hold_is_named_in_a_warning() {
    let dir = scratch("lost-image");
    let mut d = Doc::new();
    let mut prims = Vec::new();
    for image in 0..2 {
        let mut prim = grid_primitive(&mut d, 4);
        let uv: Vec<f32> = (0..25)
            .flat_map(|i| [(i % 5) as f32 / 4.0, (i / 5) as f32 / 4.0])
            .collect();
        prim["attributes"]["TEXCOORD_0"] = json!(d.floats(&uv, "VEC2", 2));
        prim["material"] = json!(image);
        prims.push(prim);
    }
    d.mesh_node(prims, json!({ "name": "pair" }));
    d.json["images"] = json!([{ "uri": "gone.png" }, { "uri": "notes.png" }]);
    d.json["textures"] = json!([{ "source": 0 }, { "source": 1 }]);
    d.json["materials"] = json!([
        { "pbrMetallicRoughness": { "baseColorTexture": { "index": 0 } } },
        { "pbrMetallicRoughness": { "baseColorTexture": { "index": 1 } } },
    ]);
    std::fs::write(dir.join("notes.png"), "not an image").expect("writes");
    std::fs::write(dir.join("in.bin"), &d.bin).expect("writes");
    let text = serde_json::to_vec(&d.with_buffer(Some("in.bin".into()))).expect("json");
    std::fs::write(dir.join("in.gltf"), text).expect("writes");
    let stderr = decimate(
        &dir,
        &["in.gltf", "nogui", "-q", "-p", "0", "-o", "out.glb"],
    );
    let warning = |name: &str, why: &str| {
        stderr
            .lines()
            .any(|l| l.contains("warning") && l.contains(name) && l.contains(why))
    };
    assert!(warning("'gone.png'", "gone.png: "), "{stderr}");
    assert!(
        warning("'notes.png'", "not a PNG or JPEG image"),
        "{stderr}"
    );
    assert_valid(&[&dir.join("out.glb")]);
}
