//! Writing VRML 2.0 and PLY and reading the files back: same counts, positions (exactly, as
//! f32 round-trips), colours, names and world placement; the target is replaced atomically.

use decimate_core::io::{read_scene, write_ply, write_vrml2, write_vrml2_to};
use decimate_core::mesh::{Attribute, Model, Scene};
use glam::{Mat4, Quat, Vec3};
use std::path::PathBuf;

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("decimate-io-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn scene() -> Scene {
    let positions = vec![
        Vec3::new(0.1, 0.2, 0.3),
        Vec3::new(1.0 / 3.0, -0.0, 1e-7),
        Vec3::new(12345.678, 0.5, -2.25),
        Vec3::new(-1.0, 3.0e10, 0.7),
    ];
    let triangles = vec![[0, 1, 2], [0, 2, 3]];
    let a = Model {
        name: "Decomposable".into(),
        origin: glam::DVec3::ZERO,
        transform: Mat4::from_scale_rotation_translation(
            Vec3::new(2.0, 0.5, 1.0),
            Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.0).normalize(), 0.7),
            Vec3::new(1.0, -2.0, 3.0),
        ),
        positions: positions.clone(),
        triangles: triangles.clone(),
        colors: Some(Attribute::PerVertex(vec![
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.3, 0.6, 0.9],
        ])),
        normals: Some(Attribute::PerFace(vec![Vec3::Z, Vec3::X])),
        texcoords: None,
        texture: None,
        texture_repeat: [true; 2],
        material: None,
        diffuse: [0.25, 0.5, 0.75],
        crease_angle: Some(0.5),
        solid: true,
        instance: None,
    };
    // A shear (not translation/rotation/scale) and a mirror: baked into the coordinates.
    let mut shear = Mat4::IDENTITY;
    shear.y_axis.x = 0.5;
    let b = Model {
        name: "has space".into(),
        transform: shear * Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)),
        positions: positions[..3].to_vec(),
        triangles: vec![[0, 1, 2]],
        colors: Some(Attribute::PerFace(vec![[0.5, 0.25, 0.125]])),
        ..Model::default()
    };
    Scene { models: vec![a, b] }
}

fn tri_normal(m: &Model, t: [u32; 3], world: bool) -> Vec3 {
    let [a, b, c] = t.map(|i| {
        let p = m.positions[i as usize];
        if world {
            m.transform.transform_point3(p)
        } else {
            p
        }
    });
    (b - a).cross(c - a)
}

#[test]
fn vrml2_round_trip_keeps_counts_positions_colours_and_placement() {
    let dir = temp_dir("rt");
    let path = dir.join("out.wrl");
    let original = scene();
    write_vrml2(&original, &path).unwrap_or_else(|e| panic!("{e}"));
    let back = read_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    let back = back.scene;
    assert_eq!(back.models.len(), 2);
    let (a, b) = (&original.models[0], &back.models[0]);
    assert_eq!(b.name, "Decomposable");
    // Positions are written with shortest round-trip formatting: bit-exact.
    assert_eq!(a.positions, b.positions);
    assert_eq!(a.triangles, b.triangles);
    assert_eq!(a.colors, b.colors);
    assert_eq!(a.normals, b.normals);
    assert_eq!(a.diffuse, b.diffuse);
    assert_eq!(a.crease_angle, b.crease_angle);
    assert!(b.solid);
    assert!(
        a.transform.abs_diff_eq(b.transform, 1e-5),
        "{} vs {}",
        a.transform,
        b.transform
    );

    // The baked model: same world positions, per-face colour, and it still faces the same way
    // in the world.
    let (a, b) = (&original.models[1], &back.models[1]);
    assert_eq!(b.transform, Mat4::IDENTITY);
    assert_eq!(b.positions.len(), 3);
    let world: Vec<Vec3> = a
        .positions
        .iter()
        .map(|&p| a.transform.transform_point3(p))
        .collect();
    for w in &world {
        assert!(
            b.positions
                .iter()
                .any(|q| (*w - *q).length() <= 1e-6 * w.length().max(1.0)),
            "{w} not among {:?}",
            b.positions
        );
    }
    assert_eq!(b.colors, Some(Attribute::PerFace(vec![[0.5, 0.25, 0.125]])));
    // The mirror is baked in: the written triangle faces where the transformed normal of the
    // original (inverse transpose) points, i.e. its winding was reversed.
    let local = tri_normal(a, a.triangles[0], false);
    let intended = glam::Mat3::from_mat4(a.transform).inverse().transpose() * local;
    assert!(tri_normal(b, b.triangles[0], false).dot(intended) > 0.0);
    assert!(!b.solid);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn written_text_has_the_vrml2_shape() {
    let mut out = Vec::new();
    write_vrml2_to(&mut out, &scene()).unwrap();
    let text = String::from_utf8(out).unwrap();
    assert!(text.starts_with("#VRML V2.0 utf8\n"));
    assert!(text.contains("DEF Decomposable Shape {"));
    assert!(!text.contains("DEF has space"));
    assert!(text.contains("ccw TRUE"));
    assert!(text.contains("coordIndex [\n          0, 1, 2, -1,"));
    assert!(text.contains("colorPerVertex FALSE"));
    assert!(text.contains("12345.678 0.5 -2.25"));
}

#[test]
fn failed_write_leaves_the_target_and_no_temporary_file() {
    let dir = temp_dir("atomic");
    let path = dir.join("keep.wrl");
    std::fs::write(&path, "old contents").unwrap();
    // Writing into a directory path fails at rename; the old file must survive untouched.
    let target_dir = dir.join("is_a_dir");
    std::fs::create_dir_all(target_dir.join("x")).unwrap();
    assert!(write_vrml2(&scene(), &target_dir).is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old contents");
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    // A successful write replaces it.
    write_vrml2(&scene(), &path).unwrap();
    assert!(std::fs::read_to_string(&path)
        .unwrap()
        .starts_with("#VRML V2.0"));
    let e = write_vrml2(&scene(), &dir.join("missing/sub/out.wrl")).unwrap_err();
    assert!(e.to_string().contains("missing/sub/out.wrl"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn ply_round_trip_bakes_transforms_and_keeps_vertex_colours() {
    let dir = temp_dir("ply");
    let path = dir.join("out.ply");
    let mut s = scene();
    s.models[1].colors = Some(Attribute::PerVertex(vec![[1.0, 1.0, 1.0]; 3]));
    write_ply(&s, &path).unwrap_or_else(|e| panic!("{e}"));
    let back = read_scene(&path).unwrap_or_else(|e| panic!("{e}")).scene;
    assert_eq!(back.models.len(), 1);
    assert_eq!(back.vertex_count(), 7);
    assert_eq!(back.triangle_count(), 3);
    let m = &back.models[0];
    let w = s.models[0]
        .transform
        .transform_point3(s.models[0].positions[2]);
    assert!(
        m.positions.iter().any(|&p| (p - w).length() < 1e-3),
        "{w} missing"
    );
    let Some(Attribute::PerVertex(c)) = &m.colors else {
        panic!("{:?}", m.colors)
    };
    assert_eq!(c[0], [1.0, 0.0, 0.0]);
    let want = [77.0 / 255.0, 153.0 / 255.0, 230.0 / 255.0];
    assert!(
        c[3].iter().zip(want).all(|(x, y)| (x - y).abs() < 1e-6),
        "{:?}",
        c[3]
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// For `tools/check/vrml-independent`: writes our VRML 2.0 output for the scene above, a
/// hand-written file and any `DECIMATE_SAMPLE_INPUTS` (colon-separated) into
/// `DECIMATE_SAMPLE_DIR`, each with a `.counts` file (`points triangles` per model).
#[test]
#[ignore = "run by tools/check/vrml-independent"]
fn write_samples_for_independent_check() {
    let Ok(dir) = std::env::var("DECIMATE_SAMPLE_DIR") else {
        panic!("set DECIMATE_SAMPLE_DIR");
    };
    let dir = PathBuf::from(dir);
    std::fs::create_dir_all(&dir).unwrap();
    let mut scenes = vec![("synthetic".to_string(), scene())];
    let inputs = std::env::var("DECIMATE_SAMPLE_INPUTS").unwrap_or_default();
    for f in ["tests/data/colored_v2.wrl", "tests/data/l_shape_v1.wrl"]
        .into_iter()
        .chain(inputs.split(':').filter(|s| !s.is_empty()))
    {
        let s = read_scene(std::path::Path::new(f)).unwrap_or_else(|e| panic!("{e}"));
        let stem = std::path::Path::new(f)
            .file_stem()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        scenes.push((stem, s.scene));
    }
    for (stem, s) in scenes {
        write_vrml2(&s, &dir.join(format!("{stem}.wrl"))).unwrap();
        let counts: String = s
            .models
            .iter()
            .map(|m| format!("{} {}\n", m.positions.len(), m.triangles.len()))
            .collect();
        std::fs::write(dir.join(format!("{stem}.counts")), counts).unwrap();
    }
}
