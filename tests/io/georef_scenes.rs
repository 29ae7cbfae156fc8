//! Georeferenced scenes: the scan patch of `georef` written as VRML 1.0, VRML 2.0,
//! Inventor and glTF, far from zero either by its points or by a transform that moves small
//! points there (a Translation, a Transform, a glTF node's translation, CESIUM_RTC's centre),
//! decimated by the binary with both algorithms. The far runs' OBJ outputs, read back in f64
//! and moved back, must be the origin run's, with an f64 Hausdorff error at most 1.1 times
//! the origin run's. With f32 transforms and points, the patch at y = 1.2e6 was moved by up
//! to 0.06 by rounding alone.

use std::fmt::Write as _;
use std::path::Path;

use crate::georef::{
    assert_lands_like_the_origin_run, decimated_moved_back, grid_patch, hausdorff, patch,
    read_output, sub, write_input, Mesh, FAR,
};
use crate::support::binary::decimate;

/// How the patch is written: which format, and whether the translation is in its points or
/// in a transform above small points.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Form {
    Vrml2Points,
    Vrml2Transform,
    Vrml1Points,
    InventorTranslation,
    InventorVertexProperty,
    GltfNode,
    GlbNode,
    GltfRtc,
}

impl Form {
    fn file(self) -> &'static str {
        match self {
            Self::Vrml2Points | Self::Vrml2Transform | Self::Vrml1Points => "patch.wrl",
            Self::InventorTranslation | Self::InventorVertexProperty => "patch.iv",
            Self::GltfNode | Self::GltfRtc => "patch.gltf",
            Self::GlbNode => "patch.glb",
        }
    }

    /// Whether the points themselves carry the translation.
    fn in_points(self) -> bool {
        matches!(
            self,
            Self::Vrml2Points | Self::Vrml1Points | Self::InventorVertexProperty
        )
    }
}

fn point_list(m: &Mesh, t: [f64; 3]) -> String {
    let mut s = String::new();
    for p in &m.points {
        let _ = writeln!(s, "{} {} {},", p[0] + t[0], p[1] + t[1], p[2] + t[2]);
    }
    s
}

fn index_list(m: &Mesh) -> String {
    let mut s = String::new();
    for [a, b, c] in &m.triangles {
        let _ = writeln!(s, "{a}, {b}, {c}, -1,");
    }
    s
}

/// The patch at `t` in one of the text scene forms.
fn scene_text(form: Form, t: [f64; 3]) -> String {
    let m = patch([0.0; 3]);
    let (points, indices) = match form.in_points() {
        true => (point_list(&m, t), index_list(&m)),
        false => (point_list(&m, [0.0; 3]), index_list(&m)),
    };
    let [x, y, z] = t;
    match form {
        Form::Vrml2Points => format!(
            "#VRML V2.0 utf8\nShape {{ geometry IndexedFaceSet {{ solid FALSE\n\
             coord Coordinate {{ point [ {points} ] }}\ncoordIndex [ {indices} ] }} }}\n"
        ),
        Form::Vrml2Transform => format!(
            "#VRML V2.0 utf8\nTransform {{ translation {x} {y} {z} children [\n\
             Shape {{ geometry IndexedFaceSet {{ solid FALSE\n\
             coord Coordinate {{ point [ {points} ] }}\ncoordIndex [ {indices} ] }} }} ] }}\n"
        ),
        Form::Vrml1Points => format!(
            "#VRML V1.0 ascii\nSeparator {{ Coordinate3 {{ point [ {points} ] }}\n\
             IndexedFaceSet {{ coordIndex [ {indices} ] }} }}\n"
        ),
        Form::InventorTranslation => format!(
            "#Inventor V2.1 ascii\nSeparator {{ Translation {{ translation {x} {y} {z} }}\n\
             Coordinate3 {{ point [ {points} ] }}\n\
             IndexedFaceSet {{ coordIndex [ {indices} ] }} }}\n"
        ),
        _ => format!(
            "#Inventor V2.1 ascii\nSeparator {{ IndexedFaceSet {{\n\
             vertexProperty VertexProperty {{ vertex [ {points} ] }}\n\
             coordIndex [ {indices} ] }} }}\n"
        ),
    }
}

/// The patch's points (f32, at the origin) and triangles as a glTF buffer, and its JSON
/// with the translation `t` in the node or in CESIUM_RTC's centre.
fn gltf(form: Form, t: [f64; 3], uri: Option<&str>) -> (serde_json::Value, Vec<u8>) {
    let m = patch([0.0; 3]);
    let mut bin = Vec::new();
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for p in &m.points {
        for k in 0..3 {
            let v = p[k] as f32;
            (lo[k], hi[k]) = (lo[k].min(v), hi[k].max(v));
            bin.extend_from_slice(&v.to_le_bytes());
        }
    }
    let positions = bin.len();
    for t in &m.triangles {
        t.iter()
            .for_each(|&v| bin.extend_from_slice(&(v as u32).to_le_bytes()));
    }
    let mut buffer = serde_json::json!({ "byteLength": bin.len() });
    if let Some(uri) = uri {
        buffer["uri"] = serde_json::json!(uri);
    }
    let mut node = serde_json::json!({ "mesh": 0 });
    if form != Form::GltfRtc {
        node["translation"] = serde_json::json!(t);
    }
    let mut json = serde_json::json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [node],
        "meshes": [{ "primitives": [{ "attributes": { "POSITION": 0 }, "indices": 1 }] }],
        "buffers": [buffer],
        "bufferViews": [
            { "buffer": 0, "byteLength": positions },
            { "buffer": 0, "byteOffset": positions, "byteLength": bin.len() - positions }
        ],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": m.points.len(),
              "type": "VEC3", "min": lo, "max": hi },
            { "bufferView": 1, "componentType": 5125, "count": 3 * m.triangles.len(),
              "type": "SCALAR" }
        ]
    });
    if form == Form::GltfRtc {
        json["extensionsUsed"] = serde_json::json!(["CESIUM_RTC"]);
        json["extensions"] = serde_json::json!({ "CESIUM_RTC": { "center": t } });
    }
    (json, bin)
}

/// A GLB container: the JSON chunk padded with spaces, the BIN chunk with zeros.
fn glb(json: &serde_json::Value, mut bin: Vec<u8>) -> Vec<u8> {
    let mut text = serde_json::to_vec(json).unwrap();
    while !text.len().is_multiple_of(4) {
        text.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let total = 12 + 8 + text.len() + 8 + bin.len();
    let mut out = Vec::new();
    for word in [0x4654_6c67, 2, total as u32, text.len() as u32, 0x4e4f_534a] {
        out.extend_from_slice(&u32::to_le_bytes(word));
    }
    out.extend_from_slice(&text);
    for word in [bin.len() as u32, 0x004e_4942] {
        out.extend_from_slice(&u32::to_le_bytes(word));
    }
    out.extend_from_slice(&bin);
    out
}

fn write_scene(form: Form, t: [f64; 3], dir: &Path) {
    let path = dir.join(form.file());
    match form {
        Form::GltfNode | Form::GltfRtc => {
            let (json, bin) = gltf(form, t, Some("patch.bin"));
            std::fs::write(dir.join("patch.bin"), bin).unwrap();
            std::fs::write(path, serde_json::to_vec(&json).unwrap()).unwrap();
        }
        Form::GlbNode => {
            let (json, bin) = gltf(form, t, None);
            std::fs::write(path, glb(&json, bin)).unwrap();
        }
        _ => std::fs::write(path, scene_text(form, t)).unwrap(),
    }
}

/// Runs the binary on the scene at `t` and returns its OBJ output moved back by `t`.
fn run(dir: &Path, form: Form, t: [f64; 3], algorithm: &[&str]) -> Mesh {
    write_scene(form, t, dir);
    decimated_moved_back(dir, form.file(), "out.obj", t, algorithm)
}

#[test]
fn far_scenes_decimate_as_they_do_at_the_origin_in_vrml_inventor_and_gltf() {
    let dir = tempfile::tempdir().unwrap();
    let input = patch([0.0; 3]);
    for form in [
        Form::Vrml2Points,
        Form::Vrml2Transform,
        Form::Vrml1Points,
        Form::InventorTranslation,
        Form::InventorVertexProperty,
        Form::GltfNode,
        Form::GlbNode,
        Form::GltfRtc,
    ] {
        for algorithm in [&[][..], &["-a", "qem"][..]] {
            let what = format!("{form:?} {algorithm:?}");
            let near = run(dir.path(), form, [0.0; 3], algorithm);
            assert!(
                near.triangles.len() > 250 && near.triangles.len() < 500,
                "{what}: {} triangles",
                near.triangles.len()
            );
            for t in FAR {
                let far = run(dir.path(), form, t, algorithm);
                assert_lands_like_the_origin_run(&format!("{what} at {t:?}"), &input, &near, &far);
            }
        }
    }
}

/// `decimate patch.ply nogui --tiles 4 -p 80 --memory 400K` on a finer patch at `t`: the
/// output (binary PLY) moved back by `t`, and what the run said.
fn tiled(dir: &Path, t: [f64; 3]) -> (Mesh, String) {
    write_input(&grid_patch(65, t), &dir.join("patch.ply"));
    let out = decimate(
        dir,
        &[
            "patch.ply",
            "nogui",
            "--tiles",
            "4",
            "-p",
            "80",
            "--memory",
            "400K",
            "-o",
            "out.ply",
        ],
    );
    let said = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "at {t:?}: {said}");
    let mut m = read_output(&dir.join("out.ply"));
    for p in &mut m.points {
        *p = sub(*p, t);
    }
    (m, said)
}

#[test]
fn a_far_patch_tiled_within_a_small_memory_budget_lands_where_the_origin_run_does() {
    let dir = tempfile::tempdir().unwrap();
    let input = grid_patch(65, [0.0; 3]);
    let (near, said) = tiled(dir.path(), [0.0; 3]);
    // 8192 triangles to 1638: the welded tiles (twice that) are over 400K and cut again.
    assert_eq!(near.triangles.len(), 1638);
    assert!(said.contains("cutting them again"), "{said}");
    for t in FAR {
        let (far, _) = tiled(dir.path(), t);
        assert_lands_like_the_origin_run(&format!("tiled at {t:?}"), &input, &near, &far);
    }
}

#[test]
fn a_far_gltf_written_as_gltf_stays_where_it_stood() {
    let dir = tempfile::tempdir().unwrap();
    let input = patch([0.0; 3]);
    for form in [Form::GltfNode, Form::GltfRtc] {
        let near = run(dir.path(), form, [0.0; 3], &[]);
        let near_error = hausdorff(&input, &near);
        let t = FAR[0];
        write_scene(form, t, dir.path());
        for args in [
            &[form.file(), "nogui", "-p", "80", "-o", "out.gltf"][..],
            &["out.gltf", "nogui", "-p", "0", "-o", "back.obj"][..],
        ] {
            let out = decimate(dir.path(), args);
            let said = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{form:?} {args:?}: {said}");
        }
        let mut back = read_output(&dir.path().join("back.obj"));
        for p in &mut back.points {
            *p = sub(*p, t);
        }
        let error = hausdorff(&input, &back);
        assert!(
            error <= 1.1 * near_error,
            "{form:?}: error {error} against {near_error} at the origin"
        );
    }
}
