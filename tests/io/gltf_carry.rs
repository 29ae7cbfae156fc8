//! What a glTF scene holds beside its triangle meshes comes back from `decimate` unchanged,
//! as a Blender or three.js user expects: the camera and its node, the point light
//! (KHR_lights_punctual) and its node, `extras` on the asset, scene, node, mesh and
//! material, a LINES primitive beside the decimated triangles (same positions and
//! indices), a material extension that names no texture with the emissive factor it
//! scales. What is left out is named in a warning. Outputs are read back with the gltf
//! crate and pass the Khronos validator.

use std::path::Path;

use serde_json::{json, Value};

use super::gltf::{assert_valid, red_over_blue_png, scratch, wavy_grid_arrays, Doc, UINT, USHORT};
use crate::support::binary;

/// An `n × n` grid of unit squares with a wave in z (every vertex can be removed) and
/// texture coordinates, as a triangle primitive of `d` using material 0.
fn wavy_grid(d: &mut Doc, n: u32) -> Value {
    let (pos, idx) = wavy_grid_arrays(n, 0.6);
    let position = d.positions(&pos);
    let uv: Vec<f32> = pos
        .chunks(3)
        .flat_map(|p| [p[0] / n as f32, p[1] / n as f32])
        .collect();
    let uv = d.floats(&uv, "VEC2", 2);
    let bytes: Vec<u8> = idx.iter().flat_map(|i| i.to_le_bytes()).collect();
    let indices = d.accessor(&bytes, UINT, "SCALAR", idx.len(), false);
    json!({ "attributes": { "POSITION": position, "TEXCOORD_0": uv }, "indices": indices,
            "material": 0 })
}

/// A 10 × 10 grid (121 vertices, 200 triangles) with a LINES primitive outlining a frame
/// above it, a perspective camera and a point light on their own nodes, extras everywhere
/// the writer writes them, a material extension without a texture (carried), one with a
/// texture and a made-up node extension (left out, named).
fn scene_with_everything() -> Doc {
    let mut d = Doc::new();
    let triangles = wavy_grid(&mut d, 10);
    let frame = [0., 0., 1., 10., 0., 1., 10., 10., 1., 0., 10., 1.];
    let position = d.positions(&frame);
    let corners: Vec<u8> = [0u16, 1, 1, 2, 2, 3, 3, 0]
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .collect();
    let indices = d.accessor(&corners, USHORT, "SCALAR", 8, false);
    let lines = json!({ "attributes": { "POSITION": position }, "indices": indices,
                        "mode": 1, "material": 1, "extras": { "stroke": "dashed" } });
    d.json["meshes"] = json!([{ "name": "terrain", "primitives": [triangles, lines],
                                "extras": { "lod": 0, "tags": ["ground", "wavy"] } }]);
    let png = d.view(&red_over_blue_png());
    d.json["images"] = json!([{ "bufferView": png, "mimeType": "image/png" }]);
    d.json["textures"] = json!([{ "source": 0 }]);
    d.json["materials"] = json!([
        { "name": "grass", "pbrMetallicRoughness": { "baseColorFactor": [0.2, 0.8, 0.2, 1] },
          "emissiveFactor": [1, 1, 1],
          "extensions": {
              "KHR_materials_emissive_strength": { "emissiveStrength": 2.5 },
              "KHR_materials_clearcoat": { "clearcoatFactor": 1.0,
                                           "clearcoatTexture": { "index": 0 } },
          },
          "extras": { "shader": "toon" } },
        { "name": "ink", "pbrMetallicRoughness": { "baseColorFactor": [1, 0, 0, 1] } },
    ]);
    d.json["cameras"] = json!([{
        "name": "eye", "type": "perspective", "extras": { "rig": "dolly" },
        "perspective": { "yfov": 0.75, "znear": 0.05, "zfar": 250.0, "aspectRatio": 1.5 },
    }]);
    d.json["extensions"] = json!({ "KHR_lights_punctual": { "lights": [
        { "name": "bulb", "type": "point", "color": [1.0, 0.5, 0.25], "intensity": 40.0,
          "range": 12.0 },
    ] } });
    d.json["extensionsUsed"] = json!([
        "KHR_lights_punctual",
        "KHR_materials_emissive_strength",
        "KHR_materials_clearcoat",
        "EXT_made_up_tag",
    ]);
    d.json["nodes"] = json!([
        { "name": "camera-holder", "camera": 0, "translation": [5, -8, 6],
          "extras": { "role": "view" } },
        { "name": "lamp", "translation": [5, 5, 4],
          "extensions": { "KHR_lights_punctual": { "light": 0 },
                          "EXT_made_up_tag": { "tag": 3 } } },
        { "name": "terrain", "mesh": 0, "extras": { "id": 7 } },
    ]);
    d.json["scenes"] = json!([{ "name": "Level", "nodes": [0, 1, 2],
                                "extras": { "level": "one" } }]);
    d.json["asset"] = json!({ "version": "2.0", "copyright": "CC0 test",
                              "extras": { "author": "gltf_carry" } });
    d
}

/// Runs `decimate ARGS` in `dir`; its stderr, after checking that it succeeded.
fn decimate(dir: &Path, args: &[&str]) -> String {
    let o = binary::decimate(dir, args);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(o.status.success(), "{args:?}: {stderr}");
    stderr
}

/// A `.glb` or `.gltf` read with the gltf crate, with its buffers' bytes (a `.gltf`'s
/// buffer is the file its `uri` names beside it).
fn load(path: &Path) -> (gltf::Document, Vec<Vec<u8>>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let g = gltf::Gltf::from_slice(&bytes).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let buffers = g
        .document
        .buffers()
        .map(|b| match b.source() {
            gltf::buffer::Source::Bin => g.blob.clone().expect("a BIN chunk"),
            gltf::buffer::Source::Uri(uri) => {
                let file = path.with_file_name(uri);
                std::fs::read(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()))
            }
        })
        .collect();
    (g.document, buffers)
}

/// The bytes of accessor `a` (tightly packed, as both the input and our writer lay them).
fn accessor_bytes(a: &gltf::Accessor<'_>, buffers: &[Vec<u8>]) -> Vec<u8> {
    let view = a.view().expect("a buffer view");
    let start = view.offset() + a.offset();
    buffers[view.buffer().index()][start..start + a.count() * a.size()].to_vec()
}

/// An `extras` value as JSON (`null` when absent).
fn extras(e: &gltf::json::Extras) -> Value {
    e.as_ref()
        .map(|raw| serde_json::from_str(raw.get()).expect("extras parse"))
        .unwrap_or(Value::Null)
}

/// What the tests compare of one primitive: mode, component type, POSITION's and the
/// indices' bytes.
fn primitive_bytes(
    p: &gltf::Primitive<'_>,
    buffers: &[Vec<u8>],
) -> impl PartialEq + std::fmt::Debug {
    let pos = p.get(&gltf::Semantic::Positions).expect("POSITION");
    let idx = p.indices().expect("indices");
    (
        p.mode(),
        idx.data_type(),
        accessor_bytes(&pos, buffers),
        accessor_bytes(&idx, buffers),
    )
}

#[test]
fn cameras_lights_extras_and_lines_come_back_unchanged_beside_the_decimated_triangles() {
    let dir = scratch("carry");
    let d = scene_with_everything();
    let input = dir.join("in.glb");
    std::fs::write(&input, d.glb()).expect("writes");
    assert_valid(&[&input]);
    let (src, src_buffers) = load(&input);
    let src_mesh = src.meshes().next().expect("a mesh");
    let src_lines = src_mesh.primitives().nth(1).expect("the lines");
    // The same grid alone, decimated alike: the triangles a plain run gives.
    let mut plain = Doc::new();
    let grid = wavy_grid(&mut plain, 10);
    plain.json["materials"] = json!([{}]);
    plain.mesh_node(vec![grid], json!({ "name": "terrain" }));
    std::fs::write(dir.join("plain.glb"), plain.glb()).expect("writes");
    decimate(
        &dir,
        &["plain.glb", "nogui", "-v", "60", "-o", "plain-out.glb"],
    );
    let (plain_out, plain_buffers) = load(&dir.join("plain-out.glb"));
    let plain_tri = plain_out
        .meshes()
        .next()
        .expect("a mesh")
        .primitives()
        .next();
    let plain_tri = primitive_bytes(&plain_tri.expect("a primitive"), &plain_buffers);

    for out in ["out.glb", "out.gltf"] {
        let stderr = decimate(&dir, &["in.glb", "nogui", "-v", "60", "-o", out]);
        let warnings: Vec<&str> = stderr.lines().filter(|l| l.contains("warning")).collect();
        let said = |what: &str| warnings.iter().filter(|l| l.contains(what)).count();
        assert_eq!(
            said(
                "points and lines primitives are copied through unchanged to a glTF output, \
                  not decimated nor shown (mesh 0 primitive 1 LINES)"
            ),
            1,
            "{stderr}"
        );
        assert_eq!(
            said(
                "glTF extensions left out of the output: KHR_materials_clearcoat, EXT_made_up_tag"
            ),
            1,
            "{stderr}"
        );
        assert_eq!(warnings.len(), 2, "{stderr}");
        let path = dir.join(out);
        assert_valid(&[&path]);
        let (doc, buffers) = load(&path);
        let json = doc.as_json();
        assert_eq!(
            extras(&json.asset.extras),
            json!({ "author": "gltf_carry" })
        );
        assert_eq!(json.asset.copyright.as_deref(), Some("CC0 test"));
        let scene = doc.default_scene().expect("a default scene");
        assert_eq!(scene.name(), Some("Level"), "{out}");
        assert_eq!(extras(scene.extras()), json!({ "level": "one" }));
        let nodes: Vec<gltf::Node<'_>> = doc.nodes().collect();
        assert_eq!(nodes.len(), 3, "{out}");

        // The camera, on its node, with every parameter as given.
        let camera = nodes[0].camera().expect("node 0 keeps its camera");
        assert_eq!(camera.name(), Some("eye"));
        assert_eq!(extras(camera.extras()), json!({ "rig": "dolly" }));
        match camera.projection() {
            gltf::camera::Projection::Perspective(p) => {
                assert_eq!(
                    (p.yfov(), p.znear(), p.zfar(), p.aspect_ratio()),
                    (0.75, 0.05, Some(250.0), Some(1.5))
                );
            }
            p => panic!("{out}: the camera became {p:?}"),
        }
        assert_eq!(extras(nodes[0].extras()), json!({ "role": "view" }));
        assert_eq!(doc.cameras().count(), 1);

        // The point light, on its node, with its colour, intensity and range.
        let light = nodes[1].light().expect("node 1 keeps its light");
        assert_eq!(light.name(), Some("bulb"));
        assert!(matches!(
            light.kind(),
            gltf::khr_lights_punctual::Kind::Point
        ));
        assert_eq!(
            (light.color(), light.intensity(), light.range()),
            ([1.0, 0.5, 0.25], 40.0, Some(12.0))
        );
        assert_eq!(doc.lights().map(|l| l.count()), Some(1));
        assert!(doc.extensions_used().any(|e| e == "KHR_lights_punctual"));
        for lost in ["EXT_made_up_tag", "KHR_materials_clearcoat"] {
            assert!(!doc.extensions_used().any(|e| e == lost), "{out}: {lost}");
        }

        // The mesh: its name and extras, the triangles decimated as a plain run does, the
        // lines' positions and indices byte for byte with their material.
        assert_eq!(extras(nodes[2].extras()), json!({ "id": 7 }));
        let mesh = nodes[2].mesh().expect("node 2 keeps its mesh");
        assert_eq!(mesh.name(), Some("terrain"));
        assert_eq!(
            extras(mesh.extras()),
            json!({ "lod": 0, "tags": ["ground", "wavy"] })
        );
        let prims: Vec<gltf::Primitive<'_>> = mesh.primitives().collect();
        assert_eq!(prims.len(), 2, "{out}");
        let tri = &prims[0];
        assert_eq!(tri.mode(), gltf::mesh::Mode::Triangles);
        let vertices = tri
            .get(&gltf::Semantic::Positions)
            .expect("POSITION")
            .count();
        assert_eq!(vertices, 121 - 60, "{out}");
        assert_eq!(primitive_bytes(tri, &buffers), plain_tri, "{out}");
        let corners = tri.indices().expect("indices").count();
        // As many triangles as the summary says were kept, fewer than the 200 read.
        let kept: usize = stderr
            .lines()
            .find_map(|l| l.strip_prefix("total: vertices 121 -> 61, triangles 200 -> "))
            .and_then(|rest| rest.split(';').next()?.parse().ok())
            .unwrap_or_else(|| panic!("{out}: no total line in {stderr}"));
        assert!(kept < 200);
        assert_eq!(corners, 3 * kept, "{out}");
        let lines = &prims[1];
        assert_eq!(
            primitive_bytes(lines, &buffers),
            primitive_bytes(&src_lines, &src_buffers),
            "{out}: the lines"
        );
        assert_eq!(extras(lines.extras()), json!({ "stroke": "dashed" }));
        let ink = lines.material();
        assert_eq!(ink.name(), Some("ink"));
        assert_eq!(
            ink.pbr_metallic_roughness().base_color_factor(),
            [1.0, 0.0, 0.0, 1.0]
        );

        // The triangles' material keeps its extras and its texture-free extension.
        let grass = tri.material();
        assert_eq!(grass.name(), Some("grass"));
        assert_eq!(extras(grass.extras()), json!({ "shader": "toon" }));
        assert!(
            doc.extensions_used()
                .any(|e| e == "KHR_materials_emissive_strength"),
            "{out}"
        );
        let text = match out.ends_with(".glb") {
            true => {
                let bytes = std::fs::read(&path).expect("reads");
                let glb = gltf::binary::Glb::from_slice(&bytes).expect("a GLB");
                serde_json::from_slice::<Value>(&glb.json).expect("JSON")
            }
            false => serde_json::from_slice(&std::fs::read(&path).expect("reads")).expect("JSON"),
        };
        let k = grass.index().expect("an index");
        assert_eq!(
            text["materials"][k]["extensions"],
            json!({ "KHR_materials_emissive_strength": { "emissiveStrength": 2.5 } }),
            "{out}"
        );
        // With the emissive factor it scales, read from the source material.
        assert_eq!(grass.emissive_factor(), [1.0, 1.0, 1.0], "{out}");
    }

    // Another format keeps the geometry and says, once, what only glTF holds.
    let stderr = decimate(&dir, &["in.glb", "nogui", "-v", "60", "-o", "out.ply"]);
    let lost = "the source's cameras, lights, points and lines primitives and extras are \
                glTF's alone: a glTF output carries them, this one leaves them out";
    assert_eq!(stderr.matches(lost).count(), 1, "{stderr}");
}

#[test]
fn lines_in_a_mesh_without_triangles_come_back_on_their_node() {
    let dir = scratch("lines-alone");
    let mut d = Doc::new();
    let grid = wavy_grid(&mut d, 4);
    d.json["materials"] = json!([{}]);
    d.mesh_node(vec![grid], json!({ "name": "ground" }));
    let strip = [0., 0., 2., 1., 0., 2., 2., 1., 2.];
    let position = d.positions(&strip);
    d.mesh_node(
        vec![json!({ "attributes": { "POSITION": position }, "mode": 3 })],
        json!({ "name": "path", "translation": [0, 0, 1] }),
    );
    std::fs::write(dir.join("in.glb"), d.glb()).expect("writes");
    assert_valid(&[&dir.join("in.glb")]);
    let (src, src_buffers) = load(&dir.join("in.glb"));
    let src_strip = src.meshes().nth(1).expect("the path").primitives().next();
    let src_strip = src_strip.expect("a primitive");
    let src_pos = src_strip.get(&gltf::Semantic::Positions).expect("POSITION");
    decimate(&dir, &["in.glb", "nogui", "-v", "5", "-o", "out.glb"]);
    assert_valid(&[&dir.join("out.glb")]);
    let (doc, buffers) = load(&dir.join("out.glb"));
    let path = doc.nodes().nth(1).expect("node 1");
    assert_eq!(path.name(), Some("path"));
    let prims: Vec<gltf::Primitive<'_>> = path.mesh().expect("its mesh").primitives().collect();
    assert_eq!(prims.len(), 1);
    assert_eq!(prims[0].mode(), gltf::mesh::Mode::LineStrip);
    assert!(prims[0].indices().is_none());
    let pos = prims[0].get(&gltf::Semantic::Positions).expect("POSITION");
    assert_eq!(
        accessor_bytes(&pos, &buffers),
        accessor_bytes(&src_pos, &src_buffers)
    );
    let ground = doc.nodes().next().and_then(|n| n.mesh()).expect("ground");
    let vertices = ground
        .primitives()
        .next()
        .and_then(|p| p.get(&gltf::Semantic::Positions));
    assert_eq!(vertices.map(|a| a.count()), Some(25 - 5));
}

#[test]
fn a_damaged_lines_primitive_is_an_error_naming_it_not_a_damaged_output() {
    let mut d = Doc::new();
    let grid = wavy_grid(&mut d, 2);
    let position = d.positions(&[0., 0., 1., 1., 0., 1.]);
    let corners: Vec<u8> = [0u16, 9].iter().flat_map(|i| i.to_le_bytes()).collect();
    let indices = d.accessor(&corners, USHORT, "SCALAR", 2, false);
    let lines = json!({ "attributes": { "POSITION": position }, "indices": indices, "mode": 1 });
    d.json["materials"] = json!([{}]);
    d.mesh_node(vec![grid, lines], json!({}));
    let e = match decimate_core::io::parse_bytes(d.glb(), Path::new("bad-lines.glb")) {
        Ok(_) => panic!("an index past the vertices is read"),
        Err(e) => e.to_string(),
    };
    assert!(
        e.starts_with("bad-lines.glb")
            && e.contains("mesh 0 primitive 1: index 1 is 9, but there are 2 vertices"),
        "{e}"
    );
}
