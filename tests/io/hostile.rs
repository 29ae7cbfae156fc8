//! Hostile inputs built on the fly, run through the binary: each is refused with a clear
//! error naming the file and a non-zero exit, and returns (no hang, no memory exhaustion).
//! Node chains and cycles 100,000 deep, a node graph that doubles at each of 24 levels,
//! meshes placed by many nodes, a FIFO and a link to /dev/zero named like meshes, a gzip
//! bomb, files over the byte limit, and references that leave the model's folder.

use std::path::Path;
use std::process::{Command, Output};

use serde_json::{json, Value};

/// Runs `decimate ARGS` in `dir` with the environment `env` added.
fn run(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(args)
        .env_remove("DECIMATE_ALLOW_OUTSIDE")
        .env_remove("DECIMATE_MAX_FILE_BYTES")
        .env_remove("DECIMATE_MAX_TRIANGLES")
        .envs(env.iter().copied())
        .current_dir(dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run decimate: {e}"))
}

/// Asserts `o` failed with exit 1 and an error that names `file` and says `what`.
fn refused(o: &Output, file: &str, what: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains(file), "the error does not name {file}: {err}");
    assert!(err.contains(what), "the error does not say '{what}': {err}");
}

/// Decimates `file` in `dir` to `out.ply`.
fn decimate(dir: &Path, file: &str, env: &[(&str, &str)]) -> Output {
    run(dir, &[file, "nogui", "-q", "-p", "0", "-o", "out.ply"], env)
}

/// A GLB of `nodes` and `scene_nodes` whose mesh 0 is a triangle list: three vertices and
/// `triangles` × (0 1 2) as 16-bit indices.
fn glb(nodes: Value, scene_nodes: Value, triangles: usize) -> Vec<u8> {
    glb_with(nodes, scene_nodes, triangles, |_| {})
}

/// [`glb`] with its JSON changed by `edit` before it is packed.
pub(crate) fn glb_with(
    nodes: Value,
    scene_nodes: Value,
    triangles: usize,
    edit: impl FnOnce(&mut Value),
) -> Vec<u8> {
    let mut bin = Vec::new();
    for v in [0f32, 0., 0., 1., 0., 0., 0., 1., 0.] {
        bin.extend(v.to_le_bytes());
    }
    for _ in 0..triangles {
        for i in [0u16, 1, 2] {
            bin.extend(i.to_le_bytes());
        }
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let index_bytes = triangles * 6;
    let json = json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": scene_nodes }],
        "nodes": nodes,
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [{ "byteLength": bin.len() }],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": index_bytes }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5123, "count": triangles * 3, "type": "SCALAR" }
        ]
    });
    let mut json = json;
    edit(&mut json);
    let mut text = serde_json::to_vec(&json).unwrap();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend(b"glTF");
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((text.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&text);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(&bin);
    out
}

#[test]
fn a_node_chain_100000_deep_is_read_and_a_100000_node_cycle_refused() {
    let dir = tempfile::tempdir().unwrap();
    let n = 100_000;
    let chain: Vec<Value> = (0..n)
        .map(|i| match i + 1 < n {
            true => json!({ "children": [i + 1] }),
            false => json!({ "mesh": 0 }),
        })
        .collect();
    std::fs::write(
        dir.path().join("deep.glb"),
        glb(json!(chain), json!([0]), 1),
    )
    .unwrap();
    let o = run(
        dir.path(),
        &["deep.glb", "nogui", "-p", "0", "-o", "deep.ply"],
        &[],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let back = decimate_core::io::read_scene(&dir.path().join("deep.ply")).unwrap();
    assert_eq!(
        back.scene.triangle_count(),
        1,
        "the deepest node's triangle"
    );

    let cycle: Vec<Value> = (0..n)
        .map(|i| json!({ "children": [(i + 1) % n], "mesh": 0 }))
        .collect();
    std::fs::write(
        dir.path().join("cycle.glb"),
        glb(json!(cycle), json!([0]), 1),
    )
    .unwrap();
    refused(
        &decimate(dir.path(), "cycle.glb", &[]),
        "cycle.glb",
        "is its own ancestor",
    );
}

#[test]
fn a_node_graph_doubling_24_times_is_refused_not_expanded() {
    let dir = tempfile::tempdir().unwrap();
    let levels = 24;
    let dag: Vec<Value> = (0..=levels)
        .map(|i| match i < levels {
            true => json!({ "children": [i + 1, i + 1] }),
            false => json!({ "mesh": 0 }),
        })
        .collect();
    std::fs::write(dir.path().join("dag.glb"), glb(json!(dag), json!([0]), 1)).unwrap();
    refused(
        &decimate(dir.path(), "dag.glb", &[]),
        "dag.glb",
        "a glTF node has one parent at most",
    );
}

#[test]
fn meshes_placed_by_many_nodes_are_capped_relative_to_the_file() {
    let dir = tempfile::tempdir().unwrap();
    // 65,536 triangles (about 400 KB) placed by 128 nodes: 8.4 million triangles, more
    // than 16 per byte of the file.
    let nodes: Vec<Value> = (0..128).map(|_| json!({ "mesh": 0 })).collect();
    let roots: Vec<usize> = (0..128).collect();
    std::fs::write(
        dir.path().join("many.glb"),
        glb(json!(nodes), json!(roots), 65_536),
    )
    .unwrap();
    refused(
        &decimate(dir.path(), "many.glb", &[]),
        "many.glb",
        "DECIMATE_MAX_TRIANGLES",
    );
    // The documented override lets it through.
    let o = decimate(
        dir.path(),
        "many.glb",
        &[("DECIMATE_MAX_TRIANGLES", "9000000")],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[cfg(unix)]
#[test]
fn a_fifo_and_a_link_to_dev_zero_are_refused_before_they_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let fifo = dir.path().join("x.ply");
    let made = Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo failed");
    refused(&decimate(dir.path(), "x.ply", &[]), "x.ply", "a FIFO");
    // Tiling streams its input: the FIFO is refused there too.
    let o = run(
        dir.path(),
        &["tile", "plan", "x.ply", "--work", "w", "-p", "50"],
        &[],
    );
    refused(&o, "x.ply", "a FIFO");

    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.obj")).unwrap();
    refused(
        &decimate(dir.path(), "zero.obj", &[]),
        "zero.obj",
        "not a regular file (a device)",
    );
    // An OBJ whose material library is the link.
    std::os::unix::fs::symlink("/dev/zero", dir.path().join("zero.mtl")).unwrap();
    std::fs::write(
        dir.path().join("m.obj"),
        "mtllib zero.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    refused(
        &decimate(dir.path(), "m.obj", &[]),
        "m.obj",
        "zero.mtl: not a regular file (a device)",
    );
}

#[test]
fn a_gzip_bomb_and_a_file_over_the_byte_limit_are_refused() {
    use std::io::Write;
    let dir = tempfile::tempdir().unwrap();
    // 64 MiB of zeros after a PLY header: a few kilobytes compressed.
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::best());
    gz.write_all(b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n")
        .unwrap();
    let zeros = vec![0u8; 1 << 20];
    for _ in 0..64 {
        gz.write_all(&zeros).unwrap();
    }
    let bomb = gz.finish().unwrap();
    assert!(bomb.len() < 200_000);
    std::fs::write(dir.path().join("bomb.ply.gz"), &bomb).unwrap();
    let limit = [("DECIMATE_MAX_FILE_BYTES", "16M")];
    refused(
        &decimate(dir.path(), "bomb.ply.gz", &limit),
        "bomb.ply.gz",
        "inflates to more than 16777216 bytes",
    );

    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    std::fs::write(dir.path().join("small.ply"), ply).unwrap();
    refused(
        &decimate(
            dir.path(),
            "small.ply",
            &[("DECIMATE_MAX_FILE_BYTES", "100")],
        ),
        "small.ply",
        "over the limit of 100 bytes",
    );
    let o = decimate(dir.path(), "small.ply", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn references_outside_the_models_folder_are_refused_unless_allowed() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("model");
    std::fs::create_dir(&dir).unwrap();
    // A valid buffer one folder up, so only the rule refuses it.
    let base = glb(json!([{ "mesh": 0 }]), json!([0]), 1);
    let bin = &base[base.len() - 48..];
    std::fs::write(root.path().join("up.bin"), bin).unwrap();
    let gltf_with = |uri: &str| {
        let glb_json_len = u32::from_le_bytes([base[12], base[13], base[14], base[15]]) as usize;
        let mut doc: Value = serde_json::from_slice(&base[20..20 + glb_json_len]).unwrap();
        doc["buffers"][0]["uri"] = json!(uri);
        serde_json::to_vec(&doc).unwrap()
    };
    for (name, uri, what) in [
        ("up.gltf", "../up.bin", "outside the model's folder"),
        ("abs.gltf", "/etc/passwd", "outside the model's folder"),
        ("uri.gltf", "file:///etc/passwd", "is a file: URI"),
    ] {
        std::fs::write(dir.join(name), gltf_with(uri)).unwrap();
        refused(&decimate(&dir, name, &[]), name, what);
    }
    // An image URI is a file the viewer and a glTF output would read.
    let mut doc: Value = serde_json::from_slice(&gltf_with("../up.bin")).unwrap();
    doc["buffers"][0]["uri"] = json!("up.bin");
    doc["images"] = json!([{ "uri": "file:///etc/passwd" }]);
    std::fs::copy(root.path().join("up.bin"), dir.join("up.bin")).unwrap();
    std::fs::write(dir.join("img.gltf"), serde_json::to_vec(&doc).unwrap()).unwrap();
    refused(
        &decimate(&dir, "img.gltf", &[]),
        "img.gltf",
        "images[0].uri",
    );
    let allowed = decimate(&dir, "up.gltf", &[("DECIMATE_ALLOW_OUTSIDE", "1")]);
    assert!(
        allowed.status.success(),
        "{}",
        String::from_utf8_lossy(&allowed.stderr)
    );
    std::fs::write(
        dir.join("m.obj"),
        "mtllib ../../../etc/passwd\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
    )
    .unwrap();
    refused(
        &decimate(&dir, "m.obj", &[]),
        "m.obj",
        "outside the model's folder",
    );
}

#[test]
fn ply_faces_beyond_the_headers_count_are_said_and_negative_indices_shown_negative() {
    let dir = tempfile::tempdir().unwrap();
    let ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
               property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
               end_header\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";
    std::fs::write(dir.path().join("extra.ply"), ply).unwrap();
    let o = decimate(dir.path(), "extra.ply", &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("faces beyond the header's count"),
        "-q keeps it: {err}"
    );

    let wrl = "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0 ] }\n coordIndex [ 0 1 2 -1 1 3 2 -1 ]\n color Color { color [ 1 0 0 ] }\n colorPerVertex FALSE\n colorIndex [ 0 -1 ] } }";
    let out = decimate_core::io::parse_str(wrl, "c.wrl").unwrap();
    let said: Vec<String> = out.warnings.iter().map(|w| w.to_string()).collect();
    assert!(said.iter().any(|w| w.contains("index -1")), "{said:?}");
    assert!(!said.iter().any(|w| w.contains("4294967295")), "{said:?}");
}
