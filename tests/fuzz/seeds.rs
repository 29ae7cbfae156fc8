//! The small valid files the mutants start from: one written by each of our writers, and
//! hand-written ones for the syntax our writers do not produce.

use std::path::Path;

use decimate_core::decimate::{simplify_scene_progressive, Params};
use decimate_core::io;
use decimate_core::mesh::{shapes, Attribute, Scene};

/// The small valid files the mutants start from, one or more per format, as (file name,
/// bytes): the name's extension says the format where the content does not.
pub fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let mut sphere = shapes::bumpy_sphere(5, 8);
    let n = sphere.positions.len();
    sphere.colors = Some(Attribute::PerVertex(
        (0..n).map(|i| [i as f32 / n as f32, 0.5, 0.25]).collect(),
    ));
    sphere.texcoords = Some(
        sphere
            .positions
            .iter()
            .map(|p| [0.5 + 0.5 * p.x, 0.5 + 0.5 * p.y])
            .collect(),
    );
    sphere.texture = Some("image.png".into());
    let mut cube = shapes::cube(2, 2.0);
    cube.name = "Cube".into();
    let scene = Scene {
        models: vec![sphere, cube],
    };
    let written = |write: fn(&mut Vec<u8>, &Scene) -> std::io::Result<()>| {
        let mut bytes = Vec::new();
        write(&mut bytes, &scene).expect("writes to memory");
        bytes
    };
    let mut pm_scene = Scene {
        models: vec![shapes::bumpy_sphere(4, 6)],
    };
    let (_, pm) = simplify_scene_progressive(&mut pm_scene, &Params::default(), &mut |_| {});
    let mut pm_bytes = Vec::new();
    io::progressive_file::write_progressive_to(&mut pm_bytes, &pm).expect("writes to memory");
    vec![
        ("seed.wrl", written(io::write_vrml2_to)),
        ("seed.ply", written(io::ply::write_ply_to)),
        ("seed.obj", written(io::obj::write_obj_to)),
        ("seed.stl", written(io::stl::write_stl_to)),
        ("seed.off", written(io::off::write_off_to)),
        ("seed.pm", pm_bytes),
        ("vrml1.wrl", VRML1.as_bytes().to_vec()),
        ("inventor.iv", INVENTOR.as_bytes().to_vec()),
        ("nodes.iv", INVENTOR_NODES.as_bytes().to_vec()),
        ("nodes.wrl", VRML2_NODES.as_bytes().to_vec()),
        ("ascii.ply", ASCII_PLY.as_bytes().to_vec()),
        ("ascii.stl", ASCII_STL.as_bytes().to_vec()),
        ("colour.off", COLOUR_OFF.as_bytes().to_vec()),
        ("faces.obj", OBJ.as_bytes().to_vec()),
        ("seed.glb", gltf_seed()),
        ("seed.gltf", gltf_json_seed(&gltf_seed())),
        ("skinned.glb", skinned_gltf_seed()),
        ("carried.gltf", carried_gltf_seed()),
    ]
}

/// A triangle beside a LINES primitive, a camera, a point light, extras and a material
/// extension, as `.gltf` text with a `data:` buffer: what the reader carries beside the
/// meshes (`io::gltf`).
fn carried_gltf_seed() -> Vec<u8> {
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut bin = floats(&[0., 0., 0., 1., 0., 0., 0., 1., 0.]);
    bin.extend_from_slice(&floats(&[0., 0., 1., 1., 1., 1.]));
    bin.extend_from_slice(&[0, 1, 0, 0]);
    let json = serde_json::json!({
        "asset": { "version": "2.0", "extras": { "a": 1 } },
        "extensionsUsed": ["KHR_lights_punctual", "KHR_materials_ior"],
        "extensions": { "KHR_lights_punctual": { "lights": [
            { "type": "spot", "color": [1, 1, 0.5], "intensity": 3, "spot": { "outerConeAngle": 0.5 } },
        ] } },
        "scene": 0,
        "scenes": [{ "nodes": [0, 1, 2], "extras": [1, 2] }],
        "nodes": [
            { "camera": 0, "extras": { "b": true } },
            { "extensions": { "KHR_lights_punctual": { "light": 0 } } },
            { "mesh": 0, "extras": "c" },
        ],
        "cameras": [{ "type": "orthographic",
                      "orthographic": { "xmag": 1, "ymag": 1, "znear": 0, "zfar": 10 } }],
        "materials": [{ "extensions": { "KHR_materials_ior": { "ior": 1.3 } }, "extras": {} }],
        "meshes": [{ "extras": { "d": null }, "primitives": [
            { "attributes": { "POSITION": 0 }, "material": 0 },
            { "attributes": { "POSITION": 1 }, "indices": 2, "mode": 1 },
        ] }],
        "accessors": [
            { "bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": 1, "componentType": 5126, "count": 2, "type": "VEC3",
              "min": [0, 0, 1], "max": [1, 1, 1] },
            { "bufferView": 2, "componentType": 5121, "count": 2, "type": "SCALAR" },
        ],
        "bufferViews": [
            { "buffer": 0, "byteOffset": 0, "byteLength": 36 },
            { "buffer": 0, "byteOffset": 36, "byteLength": 24 },
            { "buffer": 0, "byteOffset": 60, "byteLength": 2 },
        ],
        "buffers": [{ "byteLength": bin.len(),
                      "uri": io::data_uri::encode("application/octet-stream", &bin) }],
    });
    serde_json::to_vec_pretty(&json).expect("serializes")
}

/// A skinned square with a dense and a sparse morph target, a skin and an animation of
/// its joint and weights, as `.glb`: what the reader copies through (`io::gltf`).
fn skinned_gltf_seed() -> Vec<u8> {
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut view = |bin: &mut Vec<u8>, bytes: &[u8]| {
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        views.push(
            serde_json::json!({ "buffer": 0, "byteOffset": bin.len(), "byteLength": bytes.len() }),
        );
        bin.extend_from_slice(bytes);
        views.len() - 1
    };
    let floats = |v: &[f32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let square = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
    let p = view(&mut bin, &floats(&square));
    let i = view(&mut bin, &[0, 1, 2, 0, 2, 3]);
    let j = view(&mut bin, &[0; 16]);
    let w = view(&mut bin, &floats(&[1., 0., 0., 0.].repeat(4)));
    let d = view(&mut bin, &floats(&[0., 0., 0.5].repeat(4)));
    let si = view(&mut bin, &[2]);
    let sv = view(&mut bin, &floats(&[0., 0., 0.75]));
    let m = view(&mut bin, &floats(&glam::Mat4::IDENTITY.to_cols_array()));
    let t = view(&mut bin, &floats(&[0., 1.]));
    let o = view(&mut bin, &floats(&[0., 0., 0., 0., 0., 1.]));
    let ow = view(&mut bin, &floats(&[0., 0., 1., 1.]));
    let json = serde_json::json!({
        "asset": { "version": "2.0" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [
            { "name": "armature", "children": [1, 2] },
            { "name": "body", "mesh": 0, "skin": 0, "weights": [0.5, 0.25] },
            { "name": "bone", "translation": [0, 0, 1] },
        ],
        "meshes": [{ "name": "body", "weights": [0, 0], "primitives": [{
            "attributes": { "POSITION": 0, "JOINTS_0": 2, "WEIGHTS_0": 3 },
            "indices": 1,
            "targets": [{ "POSITION": 4 }, { "POSITION": 5 }],
        }] }],
        "skins": [{ "joints": [2], "inverseBindMatrices": 6, "skeleton": 0 }],
        "animations": [{
            "samplers": [{ "input": 7, "output": 8 }, { "input": 7, "output": 9 }],
            "channels": [
                { "sampler": 0, "target": { "node": 2, "path": "translation" } },
                { "sampler": 1, "target": { "node": 1, "path": "weights" } },
            ],
        }],
        "accessors": [
            { "bufferView": p, "componentType": 5126, "count": 4, "type": "VEC3",
              "min": [0, 0, 0], "max": [1, 1, 0] },
            { "bufferView": i, "componentType": 5121, "count": 6, "type": "SCALAR" },
            { "bufferView": j, "componentType": 5121, "count": 4, "type": "VEC4" },
            { "bufferView": w, "componentType": 5126, "count": 4, "type": "VEC4" },
            { "bufferView": d, "componentType": 5126, "count": 4, "type": "VEC3",
              "min": [0, 0, 0.5], "max": [0, 0, 0.5] },
            { "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 0.75],
              "sparse": { "count": 1, "indices": { "bufferView": si, "componentType": 5121 },
                          "values": { "bufferView": sv } } },
            { "bufferView": m, "componentType": 5126, "count": 1, "type": "MAT4" },
            { "bufferView": t, "componentType": 5126, "count": 2, "type": "SCALAR",
              "min": [0], "max": [1] },
            { "bufferView": o, "componentType": 5126, "count": 2, "type": "VEC3" },
            { "bufferView": ow, "componentType": 5126, "count": 4, "type": "SCALAR" },
        ],
        "bufferViews": views,
        "buffers": [{ "byteLength": bin.len() }],
    });
    let mut json = serde_json::to_vec(&json).expect("serializes");
    while !json.len().is_multiple_of(4) {
        json.push(b' ');
    }
    while !bin.len().is_multiple_of(4) {
        bin.push(0);
    }
    let mut glb = b"glTF".to_vec();
    for n in [2, 28 + json.len() + bin.len(), json.len()] {
        glb.extend_from_slice(&(n as u32).to_le_bytes());
    }
    glb.extend_from_slice(b"JSON");
    glb.extend_from_slice(&json);
    glb.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    glb.extend_from_slice(b"BIN\0");
    glb.extend_from_slice(&bin);
    glb
}

/// A small glTF scene as `.glb`, written by the program: a cube with per-face colours
/// (one vertex per corner), placed by a mirroring transform, and a sphere textured by an
/// embedded 2 × 2 PNG.
fn gltf_seed() -> Vec<u8> {
    let mut png_bytes = Vec::new();
    let mut e = png::Encoder::new(&mut png_bytes, 2, 2);
    e.set_color(png::ColorType::Rgb);
    let mut w = e.write_header().expect("png header");
    w.write_image_data(&[255; 12]).expect("png data");
    drop(w);
    let mut sphere = shapes::bumpy_sphere(3, 4);
    sphere.texcoords = Some(sphere.positions.iter().map(|p| [p.x, p.y]).collect());
    sphere.texture = Some(io::data_uri::encode("image/png", &png_bytes));
    let mut cube = shapes::cube(1, 2.0);
    let t = cube.triangles.len();
    cube.colors = Some(Attribute::PerFace(vec![[1.0, 0.5, 0.0]; t]));
    cube.transform = glam::Mat4::from_scale(glam::Vec3::new(-1.0, 2.0, 1.0));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz_inputs-seed");
    std::fs::create_dir_all(&dir).expect("creates the seed folder");
    let path = dir.join("seed.glb");
    let scene = Scene {
        models: vec![cube, sphere],
    };
    io::write_scene(&scene, &path).expect("writes the glTF seed");
    std::fs::read(&path).expect("reads the glTF seed")
}

/// The `.glb` as `.gltf` text, its binary chunk a base64 `data:` URI.
fn gltf_json_seed(glb: &[u8]) -> Vec<u8> {
    let u32_at = |i: usize| u32::from_le_bytes([glb[i], glb[i + 1], glb[i + 2], glb[i + 3]]);
    let json_len = u32_at(12) as usize;
    let json = &glb[20..20 + json_len];
    let bin_len = u32_at(20 + json_len) as usize;
    let bin = &glb[28 + json_len..28 + json_len + bin_len];
    let mut doc: serde_json::Value = serde_json::from_slice(json).expect("the seed's JSON");
    doc["buffers"][0]["uri"] = io::data_uri::encode("application/octet-stream", bin).into();
    serde_json::to_vec_pretty(&doc).expect("serializes")
}

const VRML1: &str = "#VRML V1.0 ascii
Separator {
  DEF Look Material { diffuseColor [ 1 0 0, 0 1 0, 0 0 1 ] }
  MaterialBinding { value PER_FACE }
  ShapeHints { vertexOrdering COUNTERCLOCKWISE creaseAngle 0.5 }
  Transform { translation 1 0 0 scaleFactor 2 2 2 }
  Coordinate3 { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0, 0.5 0.5 1 ] }
  Normal { vector [ 0 0 1 ] }
  NormalBinding { value OVERALL }
  TextureCoordinate2 { point [ 0 0, 1 0, 1 1, 0 1 ] }
  IndexedFaceSet {
    coordIndex [ 0 1 4 -1, 1 2 4 -1, 2 3 4 -1, 3 0 4 -1, 0 3 2 1 -1 ]
    textureCoordIndex [ 0 1 2 -1, 1 2 3 -1, 2 3 0 -1, 3 0 1 -1, 0 1 2 3 -1 ]
  }
  Separator { USE Look Cube { width 2 } }
}
";

const INVENTOR: &str = "#Inventor V2.1 ascii
Separator {
  Material { diffuseColor 0.8 0.2 0.2 }
  Coordinate3 { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0, 0.5 0.5 1 ] }
  IndexedFaceSet { coordIndex [ 0 1 4 -1, 1 2 4 -1, 2 3 4 -1, 3 0 4 -1, 0 3 2 1 -1 ] }
  Texture2 { filename \"wood.png\" wrapS CLAMP }
  Translation { translation 3 0 0 }
  Sphere { radius 0.5 }
}
";

/// Inventor's other shapes and bindings: strips, quads, per-vertex materials, arrays,
/// primitives, node kits.
const INVENTOR_NODES: &str = "#Inventor V2.1 ascii
Separator {
  ShapeHints { vertexOrdering CLOCKWISE shapeType SOLID faceType UNKNOWN_FACE_TYPE creaseAngle 1 }
  Material { diffuseColor [ 1 0 0, 0 1 0, 0 0 1, 1 1 0 ] }
  MaterialBinding { value PER_VERTEX_INDEXED }
  Coordinate3 { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0, 0 0 1, 1 0 1, 1 1 1, 0 1 1 ] }
  IndexedTriangleStripSet {
    coordIndex [ 0 1 3 2 7 6 -1, 4 5 0 1 -1 ]
    materialIndex [ 0 1 2 3 0 1 -1, 2 3 0 1 -1 ]
  }
  TransformSeparator {
    RotationXYZ { axis Y angle 0.5 }
    Array { numElements1 2 separation1 3 0 0
      FaceSet { numVertices [ 4, 3 ] }
    }
  }
  Switch { whichChild 0 Separator { QuadMesh { verticesPerColumn 2 verticesPerRow 4 } } }
  Separator {
    NormalBinding { value PER_FACE }
    Normal { vector [ 0 0 1, 0 0 -1 ] }
    TextureCoordinateBinding { value PER_VERTEX }
    TextureCoordinate2 { point [ 0 0, 1 0, 1 1, 0 1 ] }
    VertexProperty { vertex [ 0 0 0, 2 0 0, 2 2 0, 0 2 0 ] }
    TriangleStripSet { numVertices [ 4 ] }
  }
  LevelOfDetail { screenArea [ 100 ] Cube { } Sphere { } }
  Complexity { value 0.2 }
  Cylinder { parts (SIDES | TOP) radius 0.5 height 2 }
  Cone { parts ALL bottomRadius 1 height 1 }
  MultipleCopy { matrix [ 1 0 0 0 0 1 0 0 0 0 1 0 4 0 0 1 ] Sphere { radius 0.5 } }
  Switch { whichChild 1 Cube { } Switch { whichChild -2 Cube { } Cylinder { } } }
  ShapeKit {
    transform Transform { translation 0 3 0 }
    localTransform Transform { scaleFactor 2 1 1 }
    shape Cone { }
  }
  IndexedTriangleMesh { coordIndex [ 0 1 3 2 -1 ] }
}
";

/// VRML 2.0's grouping nodes, instancing and an IndexedFaceSet with every field: concave
/// polygons, colour and normal indices, texture coordinates.
const VRML2_NODES: &str = "#VRML V2.0 utf8
DEF Root Transform {
  translation 1 2 3 rotation 0 1 0 0.7 scale 2 2 2 center 0.5 0 0
  children [
    DEF Piece Shape {
      appearance Appearance {
        material Material { diffuseColor 0.2 0.4 0.6 }
        texture ImageTexture { url [ \"wood.png\" \"wood.jpg\" ] repeatS FALSE }
      }
      geometry IndexedFaceSet {
        coord Coordinate { point [ 0 0 0, 2 0 0, 2 2 0, 1 1 0, 0 2 0, 1 0 1 ] }
        coordIndex [ 0 1 2 3 4 -1, 0 5 1 -1, 1 5 2 -1 ]
        convex FALSE solid FALSE ccw FALSE creaseAngle 0.8
        color Color { color [ 1 0 0, 0 1 0, 0 0 1 ] }
        colorPerVertex FALSE colorIndex [ 0 1 2 ]
        normal Normal { vector [ 0 0 1, 0 -1 0 ] }
        normalPerVertex TRUE normalIndex [ 0 0 0 0 0 -1, 1 1 1 -1, 1 1 1 -1 ]
        texCoord TextureCoordinate { point [ 0 0, 1 0, 1 1, 0.5 0.5, 0 1, 0.5 0 ] }
        texCoordIndex [ 0 1 2 3 4 -1, 0 5 1 -1, 1 5 2 -1 ]
      }
    }
    Group { children [ Transform { translation 5 0 0 children USE Piece } ] }
    Switch { whichChoice 0 choice [ Shape { geometry Box { size 1 2 3 } } ] }
    LOD { range [ 10 ] level [ Billboard { children USE Piece } Group { } ] }
    Anchor { children Collision { children [ USE Piece ] } }
    Shape { geometry Cone { side FALSE } }
    Shape { geometry Cylinder { top FALSE height 3 } }
    Shape { geometry ElevationGrid { xDimension 3 zDimension 2 height [ 0 1 2 0 1 2 ]
      colorPerVertex FALSE color Color { color [ 1 0 0, 0 1 0 ] } } }
    Shape { geometry Extrusion { spine [ 0 0 0, 0 2 0, 2 2 0 ] scale [ 0.25 0.25, 0.5 0.5 ]
      orientation [ 0 1 0 0.3 ] crossSection [ 1 0, 0 -1, -1 0, 0 1, 1 0 ] } }
  ]
}
Transform { children USE Root }
Shape { geometry Sphere { radius 0.5 } }
";

const ASCII_PLY: &str = "ply
format ascii 1.0
comment a pyramid
element vertex 5
property float x
property float y
property float z
property uchar red
property uchar green
property uchar blue
property float nx
property float ny
property float nz
property float s
property float t
element face 5
property list uchar int vertex_indices
end_header
0 0 0 255 0 0 0 0 1 0 0
1 0 0 0 255 0 0 0 1 1 0
1 1 0 0 0 255 0 0 1 1 1
0 1 0 255 255 0 0 0 1 0 1
0.5 0.5 1 0 255 255 0 0 1 0.5 0.5
3 0 1 4
3 1 2 4
3 2 3 4
3 3 0 4
4 0 3 2 1
";

const ASCII_STL: &str = "solid pyramid
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 1 1 0
  vertex 1 0 0
 endloop
endfacet
facet normal 0 0 -1
 outer loop
  vertex 0 0 0
  vertex 0 1 0
  vertex 1 1 0
 endloop
endfacet
facet normal 0 -1 1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 0.5 0.5 1
 endloop
endfacet
facet normal 1 0 1
 outer loop
  vertex 1 0 0
  vertex 1 1 0
  vertex 0.5 0.5 1
 endloop
endfacet
facet normal 0 1 1
 outer loop
  vertex 1 1 0
  vertex 0 1 0
  vertex 0.5 0.5 1
 endloop
endfacet
facet normal -1 0 1
 outer loop
  vertex 0 1 0
  vertex 0 0 0
  vertex 0.5 0.5 1
 endloop
endfacet
endsolid pyramid
";

const COLOUR_OFF: &str = "COFF
# a pyramid, coloured
5 5 0
0 0 0 255 0 0 255
1 0 0 0 255 0 255
1 1 0 0 0 255 255
0 1 0 255 255 0 255
0.5 0.5 1 0 255 255 255
3 0 1 4
3 1 2 4 1.0 0.0 0.0
3 2 3 4
3 3 0 4
4 0 3 2 1
";

const OBJ: &str = "# a pyramid
mtllib pyramid.mtl
o Pyramid
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0 0.5 0.5 0.5
v 0.5 0.5 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 1
g sides
usemtl red
f 1/1/1 2/2/1 5/3/1
f 2/2 3/3 5/4
f -3//1 -2//1 -1//1
f 4 1 5
s off
usemtl blue
f 1 4 3 2
l 1 2
p 3
";
