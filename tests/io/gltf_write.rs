//! glTF written: `.glb` and `.gltf` read back equal and pass the Khronos validator
//! (tools/check/gltf-validate.js); PLY → glTF → PLY keeps counts and positions exactly; the
//! command line decimates a `.glb` to valid files; a textured OBJ decimated to `.glb` is
//! drawn textured. (Reading: `gltf.rs`.)

use std::path::Path;
use std::process::Command;

use decimate_core::io::{self, read_scene, write_scene};
use decimate_core::mesh::{shapes, Attribute, Scene};
use glam::{Mat4, Quat, Vec3};
use serde_json::Value;

use super::gltf::{assert_valid, red_over_blue_png, scratch};

/// A scene with what a glTF file can hold: per-vertex colours, normals and texture
/// coordinates with a PNG image beside, per-face colours, two models with equal
/// geometry, a mirrored transform.
fn rich_scene(dir: &Path) -> Scene {
    std::fs::write(dir.join("map.png"), red_over_blue_png()).expect("writes");
    let mut sphere = shapes::bumpy_sphere(6, 10);
    let n = sphere.positions.len();
    sphere.name = "sphere".into();
    sphere.colors = Some(Attribute::PerVertex(
        (0..n).map(|i| [i as f32 / n as f32, 0.5, 0.25]).collect(),
    ));
    sphere.normals = Some(Attribute::PerVertex(
        sphere.positions.iter().map(|p| *p * 3.0).collect(),
    ));
    sphere.texcoords = Some(sphere.positions.iter().map(|p| [p.x, p.y]).collect());
    sphere.texture = Some("map.png".into());
    sphere.texture_repeat = [false, true];
    sphere.solid = true;
    let mut cube = shapes::cube(2, 2.0);
    cube.name = "cube".into();
    let t = cube.triangles.len();
    cube.colors = Some(Attribute::PerFace(
        (0..t).map(|i| [(i % 2) as f32, 0.0, 1.0]).collect(),
    ));
    let mut twin = cube.clone();
    twin.name = "twin".into();
    twin.transform = Mat4::from_scale_rotation_translation(
        Vec3::new(-1.0, 1.0, 2.0),
        Quat::from_rotation_y(0.5),
        Vec3::new(5.0, 0.0, 0.0),
    );
    Scene {
        models: vec![sphere, cube, twin],
    }
}

#[test]
fn written_glb_and_gltf_read_back_equal_and_pass_the_khronos_validator() {
    let dir = scratch("write");
    let scene = rich_scene(&dir);
    let glb = dir.join("out.glb");
    let gltf = dir.join("out.gltf");
    write_scene(&scene, &glb).unwrap_or_else(|e| panic!("{e}"));
    write_scene(&scene, &gltf).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        dir.join("out.bin").is_file(),
        "the .gltf's buffer is beside it"
    );
    assert_valid(&[&glb, &gltf]);
    for path in [&glb, &gltf] {
        let back = read_scene(path).unwrap_or_else(|e| panic!("{e}")).scene;
        assert_eq!(back.models.len(), 3);
        let (a, b) = (&scene.models[0], &back.models[0]);
        assert_eq!(b.positions, a.positions, "{}", path.display());
        assert_eq!(b.triangles, a.triangles);
        assert_eq!(b.colors, a.colors);
        // v is stored flipped (1 - v): exact to a float's rounding.
        let (ta, tb) = (a.texcoords.as_ref(), b.texcoords.as_ref());
        for (x, y) in ta
            .expect("texcoords")
            .iter()
            .zip(tb.expect("texcoords read"))
        {
            assert!(x[0] == y[0] && (x[1] - y[1]).abs() < 1e-6, "{x:?} {y:?}");
        }
        let Some(Attribute::PerVertex(n)) = &b.normals else {
            panic!("no normals")
        };
        for (got, p) in n.iter().zip(&a.positions) {
            assert!((*got - p.normalize()).length() < 1e-6, "unit normals");
        }
        assert_eq!(b.texture_repeat, [false, true]);
        assert!(b.solid);
        let texture = b.texture.as_deref().expect("a texture");
        if path == &glb {
            assert!(texture.starts_with("data:image/png;base64,"), "embedded");
        } else {
            assert_eq!(texture, "map.png");
        }
        // Per-face colours: one vertex per corner, each triangle's colour on its three.
        let (cube, back_cube) = (&scene.models[1], &back.models[1]);
        assert_eq!(back_cube.triangles.len(), cube.triangles.len());
        assert_eq!(back_cube.positions.len(), 3 * cube.triangles.len());
        let Some(Attribute::PerVertex(c)) = &back_cube.colors else {
            panic!("no colours")
        };
        for (t, tri) in back_cube.triangles.iter().enumerate() {
            assert_eq!(c[tri[0] as usize], [(t % 2) as f32, 0.0, 1.0]);
        }
        assert_eq!(back.models[2].transform, scene.models[2].transform);
        assert_eq!(back.models[2].name, "twin");
    }
    // The twins share one mesh in the file.
    let json: Value = serde_json::from_slice(&std::fs::read(&gltf).expect("reads")).expect("json");
    assert_eq!(json["meshes"].as_array().map(Vec::len), Some(2));
    assert_eq!(json["nodes"][1]["mesh"], json["nodes"][2]["mesh"]);
}

#[test]
fn ply_to_gltf_to_ply_keeps_counts_and_positions_exactly() {
    let dir = scratch("ply");
    let mut sphere = shapes::bumpy_sphere(20, 30);
    sphere.name = "sphere".into();
    let scene = Scene {
        models: vec![sphere],
    };
    let ply = dir.join("in.ply");
    io::write_ply(&scene, &ply).unwrap_or_else(|e| panic!("{e}"));
    let original = read_scene(&ply).unwrap_or_else(|e| panic!("{e}")).scene;
    for ext in ["glb", "gltf"] {
        let mid = dir.join(format!("mid.{ext}"));
        write_scene(&original, &mid).unwrap_or_else(|e| panic!("{e}"));
        let back_ply = dir.join(format!("back-{ext}.ply"));
        let mid_scene = read_scene(&mid).unwrap_or_else(|e| panic!("{e}")).scene;
        io::write_ply(&mid_scene, &back_ply).unwrap_or_else(|e| panic!("{e}"));
        let back = read_scene(&back_ply)
            .unwrap_or_else(|e| panic!("{e}"))
            .scene;
        assert_eq!(back.vertex_count(), original.vertex_count());
        assert_eq!(back.triangle_count(), original.triangle_count());
        assert_eq!(back.models[0].positions, original.models[0].positions);
        assert_eq!(back.models[0].triangles, original.models[0].triangles);
    }
}

#[test]
fn the_cli_decimates_a_glb_to_a_valid_glb_and_gltf() {
    let dir = scratch("cli");
    let scene = rich_scene(&dir);
    write_scene(&scene, &dir.join("in.glb")).unwrap_or_else(|e| panic!("{e}"));
    for out in ["out.glb", "out.gltf"] {
        let o = Command::new(env!("CARGO_BIN_EXE_decimate"))
            .args(["in.glb", "nogui", "-p", "50", "-a", "qem", "-o", out])
            .current_dir(&dir)
            .output()
            .expect("runs decimate");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{stderr}");
        assert!(!stderr.contains("warning"), "{stderr}");
        let back = read_scene(&dir.join(out))
            .unwrap_or_else(|e| panic!("{e}"))
            .scene;
        assert_eq!(back.models.len(), 3);
        assert!(back.triangle_count() < scene.triangle_count());
        assert!(back.models[0].texture.is_some());
        assert_valid(&[&dir.join(out)]);
    }
}

use crate::support::shot as shot_support;

const LAVAPIPE: &str = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

/// A flat `n × n` textured grid in the xy plane as OBJ, its material's `map_Kd` the image.
fn write_textured_obj(dir: &Path, n: usize) {
    let mut text = String::from("mtllib grid.mtl\no grid\nusemtl skin\n");
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            text += &format!("v {} {} 0\nvt {u} {v}\n", 2.0 * u - 1.0, 2.0 * v - 1.0);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            text += &format!("f {a}/{a} {b}/{b} {c}/{c}\nf {a}/{a} {c}/{c} {d}/{d}\n");
        }
    }
    std::fs::write(dir.join("grid.obj"), text).expect("writes");
    std::fs::write(
        dir.join("grid.mtl"),
        "newmtl skin\nKd 1 1 1\nmap_Kd map.png\n",
    )
    .expect("writes");
    std::fs::write(dir.join("map.png"), red_over_blue_png()).expect("writes");
}

#[test]
fn a_textured_obj_decimated_to_glb_is_drawn_textured_the_right_way_up() {
    let dir = scratch("shot");
    write_textured_obj(&dir, 12);
    let run = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_decimate"))
            .args(args)
            .current_dir(&dir)
            .env("VK_ICD_FILENAMES", LAVAPIPE)
            .env("VK_DRIVER_FILES", LAVAPIPE)
            .output()
            .expect("runs decimate");
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(o.status.success(), "{args:?}: {stderr}");
        stderr
    };
    run(&[
        "grid.obj", "nogui", "-a", "qem", "-p", "50", "-o", "grid.glb",
    ]);
    // The image travels inside the .glb: the shot is taken with the PNG gone.
    std::fs::remove_file(dir.join("map.png")).expect("removes");
    let stderr = run(&["grid.glb", "shot", "-o", "shot.png", "--size", "320x240"]);
    assert!(!stderr.contains("not drawn"), "{stderr}");
    let image = shot_support::read_png(&dir.join("shot.png"));
    let bg = shot_support::background();
    let (mut top, mut bottom) = (u32::MAX, 0);
    for y in 0..image.height {
        for x in 0..image.width {
            if !shot_support::close(shot_support::pixel(&image, x, y), bg, 6) {
                top = top.min(y);
                bottom = bottom.max(y);
            }
        }
    }
    assert!(bottom > top + 40, "the grid is not visible");
    let third = (bottom - top) / 3;
    let count = |y0: u32, y1: u32| {
        let (mut red, mut blue) = (0, 0);
        for y in y0..y1 {
            for x in 0..image.width {
                let [r, g, b, _] = shot_support::pixel(&image, x, y).map(u32::from);
                red += usize::from(r > 2 * b + 20 && r > 2 * g + 20);
                blue += usize::from(b > 2 * r + 20 && b > 2 * g + 20);
            }
        }
        (red, blue)
    };
    let (red_up, blue_up) = count(top, top + third);
    let (red_down, blue_down) = count(bottom - third, bottom);
    assert!(
        red_up > 200 && blue_up < red_up / 20,
        "upper third: {red_up} red, {blue_up} blue"
    );
    assert!(
        blue_down > 200 && red_down < blue_down / 20,
        "lower third: {red_down} red, {blue_down} blue"
    );
}
