//! Texture coordinates of the VRML / Inventor primitives under a texture, as VRML 2.0
//! defines them (§6.4 Box, §6.8 Cone, §6.11 Cylinder, §6.42 Sphere; Inventor's SoCube,
//! SoCone, SoCylinder and SoSphere agree): exact vertex and triangle counts textured and
//! not, the coordinates at known points, seams whose copies weld back into the untextured
//! closed surface, a textured sphere and cylinder decimated by both algorithms without a
//! crack and with their coordinates in 0..1, texture transforms, and the coordinates
//! carried into VRML 2.0 and OBJ outputs; the default mappings of extrusions, and of face
//! sets and elevation grids that give no coordinates; textures the reader cannot use named
//! in a warning.

use std::collections::{HashMap, HashSet};
use std::f32::consts::TAU;

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::io::{parse_str, read_scene, write_scene};
use decimate_core::mesh::build::build_scene;
use decimate_core::mesh::{Model, Scene};
use glam::Vec3;

use crate::support::texture::textured_corners;

/// `geometry` in a VRML 2.0 Shape, under an `ImageTexture` when `textured`.
fn vrml2_text(geometry: &str, textured: bool) -> String {
    let texture = if textured {
        "texture ImageTexture { url \"checker.png\" }"
    } else {
        ""
    };
    format!(
        "#VRML V2.0 utf8\nShape {{ appearance Appearance {{ {texture} }} geometry {geometry} }}\n"
    )
}

/// `shape` (with any property nodes before it) in an Inventor file, under a `Texture2`
/// when `textured`.
fn inventor_text(shape: &str, textured: bool) -> String {
    let texture = if textured {
        "Texture2 { filename \"checker.png\" }"
    } else {
        ""
    };
    format!("#Inventor V2.1 ascii\nSeparator {{ {texture} {shape} }}\n")
}

fn one_model(text: &str, name: &str) -> Model {
    let mut scene = parse_str(text, name)
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    assert_eq!(scene.models.len(), 1, "{text}");
    scene.models.remove(0)
}

fn vrml2(geometry: &str, textured: bool) -> Model {
    one_model(&vrml2_text(geometry, textured), "t.wrl")
}

fn inventor(shape: &str, textured: bool) -> Model {
    one_model(&inventor_text(shape, textured), "t.iv")
}

fn uv(m: &Model, v: u32) -> [f32; 2] {
    m.texcoords.as_ref().expect("texture coordinates")[v as usize]
}

fn normal(m: &Model, t: [u32; 3]) -> Vec3 {
    let [a, b, c] = t.map(|v| m.positions[v as usize]);
    (b - a).cross(c - a).normalize()
}

fn near(a: f32, b: f32) -> bool {
    (a - b).abs() < 1e-5
}

/// u of a point around the y axis as the spec measures it: 0 at the back (-z), a quarter at
/// -x, a half at the front (+z), three quarters at +x.
fn around(p: Vec3) -> f32 {
    let u = (-p.x).atan2(-p.z) / TAU;
    if u < 0.0 {
        u + 1.0
    } else {
        u
    }
}

/// A corner's u against [`around`]: equal, or 1 where the seam's second copy is (at the
/// back), or anywhere strictly inside 0..1 on the axis (poles and apex, checked apart).
fn u_fits(p: Vec3, u: f32) -> bool {
    if p.x.abs() < 1e-6 && p.z.abs() < 1e-6 {
        return u > 0.0 && u < 1.0;
    }
    let expected = around(p);
    near(u, expected) || (near(expected, 0.0) && near(u, 1.0))
}

#[test]
fn textured_primitives_split_their_seams_and_keep_coins_triangle_counts() {
    // (geometry, vertices untextured, vertices textured, triangles). The sphere has 13 rings
    // of 15 slices: textured each ring gets a seam copy and each pole one copy per slice. A
    // cylinder's 20-slice rings gain seam copies and the caps rings of their own, a cone's
    // apex one copy per slice.
    let cases = [
        ("Box { size 4 2 6 }", 8, 24, 12),
        ("Sphere { radius 2 }", 197, 13 * 16 + 2 * 15, 390),
        ("Cylinder {}", 40, 2 * 21 + 2 * 20, 40 + 18 + 18),
        ("Cylinder { top FALSE }", 40, 2 * 21 + 20, 40 + 18),
        ("Cylinder { side FALSE }", 40, 2 * 20, 18 + 18),
        ("Cone {}", 21, 21 + 20 + 20, 20 + 18),
        ("Cone { bottom FALSE }", 21, 21 + 20, 20),
    ];
    for (geometry, plain, textured, triangles) in cases {
        let m = vrml2(geometry, false);
        assert_eq!(
            (m.positions.len(), m.triangles.len()),
            (plain, triangles),
            "{geometry}"
        );
        assert!(
            m.texcoords.is_none(),
            "{geometry}: no texture, no coordinates"
        );
        let t = vrml2(geometry, true);
        assert_eq!(
            (t.positions.len(), t.triangles.len()),
            (textured, triangles),
            "{geometry} textured"
        );
        assert_eq!(t.texcoords.as_ref().map(Vec::len), Some(textured));
        assert_eq!(t.texture.as_deref(), Some("checker.png"));
    }
    // Inventor: the same shapes under a Texture2, at another complexity too.
    let cases = [
        ("Cube { width 4 }", 8, 24, 12),
        ("Sphere {}", 197, 238, 390),
        (
            "Complexity { value 1 } Sphere {}",
            30 * 28 + 2,
            28 * 31 + 2 * 30,
            2 * 30 * 28,
        ),
        ("Cylinder { parts SIDES }", 40, 42, 40),
        ("Cone { parts ALL }", 21, 61, 38),
    ];
    for (shape, plain, textured, triangles) in cases {
        let m = inventor(shape, false);
        assert_eq!(
            (m.positions.len(), m.triangles.len()),
            (plain, triangles),
            "{shape}"
        );
        assert!(m.texcoords.is_none(), "{shape}");
        let t = inventor(shape, true);
        assert_eq!(
            (
                t.positions.len(),
                t.triangles.len(),
                t.texcoords.map(|c| c.len())
            ),
            (textured, triangles, Some(textured)),
            "{shape} textured"
        );
    }
}

/// The texture axes of a box face by its outward normal (VRML 2.0 §6.4): the sides upright
/// seen from outside with +y up, the top seen from above with -z up, the bottom seen from
/// below with +z up.
fn box_face_axes(n: Vec3) -> (Vec3, Vec3) {
    let n = n.round();
    match (n.x as i32, n.y as i32, n.z as i32) {
        (0, 0, 1) => (Vec3::X, Vec3::Y),
        (0, 0, -1) => (Vec3::NEG_X, Vec3::Y),
        (1, 0, 0) => (Vec3::NEG_Z, Vec3::Y),
        (-1, 0, 0) => (Vec3::Z, Vec3::Y),
        (0, 1, 0) => (Vec3::X, Vec3::NEG_Z),
        (0, -1, 0) => (Vec3::X, Vec3::Z),
        _ => panic!("not a box face: {n}"),
    }
}

#[test]
fn a_box_maps_the_whole_texture_upright_on_each_face() {
    let half = Vec3::new(2.0, 1.0, 3.0);
    for m in [
        vrml2("Box { size 4 2 6 }", true),
        inventor("Cube { width 4 height 2 depth 6 }", true),
    ] {
        let mut faces = HashSet::new();
        for &t in &m.triangles {
            let (u_axis, v_axis) = box_face_axes(normal(&m, t));
            faces.insert(normal(&m, t).round().to_array().map(|x| x as i32));
            for v in t {
                let p = m.positions[v as usize] / half;
                let expected = [0.5 + 0.5 * p.dot(u_axis), 0.5 + 0.5 * p.dot(v_axis)];
                assert_eq!(uv(&m, v), expected, "corner {p} of a face");
            }
        }
        assert_eq!(faces.len(), 6, "every face was seen");
        // Known corners: the front face's top right is the image's top right, the top face's
        // back left (-x, -z) its top left, the right face's front bottom its bottom left.
        let at = |p: Vec3, n: Vec3| -> [f32; 2] {
            let t = m
                .triangles
                .iter()
                .find(|&&t| {
                    normal(&m, t).dot(n) > 0.99
                        && t.iter().any(|&v| m.positions[v as usize] == p * half)
                })
                .unwrap_or_else(|| panic!("no face {n} at {p}"));
            let v = t
                .iter()
                .find(|&&v| m.positions[v as usize] == p * half)
                .unwrap();
            uv(&m, *v)
        };
        assert_eq!(at(Vec3::new(1.0, 1.0, 1.0), Vec3::Z), [1.0, 1.0]);
        assert_eq!(at(Vec3::new(-1.0, -1.0, 1.0), Vec3::Z), [0.0, 0.0]);
        assert_eq!(at(Vec3::new(-1.0, 1.0, -1.0), Vec3::Y), [0.0, 1.0]);
        assert_eq!(at(Vec3::new(1.0, -1.0, 1.0), Vec3::X), [0.0, 0.0]);
        assert_eq!(at(Vec3::new(1.0, -1.0, -1.0), Vec3::NEG_Z), [0.0, 0.0]);
    }
}

#[test]
fn a_sphere_wraps_from_the_back_with_v_from_the_bottom_pole() {
    // Complexity 0.4: 12 slices (a meridian through -x, +z and +x) and 12 stacks.
    let m = inventor("Complexity { value 0.4 } Sphere { radius 2 }", true);
    let c = m.texcoords.as_ref().unwrap();
    assert!(c.iter().flatten().all(|&x| (0.0..=1.0).contains(&x)));
    let mut front = Vec::new();
    for (i, &p) in m.positions.iter().enumerate() {
        let [u, v] = c[i];
        assert!(u_fits(p, u), "({u}, {v}) at {p}");
        // v from 0 at the bottom pole to 1 at the top, evenly in latitude.
        assert!(
            near(
                v,
                1.0 - (p.y / 2.0).clamp(-1.0, 1.0).acos() / std::f32::consts::PI
            ),
            "v {v} at {p}"
        );
        if p.x.abs() < 1e-5 && p.z > 0.0 {
            front.push(u);
        }
        if p.z.abs() < 1e-5 && p.x.abs() > 1e-5 {
            assert!(near(u, if p.x < 0.0 { 0.25 } else { 0.75 }), "u {u} at {p}");
        }
    }
    // The meridian through +z is the middle of the image: u = 0.5 on each of its 10 rings.
    assert_eq!(front.len(), 10);
    assert!(front.iter().all(|&u| near(u, 0.5)), "{front:?}");
    // Poles: one copy per slice, at the middle of its slice; v = 1 on top, 0 below.
    for (y, v) in [(2.0, 1.0), (-2.0, 0.0)] {
        let mut us: Vec<f32> = (0..m.positions.len())
            .filter(|&i| m.positions[i] == Vec3::new(0.0, y, 0.0))
            .map(|i| {
                assert_eq!(c[i][1], v);
                c[i][0]
            })
            .collect();
        us.sort_by(f32::total_cmp);
        let expected: Vec<f32> = (0..12).map(|j| (j as f32 + 0.5) / 12.0).collect();
        assert_eq!(us, expected, "pole at y = {y}");
    }
    // Every triangle faces the same way in the texture (none mirrored or flat).
    for t in &m.triangles {
        let [a, b, d] = t.map(|v| c[v as usize]);
        let area = (b[0] - a[0]) * (d[1] - a[1]) - (d[0] - a[0]) * (b[1] - a[1]);
        assert!(area > 0.0, "{t:?}: {a:?} {b:?} {d:?}");
    }
}

#[test]
fn cylinder_and_cone_sides_wrap_around_and_caps_cut_a_circle_out_of_the_texture() {
    for (m, h, r) in [
        (vrml2("Cylinder { radius 2 height 4 }", true), 2.0, 2.0),
        (inventor("Cylinder { radius 2 height 4 }", true), 2.0, 2.0),
        (vrml2("Cone { bottomRadius 2 height 4 }", true), 2.0, 2.0),
        (inventor("Cone { bottomRadius 2 height 4 }", true), 2.0, 2.0),
    ] {
        let (mut side, mut top, mut bottom) = (0, 0, 0);
        for &t in &m.triangles {
            let n = normal(&m, t);
            for v in t {
                let p = m.positions[v as usize];
                let [u, tv] = uv(&m, v);
                if n.y > 0.99 {
                    // The top: upright when the top is tilted towards +z (-z at the image's top).
                    assert!(near(u, 0.5 + p.x / (2.0 * r)) && near(tv, 0.5 - p.z / (2.0 * r)));
                    top += 1;
                } else if n.y < -0.99 {
                    // The bottom: upright when the top is tilted towards -z.
                    assert!(near(u, 0.5 + p.x / (2.0 * r)) && near(tv, 0.5 + p.z / (2.0 * r)));
                    bottom += 1;
                } else {
                    assert!(u_fits(p, u), "side ({u}, {tv}) at {p}");
                    assert!(near(tv, (p.y + h) / (2.0 * h)), "side v {tv} at {p}");
                    side += 1;
                }
            }
        }
        let cone = top == 0;
        assert_eq!(
            (side, top, bottom),
            if cone {
                (20 * 3, 0, 18 * 3)
            } else {
                (40 * 3, 18 * 3, 18 * 3)
            }
        );
        // Caps' rims are the circle inscribed in the image: their points at -z, -x, +z.
        let rim = |p: Vec3, n: f32| {
            m.triangles
                .iter()
                .filter(|&&t| normal(&m, t).y * n > 0.99)
                .flatten()
                .find(|&&v| (m.positions[v as usize] - p).length() < 1e-5)
                .map(|&v| uv(&m, v))
        };
        let c = |a: [f32; 2], b: [f32; 2]| near(a[0], b[0]) && near(a[1], b[1]);
        assert!(c(rim(Vec3::new(0.0, -h, -r), -1.0).unwrap(), [0.5, 0.0]));
        assert!(c(rim(Vec3::new(-r, -h, 0.0), -1.0).unwrap(), [0.0, 0.5]));
        if !cone {
            assert!(c(rim(Vec3::new(0.0, h, -r), 1.0).unwrap(), [0.5, 1.0]));
            assert!(c(rim(Vec3::new(0.0, h, r), 1.0).unwrap(), [0.5, 0.0]));
        }
    }
}

/// Each triangle as its corners' position bits, sorted: the surface welded by position.
fn welded_triangles(m: &Model) -> Vec<[[u32; 3]; 3]> {
    let mut v: Vec<[[u32; 3]; 3]> = m
        .triangles
        .iter()
        .map(|t| {
            let c = t.map(|i| {
                (m.positions[i as usize] + Vec3::ZERO)
                    .to_array()
                    .map(f32::to_bits)
            });
            // Rotate so the smallest corner comes first, keeping the orientation.
            let k = (0..3).min_by_key(|&k| c[k]).unwrap();
            [c[k], c[(k + 1) % 3], c[(k + 2) % 3]]
        })
        .collect();
    v.sort();
    v
}

#[test]
fn seam_copies_share_positions_and_weld_back_into_the_untextured_surface() {
    for geometry in [
        "Box {}",
        "Sphere {}",
        "Cylinder {}",
        "Cone {}",
        "Cylinder { bottom FALSE }",
    ] {
        let plain = vrml2(geometry, false);
        let textured = vrml2(geometry, true);
        // Same points, the same triangles between them, the same orientation.
        assert_eq!(
            welded_triangles(&textured),
            welded_triangles(&plain),
            "{geometry}"
        );
        let mut copies: HashMap<[u32; 3], usize> = HashMap::new();
        for p in &textured.positions {
            *copies.entry(p.to_array().map(f32::to_bits)).or_default() += 1;
        }
        assert_eq!(
            copies.len(),
            plain.positions.len(),
            "{geometry}: distinct points"
        );
    }
    // The sphere's copies: 15 per pole, 2 per ring at the back, 1 elsewhere.
    let m = vrml2("Sphere {}", true);
    let mut copies: HashMap<[u32; 3], usize> = HashMap::new();
    for p in &m.positions {
        *copies.entry(p.to_array().map(f32::to_bits)).or_default() += 1;
    }
    let mut histogram: HashMap<usize, usize> = HashMap::new();
    for &n in copies.values() {
        *histogram.entry(n).or_default() += 1;
    }
    assert_eq!(histogram, HashMap::from([(15, 2), (2, 13), (1, 13 * 14)]));
}

/// Closed and consistently oriented once welded by position, with no triangle between two
/// copies of one point: each directed edge once, its reverse once. Returns 6 × the signed
/// volume.
fn welded_closed_volume(m: &Model) -> Option<f64> {
    let mut id: HashMap<[u32; 3], u32> = HashMap::new();
    let keys: Vec<u32> = m
        .positions
        .iter()
        .map(|p| {
            let n = id.len() as u32;
            *id.entry((*p + Vec3::ZERO).to_array().map(f32::to_bits))
                .or_insert(n)
        })
        .collect();
    let mut edges: HashMap<(u32, u32), u32> = HashMap::new();
    let mut volume = 0.0;
    for t in &m.triangles {
        let w = t.map(|v| keys[v as usize]);
        if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] {
            return None;
        }
        for k in 0..3 {
            *edges.entry((w[k], w[(k + 1) % 3])).or_default() += 1;
        }
        let [a, b, c] = t.map(|v| m.positions[v as usize].as_dvec3());
        volume += a.dot(b.cross(c));
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
        .then_some(volume)
}

#[test]
fn a_textured_sphere_and_cylinder_decimated_by_half_stay_closed_and_keep_their_coordinates() {
    for geometry in ["Sphere { radius 2 }", "Cylinder { radius 1 height 3 }"] {
        let scene = parse_str(&vrml2_text(geometry, true), "t.wrl")
            .unwrap_or_else(|e| panic!("{e}"))
            .scene;
        let scene = build_scene(scene, true);
        let before = scene.models[0].clone();
        let volume = welded_closed_volume(&before).expect("the input is closed once welded");
        for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
            let mut out = scene.clone();
            let params = Params {
                target: Target::RemovePercent(50.0),
                algorithm,
                ..Params::default()
            };
            simplify_scene(&mut out, &params, &mut |_| {});
            let m = &out.models[0];
            assert!(
                m.triangles.len() * 10 < before.triangles.len() * 8,
                "{geometry} {algorithm:?}: {} of {} triangles left",
                m.triangles.len(),
                before.triangles.len()
            );
            let kept = welded_closed_volume(m).unwrap_or_else(|| {
                panic!("{geometry} {algorithm:?}: a crack or a sliver once welded")
            });
            assert!(
                kept > 0.8 * volume && kept <= volume * 1.01,
                "{geometry} {algorithm:?}: volume {kept} of {volume}"
            );
            let c = m.texcoords.as_ref().expect("coordinates kept");
            assert_eq!(c.len(), m.positions.len());
            assert!(
                c.iter().flatten().all(|&x| (0.0..=1.0).contains(&x)),
                "{geometry} {algorithm:?}: coordinates outside 0..1"
            );
        }
    }
}

#[test]
fn texture_transforms_move_the_primitives_coordinates() {
    // VRML 2.0: translated by (0.5, 0), then scaled by 2 (the centre at 0).
    let plain = vrml2("Box {}", true);
    let text = vrml2_text("Box {}", true).replace(
        "url \"checker.png\" }",
        "url \"checker.png\" } textureTransform TextureTransform { translation 0.5 0 scale 2 2 }",
    );
    let moved = one_model(&text, "t.wrl");
    assert_moved(&plain, &moved, |[u, v]| [(u + 0.5) * 2.0, v * 2.0]);
    // Inventor: scaled by 2, then translated by (0.5, 0); two nodes accumulate, and a
    // Separator ends their scope.
    let plain = inventor("Sphere {}", true);
    let moved = inventor(
        "Texture2Transform { translation 0.5 0 } Texture2Transform { scaleFactor 2 2 } Sphere {}",
        true,
    );
    assert_moved(&plain, &moved, |[u, v]| [u * 2.0 + 0.5, v * 2.0]);
    let scene = parse_str(
        "#Inventor V2.1 ascii\nSeparator { Texture2 { filename \"c.png\" } \
         Separator { Texture2Transform { rotation 1.5707964 } Cube {} } Cube {} }\n",
        "t.iv",
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .scene;
    let [turned, kept] = [&scene.models[0], &scene.models[1]].map(|m| m.texcoords.clone().unwrap());
    assert_eq!(kept, plain_cube_texcoords());
    // A quarter turn counter-clockwise: (u, v) -> (-v, u).
    for (a, b) in kept.iter().zip(&turned) {
        assert!(near(b[0], -a[1]) && near(b[1], a[0]), "{a:?} -> {b:?}");
    }
}

/// Asserts that each of `moved`'s texture coordinates is `map` of `plain`'s, pair by pair.
fn assert_moved(plain: &Model, moved: &Model, map: impl Fn([f32; 2]) -> [f32; 2]) {
    let [plain, moved] = [plain, moved].map(|m| m.texcoords.as_deref().expect("coordinates"));
    for (a, b) in plain.iter().zip(moved) {
        let [u, v] = map(*a);
        assert!(near(b[0], u) && near(b[1], v), "{a:?} -> {b:?}");
    }
}

fn plain_cube_texcoords() -> Vec<[f32; 2]> {
    inventor("Cube {}", true).texcoords.unwrap()
}

#[test]
fn a_textured_sphere_written_to_vrml2_and_obj_reads_back_with_its_coordinates() {
    let dir = tempfile::tempdir().unwrap();
    let scene = Scene {
        models: vec![vrml2("Sphere { radius 2 }", true)],
    };
    for name in ["sphere.wrl", "sphere.obj"] {
        let path = dir.path().join(name);
        write_scene(&scene, &path).unwrap_or_else(|e| panic!("{name}: {e}"));
        let back = read_scene(&path)
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .scene;
        assert_eq!(back.models.len(), 1, "{name}");
        assert_eq!(
            back.models[0].positions.len(),
            238,
            "{name}: the seams stay cut"
        );
        // Exactly, but for the sign of zero (OBJ writes -0 as 0).
        let values = |s: &Scene| -> Vec<[f32; 5]> {
            textured_corners(s)
                .into_iter()
                .map(|c| c.map(|x| f32::from_bits(x) + 0.0))
                .collect()
        };
        assert_eq!(values(&back), values(&scene), "{name}");
    }
}

#[test]
fn textures_the_reader_cannot_use_are_named_in_a_warning() {
    // An Inventor image given inline, a VRML 2.0 PixelTexture: the shapes are read
    // untextured, and the warning (kept under -q: it names what is lost) says why.
    for (text, name, expected) in [
        (
            "#Inventor V2.1 ascii\nSeparator { Texture2 { image 2 1 3 0xff0000 0x0000ff }\nCube {} }\n",
            "t.iv",
            "line 2: Texture2's inline 'image' ignored",
        ),
        (
            "#VRML V2.0 utf8\nShape { appearance Appearance {\ntexture PixelTexture { image 1 1 1 0xff } }\n\
             geometry Sphere {} }\n",
            "t.wrl",
            "'PixelTexture' unsupported node(s) skipped, the first at line 3",
        ),
    ] {
        let out = parse_str(text, name).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(out.scene.models.len(), 1, "{name}");
        assert!(out.scene.models[0].texcoords.is_none(), "{name}");
        assert!(
            out.warnings.iter().any(|w| w.message.contains(expected)),
            "{name}: {:?}",
            out.warnings
        );
        assert!(out.warnings.iter().any(|w| w.loses_data()));
    }
}

/// Each vertex's (position, texture coordinates), sorted, for comparing whatever the order.
fn mapped(m: &Model) -> Vec<([f32; 3], [f32; 2])> {
    let c = m.texcoords.as_ref().expect("texture coordinates");
    let mut v: Vec<_> = m
        .positions
        .iter()
        .map(|p| p.to_array())
        .zip(c.iter().copied())
        .collect();
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v
}

#[test]
fn face_sets_and_grids_without_coordinates_get_the_default_mapping_under_a_texture() {
    // A quad 4 long in x, 1 in y, 2 in z: s along x (the longest side) from 0 to 1, t along
    // z (the next) from 0 to 2 / 4.
    let quad = "coord Coordinate { point [ 0 0 0, 4 0 0, 4 1 2, 0 1 2 ] } coordIndex [ 0 1 2 3 ]";
    let expected = vec![
        ([0.0, 0.0, 0.0], [0.0, 0.0]),
        ([0.0, 1.0, 2.0], [0.0, 0.5]),
        ([4.0, 0.0, 0.0], [1.0, 0.0]),
        ([4.0, 1.0, 2.0], [1.0, 0.5]),
    ];
    let m = vrml2(&format!("IndexedFaceSet {{ {quad} }}"), true);
    assert_eq!(mapped(&m), expected);
    assert!(vrml2(&format!("IndexedFaceSet {{ {quad} }}"), false)
        .texcoords
        .is_none());
    let inventor_quad = "Coordinate3 { point [ 0 0 0, 4 0 0, 4 1 2, 0 1 2 ] } \
                         IndexedFaceSet { coordIndex [ 0, 1, 2, 3, -1 ] }";
    assert_eq!(mapped(&inventor(inventor_quad, true)), expected);
    // Equal sides: x before y before z. A square in x and y, 1 deep in z.
    let m = inventor(
        "Coordinate3 { point [ 0 0 0, 2 0 1, 2 2 1, 0 2 0 ] } FaceSet { numVertices 4 }",
        true,
    );
    assert_eq!(
        mapped(&m),
        vec![
            ([0.0, 0.0, 0.0], [0.0, 0.0]),
            ([0.0, 2.0, 0.0], [0.0, 1.0]),
            ([2.0, 0.0, 1.0], [1.0, 0.0]),
            ([2.0, 2.0, 1.0], [1.0, 1.0]),
        ]
    );
    // Coordinates the file gives win over the default.
    let m = inventor(
        &format!("TextureCoordinate2 {{ point [ 0 0, 0.5 0, 0.5 0.5, 0 0.5 ] }} {inventor_quad}"),
        true,
    );
    assert_eq!(m.texcoords.unwrap()[2], [0.5, 0.5]);
    // An ElevationGrid spans its grid: s along x, t along z, each from 0 to 1.
    let m = vrml2(
        "ElevationGrid { xDimension 3 zDimension 2 xSpacing 2 zSpacing 5 \
         height [ 0 1 0, 3 0 2 ] }",
        true,
    );
    for (p, uv) in mapped(&m) {
        assert_eq!(uv, [p[0] / 4.0, p[2] / 5.0], "at {p:?}");
    }
    assert_eq!(mapped(&m).last().unwrap(), &([4.0, 2.0, 5.0], [1.0, 1.0]));
}

#[test]
fn an_extrusion_maps_u_along_its_cross_section_and_v_along_its_spine() {
    // A square cross-section (closed, sides 2 long) along a straight spine 1 then 2 long.
    let geometry = "Extrusion { spine [ 0 0 0, 0 1 0, 0 3 0 ] \
                    crossSection [ 1 1, 1 -1, -1 -1, -1 1, 1 1 ] }";
    let plain = vrml2(geometry, false);
    let m = vrml2(geometry, true);
    // 12 points; textured, the sides' 3 × 5 pairs (the square's end meets its start at
    // u = 1) and each cap's 4.
    assert_eq!((plain.positions.len(), plain.triangles.len()), (12, 20));
    assert_eq!((m.positions.len(), m.triangles.len()), (15 + 4 + 4, 20));
    assert_eq!(welded_triangles(&m), welded_triangles(&plain));
    let (mut side, mut cap) = (HashMap::new(), HashMap::new());
    for &t in &m.triangles {
        let on_cap = normal(&m, t).y.abs() > 0.99;
        for v in t {
            let key = m.positions[v as usize].to_array().map(f32::to_bits);
            let map = if on_cap { &mut cap } else { &mut side };
            map.entry(key).or_insert_with(Vec::new).push(uv(&m, v));
        }
    }
    let at = |map: &HashMap<[u32; 3], Vec<[f32; 2]>>, p: [f32; 3]| {
        let mut v = map[&p.map(f32::to_bits)].clone();
        v.sort_by(|a, b| a.partial_cmp(b).unwrap());
        v.dedup();
        v
    };
    // The cross-section's second point (1, -1) a quarter along it, the spine's middle point
    // a third along it; the first point is both ends of the square (u = 0 and 1).
    assert_eq!(at(&side, [1.0, 1.0, -1.0]), [[0.25, 1.0 / 3.0]]);
    assert_eq!(at(&side, [1.0, 3.0, 1.0]), [[0.0, 1.0], [1.0, 1.0]]);
    // Caps: the square spans the texture, u along x, v along z.
    assert_eq!(at(&cap, [1.0, 0.0, -1.0]), [[1.0, 0.0]]);
    assert_eq!(at(&cap, [-1.0, 3.0, 1.0]), [[0.0, 1.0]]);
}
