//! Whether a texture repeats or clamps to its edge survives the trip through the binary:
//! VRML 2.0's `repeatS`/`repeatT`, Inventor's `Texture2` `wrapS`/`wrapT` and an MTL's
//! `map_Kd -clamp on` are read, kept through decimation, and written as VRML 2.0 and as
//! OBJ + MTL; a wrap value Inventor does not have is refused with its file and line.

use std::path::{Path, PathBuf};

use crate::support::binary::decimate;
use crate::support::shapes::Grid;

/// A fresh scratch folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("texture_wrap-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// An `n × n` grid's points, texture coordinates (twice the image across, so that wrapping
/// matters) and quads as `coordIndex` text.
fn grid(n: usize) -> (String, String, String) {
    let (mut points, mut uvs, mut faces) = (String::new(), String::new(), String::new());
    let grid = Grid::square(n);
    for (i, j) in grid.points() {
        let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
        points += &format!("{x} {y} 0, ");
        uvs += &format!("{} {}, ", 2.0 * x, 2.0 * y);
    }
    for (_, _, [a, b, c, d]) in grid.squares() {
        faces += &format!("{a} {b} {c} {d} -1, ");
    }
    (points, uvs, faces)
}

fn vrml2(repeat: &str) -> String {
    let (points, uvs, faces) = grid(8);
    format!(
        "#VRML V2.0 utf8\nShape {{\n appearance Appearance {{ texture ImageTexture \
         {{ url \"decal.png\" {repeat} }} }}\n geometry IndexedFaceSet {{\n  \
         coord Coordinate {{ point [ {points} ] }}\n  coordIndex [ {faces} ]\n  \
         texCoord TextureCoordinate {{ point [ {uvs} ] }}\n }}\n}}\n"
    )
}

fn inventor(wrap: &str) -> String {
    let (points, uvs, faces) = grid(8);
    format!(
        "#Inventor V2.1 ascii\nSeparator {{\n Texture2 {{ filename \"decal.png\"\n {wrap} }}\n \
         Coordinate3 {{ point [ {points} ] }}\n TextureCoordinate2 {{ point [ {uvs} ] }}\n \
         IndexedFaceSet {{ coordIndex [ {faces} ] }}\n}}\n"
    )
}

/// Decimates `name` in `dir` by half to `out` (no warnings) and reads the result back: its
/// one model's `texture_repeat`, checking it still names `decal.png`.
fn decimate_and_read(dir: &Path, name: &str, out: &str) -> [bool; 2] {
    let run = decimate(dir, &[name, "nogui", "-p", "50", "-o", out]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{name} -> {out}: {stderr}");
    assert!(!stderr.contains("warning"), "{name} -> {out}: {stderr}");
    let scene = decimate_core::io::read_scene(&dir.join(out))
        .unwrap_or_else(|e| panic!("{out}: {e}"))
        .scene;
    let [m] = scene.models.as_slice() else {
        panic!("{name} -> {out}: one model expected");
    };
    assert_eq!(m.texture.as_deref(), Some("decal.png"), "{name} -> {out}");
    m.texture_repeat
}

/// Writes `input` as `name` in a fresh folder and [`decimate_and_read`]s it to `out`; also
/// returns the folder.
fn through(test: &str, name: &str, input: &str, out: &str) -> ([bool; 2], PathBuf) {
    // Tests run at once: each in a directory of its own.
    let dir = scratch(&format!("{test}-{name}-{out}"));
    std::fs::write(dir.join(name), input).unwrap_or_else(|e| panic!("{e}"));
    (decimate_and_read(&dir, name, out), dir)
}

#[test]
fn vrml_and_inventor_wrapping_is_kept_through_decimation_into_vrml() {
    for (label, name, input, expected) in [
        ("vrml default", "in.wrl", vrml2(""), [true, true]),
        ("vrml S", "in.wrl", vrml2("repeatS FALSE"), [false, true]),
        (
            "vrml both",
            "in.wrl",
            vrml2("repeatS FALSE repeatT FALSE"),
            [false, false],
        ),
        ("inventor default", "in.iv", inventor(""), [true, true]),
        (
            "inventor T",
            "in.iv",
            inventor("wrapS REPEAT wrapT CLAMP"),
            [true, false],
        ),
    ] {
        let (repeat, dir) = through(label, name, &input, "out.wrl");
        assert_eq!(repeat, expected, "{label}");
        // Written only where it is not the default, as a VRML 2.0 reader expects it.
        let text = std::fs::read_to_string(dir.join("out.wrl")).unwrap_or_default();
        assert_eq!(text.contains("repeatS FALSE"), !expected[0], "{label}");
        assert_eq!(text.contains("repeatT FALSE"), !expected[1], "{label}");
    }
}

#[test]
fn an_mtl_clamp_comes_in_and_goes_out_as_clamp_on() {
    let dir = scratch("mtl");
    let (_, uvs, _) = grid(8);
    let mut obj = String::from("mtllib in.mtl\nusemtl decal\n");
    for j in 0..=8 {
        for i in 0..=8 {
            obj += &format!("v {} {} 0\n", i as f32 / 8.0, j as f32 / 8.0);
        }
    }
    for uv in uvs.split(", ").filter(|s| !s.is_empty()) {
        obj += &format!("vt {uv}\n");
    }
    for j in 0..8 {
        for i in 0..8 {
            let a = j * 9 + i + 1;
            let quad = [a, a + 1, a + 10, a + 9].map(|v| format!("{v}/{v}"));
            obj += &format!("f {}\n", quad.join(" "));
        }
    }
    std::fs::write(dir.join("in.obj"), obj).unwrap_or_else(|e| panic!("{e}"));
    std::fs::write(
        dir.join("in.mtl"),
        "newmtl decal\nKd 1 1 1\nmap_Kd -clamp on -s 1 1 1 decal.png\n",
    )
    .unwrap_or_else(|e| panic!("{e}"));
    for out in ["out.wrl", "out.obj"] {
        assert_eq!(decimate_and_read(&dir, "in.obj", out), [false; 2], "{out}");
    }
    let mtl = std::fs::read_to_string(dir.join("out.mtl")).unwrap_or_default();
    assert!(mtl.contains("map_Kd -clamp on decal.png"), "{mtl}");
}

#[test]
fn an_inventor_wrap_it_does_not_have_is_named_with_its_line() {
    let dir = scratch("bad-wrap");
    // The wrap field is on line 4 (`inventor` puts the Texture2's fields on a line of their
    // own).
    std::fs::write(dir.join("in.iv"), inventor("wrapS MIRROR")).unwrap_or_else(|e| panic!("{e}"));
    let run = decimate(&dir, &["in.iv", "nogui", "-p", "50", "-o", "out.wrl"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("in.iv:4")
            && stderr.contains("expected REPEAT or CLAMP in Texture2's wrapS, found 'MIRROR'"),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(!dir.join("out.wrl").exists(), "nothing written");
}

#[test]
fn outputs_that_cannot_say_clamp_say_so() {
    // Clamped along s only: an MTL has one switch for both directions.
    let (_, dir) = through("obj", "in.wrl", &vrml2("repeatS FALSE"), "out.wrl");
    let run = decimate(&dir, &["out.wrl", "nogui", "-p", "0", "-o", "again.obj"]);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains(
            "OBJ output writes the texture as repeating where the input clamps it (1 of 1 \
             models; an MTL clamps a texture along both directions or neither)"
        ),
        "{stderr}"
    );
}
