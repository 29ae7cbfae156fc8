//! An OBJ's material library in the text forms an OBJ itself may come in: with a UTF-8
//! byte-order mark, with CR-only or CRLF line ends, or both. The binary decimates the
//! textured OBJ to VRML, and the output (read by this file's own few lines) must still
//! show the material: its `ImageTexture` url is the library's `map_Kd` image and its
//! `diffuseColor` the library's `Kd`, with no warning. A UTF-16 library is a warning naming
//! it and its first line; the model is still read and written.

use std::path::Path;
use std::process::{Command, Output};

use crate::support::shapes::Grid;

/// The library: one material, its colour and image (`newmtl` first, where a mark would
/// hide it).
const MTL: &str = "newmtl skin\nKd 0.9 0.6 0.3\nmap_Kd tex/skin.png\n# made by hand\n";

/// A textured 6 x 6 grid using `skin` from `scan.mtl`.
fn grid_obj() -> String {
    let n = 6;
    let mut text = String::from("mtllib scan.mtl\nusemtl skin\n");
    let grid = Grid::square(n);
    for (i, j) in grid.points() {
        let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
        text += &format!("v {x} {y} {}\nvt {x} {y}\n", 0.1 * (3.0 * x).sin() * y);
    }
    for t in grid.triangles() {
        let [a, b, c] = t.map(|p| p + 1);
        text += &format!("f {a}/{a} {b}/{b} {c}/{c}\n");
    }
    text
}

/// Decimates `scan.obj` (beside `scan.mtl` holding `mtl`) in `dir` to `out.wrl`.
fn run(dir: &Path, mtl: &[u8]) -> Output {
    std::fs::create_dir_all(dir.join("tex")).unwrap();
    std::fs::write(dir.join("tex/skin.png"), b"\x89PNG not really").unwrap();
    std::fs::write(dir.join("scan.obj"), grid_obj()).unwrap();
    std::fs::write(dir.join("scan.mtl"), mtl).unwrap();
    Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(["scan.obj", "nogui", "-p", "50", "-o", "out.wrl"])
        .current_dir(dir)
        .output()
        .expect("run decimate")
}

/// The VRML output's texture urls and diffuse colours.
fn looks(text: &str) -> (Vec<String>, Vec<Vec<f32>>) {
    let urls = text
        .lines()
        .filter_map(|l| l.split_once("ImageTexture { url \"")?.1.split_once('"'))
        .map(|(url, _)| url.to_string())
        .collect();
    let colours = text
        .lines()
        .filter_map(|l| l.split_once("diffuseColor ")?.1.split_once(" }"))
        .map(|(c, _)| c.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    (urls, colours)
}

#[test]
fn a_material_library_with_a_mark_or_mac_line_ends_still_colours_and_textures_the_model() {
    let bom = |t: &str| [&[0xEF, 0xBB, 0xBF][..], t.as_bytes()].concat();
    let cr = |t: &str| t.replace('\n', "\r");
    let forms: [(&str, Vec<u8>); 5] = [
        ("plain", MTL.into()),
        ("bom", bom(MTL)),
        ("cr", cr(MTL).into()),
        ("crlf", MTL.replace('\n', "\r\n").into()),
        ("bom+cr", bom(&cr(MTL))),
    ];
    for (form, mtl) in forms {
        let dir = tempfile::tempdir().unwrap();
        let o = run(dir.path(), &mtl);
        let said = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{form}: {said}");
        assert!(!said.contains("warning"), "{form}: {said}");
        let text = std::fs::read_to_string(dir.path().join("out.wrl")).unwrap();
        let (urls, colours) = looks(&text);
        assert_eq!(urls, ["tex/skin.png"], "{form}");
        assert_eq!(colours, [vec![0.9, 0.6, 0.3]], "{form}");
    }
}

#[test]
fn a_utf16_material_library_is_a_warning_naming_it() {
    let mut wide = vec![0xFF, 0xFE];
    MTL.encode_utf16()
        .for_each(|u| wide.extend(u.to_le_bytes()));
    let dir = tempfile::tempdir().unwrap();
    let o = run(dir.path(), &wide);
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{said}");
    assert!(
        said.contains("scan.mtl:1: the file is UTF-16 text"),
        "{said}"
    );
    let text = std::fs::read_to_string(dir.path().join("out.wrl")).unwrap();
    let (urls, _) = looks(&text);
    assert!(urls.is_empty(), "{urls:?}");
}
