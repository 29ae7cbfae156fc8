//! OBJ materials end to end: a photogrammetry-style OBJ + MTL + image decimated by the binary
//! into another folder still shows its texture there (the output's `mtllib`, `usemtl` and
//! `map_Kd`, or VRML's `ImageTexture` url, lead to the same image file, and the `Kd` colour
//! is kept); several materials in one group become one model each; a missing or damaged MTL
//! is a warning naming it, never a failure; texture names are rebased between folders.
//! The outputs are read back by this file's own small readers, not by the crate's.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::support::shapes::Grid;
use decimate_core::io::texture_path::rebase;
use decimate_core::io::{read_scene, write_scene};

/// The image file this test's scans point at.
const IMAGE: &[u8] = b"\xff\xd8\xff\xe0 not really a JPEG";

/// A `n` × `n` grid of squares over the unit square, slightly curved, textured by its own
/// x and y, under `o scan` and `usemtl skin`, naming `mtllib`.
fn grid_obj(n: usize, mtllib: &str) -> String {
    let mut text = format!("mtllib {mtllib}\no scan\nusemtl skin\n");
    let at = |i: usize| i as f32 / n as f32;
    let grid = Grid::square(n);
    for (i, j) in grid.points() {
        let (x, y) = (at(i), at(j));
        text += &format!("v {x} {y} {}\nvt {x} {y}\n", 0.1 * (3.0 * x).sin() * y);
    }
    for t in grid.triangles() {
        let [a, b, c] = t.map(|p| p + 1);
        text += &format!("f {a}/{a} {b}/{b} {c}/{c}\n");
    }
    text
}

/// `root/in/scan.obj` naming `scan.mtl` (with `mtl_text`) and `root/in/tex/skin.jpg`;
/// returns the OBJ's path and the image's.
fn scan(root: &Path, mtl_text: &str) -> (PathBuf, PathBuf) {
    let dir = root.join("in");
    std::fs::create_dir_all(dir.join("tex")).unwrap();
    let image = dir.join("tex/skin.jpg");
    std::fs::write(&image, IMAGE).unwrap();
    std::fs::write(dir.join("scan.mtl"), mtl_text).unwrap();
    let obj = dir.join("scan.obj");
    std::fs::write(&obj, grid_obj(12, "scan.mtl")).unwrap();
    (obj, image)
}

const SKIN_MTL: &str = "# from a scanner\nnewmtl skin\nKa 1 1 1\nKd 0.9 0.6 0.3\nKs 0.5 0.5 0.5\n\
                        illum 2\nmap_Kd -s 1 1 1 -clamp on tex/skin.jpg\n";

fn decimate(input: &Path, output: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_decimate"))
        .arg(input)
        .arg("nogui")
        .args(args)
        .arg("-o")
        .arg(output)
        .output()
        .expect("run decimate")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The rest of each line of `text` that starts with `key` (and a space).
fn statements<'a>(text: &'a str, key: &str) -> Vec<&'a str> {
    text.lines()
        .filter_map(|l| l.trim().strip_prefix(key)?.strip_prefix(' '))
        .map(str::trim)
        .collect()
}

/// One `newmtl` of an MTL file as this test reads it: name, `Kd`, `map_Kd`.
#[derive(Debug, PartialEq)]
struct Mtl {
    name: String,
    kd: Option<[f32; 3]>,
    map_kd: Option<String>,
}

fn read_mtl(text: &str) -> Vec<Mtl> {
    let mut out: Vec<Mtl> = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if let Some(name) = line.strip_prefix("newmtl ") {
            out.push(Mtl {
                name: name.to_string(),
                kd: None,
                map_kd: None,
            });
        } else if let (Some(kd), Some(m)) = (line.strip_prefix("Kd "), out.last_mut()) {
            let v: Vec<f32> = kd.split_whitespace().map(|x| x.parse().unwrap()).collect();
            m.kd = Some([v[0], v[1], v[2]]);
        } else if let (Some(map), Some(m)) = (line.strip_prefix("map_Kd "), out.last_mut()) {
            m.map_kd = Some(map.to_string());
        }
    }
    out
}

/// True when `name`, read from the folder `dir`, is the file `target`.
fn resolves_to(dir: &Path, name: &str, target: &Path) -> bool {
    match (dir.join(name).canonicalize(), target.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

#[test]
fn a_textured_obj_decimated_into_another_folder_still_finds_its_image() {
    for args in [&["-a", "qem", "-p", "60"][..], &["-p", "60"]] {
        let root = tempfile::tempdir().unwrap();
        let (obj, image) = scan(root.path(), SKIN_MTL);
        let out_dir = root.path().join("results");
        std::fs::create_dir_all(&out_dir).unwrap();
        let out = out_dir.join("small.obj");
        let run = decimate(&obj, &out, args);
        assert!(run.status.success(), "{args:?}: {}", stderr(&run));
        assert!(!stderr(&run).contains("warning"), "{}", stderr(&run));

        let text = std::fs::read_to_string(&out).unwrap();
        assert_eq!(statements(&text, "mtllib"), ["small.mtl"], "{args:?}");
        assert_eq!(statements(&text, "usemtl"), ["skin"], "{args:?}");
        assert!(
            text.lines().any(|l| l.starts_with("f ") && l.contains('/')),
            "faces keep their texture coordinates"
        );
        let mtl = read_mtl(&std::fs::read_to_string(out_dir.join("small.mtl")).unwrap());
        assert_eq!(mtl.len(), 1, "{mtl:?}");
        assert_eq!(mtl[0].name, "skin");
        assert_eq!(mtl[0].kd, Some([0.9, 0.6, 0.3]));
        // The input's `-clamp on` is kept; its `-s 1 1 1` (the default scale) is not.
        let map = mtl[0].map_kd.as_deref().expect("map_Kd");
        assert_eq!(map, "-clamp on ../in/tex/skin.jpg");
        let file = map.trim_start_matches("-clamp on ");
        assert!(resolves_to(&out_dir, file, &image), "{map}");
    }
}

#[test]
fn a_textured_obj_written_as_vrml_elsewhere_keeps_its_image_and_colour() {
    let root = tempfile::tempdir().unwrap();
    let (obj, image) = scan(root.path(), SKIN_MTL);
    let out_dir = root.path().join("web/models");
    std::fs::create_dir_all(&out_dir).unwrap();
    let out = out_dir.join("small.wrl");
    let run = decimate(&obj, &out, &["-a", "qem", "-p", "50"]);
    assert!(run.status.success(), "{}", stderr(&run));

    let text = std::fs::read_to_string(&out).unwrap();
    let urls: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split_once("ImageTexture { url \"")?.1.split_once('"'))
        .map(|(url, _)| url)
        .collect();
    assert_eq!(urls, ["../../in/tex/skin.jpg"]);
    assert!(resolves_to(&out_dir, urls[0], &image));
    let diffuse: Vec<Vec<f32>> = text
        .lines()
        .filter_map(|l| l.split_once("diffuseColor ")?.1.split_once(" }"))
        .map(|(c, _)| c.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(diffuse, [vec![0.9, 0.6, 0.3]]);
    // No MTL is written for a VRML output.
    assert!(!out_dir.join("small.mtl").exists());
}

#[test]
fn a_vrml_texture_written_as_obj_in_another_folder_points_at_the_same_image() {
    let root = tempfile::tempdir().unwrap();
    let in_dir = root.path().join("in/dir");
    std::fs::create_dir_all(&in_dir).unwrap();
    let image = in_dir.join("wood.png");
    std::fs::write(&image, IMAGE).unwrap();
    let wrl = in_dir.join("a.wrl");
    std::fs::write(
        &wrl,
        "#VRML V2.0 utf8\nDEF board Shape {\n appearance Appearance {\n  material Material { \
         diffuseColor 1 0.5 0 }\n  texture ImageTexture { url \"wood.png\" }\n }\n geometry \
         IndexedFaceSet {\n  coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }\n  \
         coordIndex [0 1 2 3 -1]\n  texCoord TextureCoordinate { point [0 0, 1 0, 1 1, 0 1] \
         }\n }\n}\n",
    )
    .unwrap();
    let out_dir = root.path().join("out");
    std::fs::create_dir_all(&out_dir).unwrap();
    let out = out_dir.join("b.obj");
    let run = decimate(&wrl, &out, &["-p", "0"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(statements(&text, "mtllib"), ["b.mtl"]);
    assert_eq!(statements(&text, "usemtl"), ["board"]);
    let mtl = read_mtl(&std::fs::read_to_string(out_dir.join("b.mtl")).unwrap());
    assert_eq!(
        mtl,
        [Mtl {
            name: "board".into(),
            kd: Some([1.0, 0.5, 0.0]),
            map_kd: Some("../in/dir/wood.png".into()),
        }]
    );
    assert!(resolves_to(&out_dir, "../in/dir/wood.png", &image));
}

#[test]
fn several_materials_in_one_group_become_one_model_each() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path();
    std::fs::write(
        dir.join("parts.mtl"),
        "newmtl red\nKd 1 0 0\n\nnewmtl blue\nKd 0 0 1\n",
    )
    .unwrap();
    // body: a red triangle, a blue quad, another red triangle (back to red: same model);
    // lid: one triangle, still red (usemtl carries over `o`).
    let obj = dir.join("parts.obj");
    std::fs::write(
        &obj,
        "mtllib parts.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\no body\nusemtl red\n\
         f 1 2 3\nusemtl blue\nf 1 2 3 4\nusemtl red\nf 1 3 4\no lid\nf 1 2 5\n",
    )
    .unwrap();
    let read = read_scene(&obj).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let models: Vec<(&str, usize, Option<&str>, [f32; 3])> = read
        .scene
        .models
        .iter()
        .map(|m| {
            let material = m.material.as_deref();
            (m.name.as_str(), m.triangles.len(), material, m.diffuse)
        })
        .collect();
    assert_eq!(
        models,
        [
            ("body (red)", 2, Some("red"), [1.0, 0.0, 0.0]),
            ("body (blue)", 2, Some("blue"), [0.0, 0.0, 1.0]),
            ("lid", 1, Some("red"), [1.0, 0.0, 0.0]),
        ]
    );

    // Written as OBJ: the same two materials, one `usemtl` per model.
    let out = dir.join("out.obj");
    write_scene(&read.scene, &out).unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(statements(&text, "usemtl"), ["red", "blue", "red"]);
    let mtl = read_mtl(&std::fs::read_to_string(dir.join("out.mtl")).unwrap());
    let kd: Vec<(&str, Option<[f32; 3]>)> = mtl.iter().map(|m| (m.name.as_str(), m.kd)).collect();
    assert_eq!(
        kd,
        [
            ("red", Some([1.0, 0.0, 0.0])),
            ("blue", Some([0.0, 0.0, 1.0]))
        ]
    );
    assert!(mtl.iter().all(|m| m.map_kd.is_none()));
}

#[test]
fn faces_before_the_first_usemtl_are_a_part_of_their_own() {
    let root = tempfile::tempdir().unwrap();
    let obj = root.path().join("g.obj");
    std::fs::write(
        &obj,
        "v 0 0 0\nv 1 0 0\nv 1 1 0\ng shell\nf 1 2 3\nusemtl paint\nf 1 3 2\n",
    )
    .unwrap();
    let read = read_scene(&obj).unwrap();
    let names: Vec<&str> = read.scene.models.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["shell (no material)", "shell (paint)"]);
    // `paint` is used but no library defines it: one warning naming the OBJ.
    assert_eq!(read.warnings.len(), 1, "{:?}", read.warnings);
    let w = &read.warnings[0].message;
    assert!(w.contains("g.obj") && w.contains("'paint'"), "{w}");
}

#[test]
fn a_library_in_a_subfolder_gives_texture_names_relative_to_the_obj() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path();
    std::fs::create_dir_all(dir.join("materials")).unwrap();
    std::fs::write(
        dir.join("materials/scan.mtl"),
        "newmtl skin\nmap_Kd skin.jpg\n",
    )
    .unwrap();
    let obj = dir.join("scan.obj");
    std::fs::write(&obj, grid_obj(2, "materials/scan.mtl")).unwrap();
    let read = read_scene(&obj).unwrap();
    assert!(read.warnings.is_empty(), "{:?}", read.warnings);
    let m = &read.scene.models[0];
    assert_eq!(m.texture.as_deref(), Some("materials/skin.jpg"));
    // No Kd: the default grey stays.
    assert_eq!(m.diffuse, [0.8; 3]);
}

#[test]
fn a_missing_library_is_a_warning_and_the_output_is_still_written() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path();
    let obj = dir.join("scan.obj");
    std::fs::write(&obj, grid_obj(8, "gone.mtl")).unwrap();
    let out = dir.join("out.obj");
    let run = decimate(&obj, &out, &["-p", "50"]);
    let err = stderr(&run);
    assert!(run.status.success(), "{err}");
    let warnings: Vec<&str> = err.lines().filter(|l| l.contains("warning")).collect();
    assert_eq!(warnings.len(), 2, "{err}");
    assert!(warnings[0].contains("scan.obj") && warnings[0].contains("gone.mtl"));
    assert!(warnings[1].contains("'skin'"));
    // The material's name is kept (so the output can still be given one), in grey.
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(statements(&text, "usemtl"), ["skin"]);
    let mtl = read_mtl(&std::fs::read_to_string(dir.join("out.mtl")).unwrap());
    assert_eq!(mtl[0].kd, Some([0.8, 0.8, 0.8]));
    assert_eq!(mtl[0].map_kd, None);
}

#[test]
fn a_damaged_library_line_is_a_warning_naming_file_and_line() {
    let root = tempfile::tempdir().unwrap();
    let (obj, image) = scan(
        root.path(),
        "newmtl skin\nKd 0.5 zero 0.5\nmap_Kd -bogus 3 tex/skin.jpg\nmap_Kd tex/skin.jpg\n\
         map_Bump tex/normal.png\n",
    );
    let out = root.path().join("out.obj");
    let run = decimate(&obj, &out, &["-a", "qem", "-p", "50"]);
    let err = stderr(&run);
    assert!(run.status.success(), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    let mtl_file = root.path().join("in/scan.mtl");
    let at = |line: usize| format!("{}:{line}:", mtl_file.display());
    let warnings: Vec<&str> = err.lines().filter(|l| l.contains("warning")).collect();
    assert_eq!(warnings.len(), 3, "{err}");
    assert!(warnings[0].contains(&at(2)) && warnings[0].contains("'zero'"));
    assert!(warnings[1].contains(&at(3)) && warnings[1].contains("'-bogus'"));
    assert!(warnings[2].contains("map_Bump"));
    // The good map_Kd on line 4 still counts; the bad Kd leaves the default grey.
    let mtl = read_mtl(&std::fs::read_to_string(root.path().join("out.mtl")).unwrap());
    assert_eq!(mtl[0].kd, Some([0.8, 0.8, 0.8]));
    let map = mtl[0].map_kd.as_deref().expect("map_Kd");
    assert!(resolves_to(root.path(), map, &image), "{map}");
}

#[test]
fn a_plain_obj_stays_plain() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path();
    let obj = dir.join("plain.obj");
    let text = grid_obj(6, "x.mtl")
        .lines()
        .filter(|l| !l.starts_with("mtllib") && !l.starts_with("usemtl"))
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(&obj, text).unwrap();
    let out = dir.join("out.obj");
    let run = decimate(&obj, &out, &["-p", "50"]);
    assert!(run.status.success(), "{}", stderr(&run));
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(statements(&written, "mtllib").is_empty());
    assert!(statements(&written, "usemtl").is_empty());
    assert!(!dir.join("out.mtl").exists());
}

#[test]
fn texture_names_are_rebased_between_folders() {
    let root = tempfile::tempdir().unwrap();
    let r = root.path();
    let (from, to) = (r.join("in/dir"), r.join("out"));
    for d in [&from, &to, &r.join("in/shared")] {
        std::fs::create_dir_all(d).unwrap();
    }
    // Relative names: the same file from the new folder.
    assert_eq!(rebase("tex/a.jpg", &from, &to), "../in/dir/tex/a.jpg");
    assert_eq!(rebase("../shared/a.jpg", &from, &to), "../in/shared/a.jpg");
    assert_eq!(rebase("./a.jpg", &from, &r.join("in")), "dir/a.jpg");
    assert_eq!(rebase("tex\\a.jpg", &from, &to), "../in/dir/tex/a.jpg");
    assert_eq!(rebase("a.jpg", &to, &from), "../../out/a.jpg");
    // The same folder, however it is spelled: unchanged.
    assert_eq!(
        rebase("tex/a.jpg", &from, &r.join("in/../in/dir")),
        "tex/a.jpg"
    );
    // Absolute names and URLs: unchanged.
    for name in [
        "/srv/textures/a.jpg",
        "C:\\textures\\a.jpg",
        "http://example.org/a.jpg",
        "file:///srv/a.jpg",
    ] {
        assert_eq!(rebase(name, &from, &to), name);
    }
    // The new name leads to the image itself.
    let image = from.join("tex/a.jpg");
    std::fs::create_dir_all(image.parent().unwrap()).unwrap();
    std::fs::write(&image, IMAGE).unwrap();
    assert!(resolves_to(&to, &rebase("tex/a.jpg", &from, &to), &image));
}

#[test]
fn an_output_beside_the_input_never_replaces_the_input_s_library_unasked() {
    let root = tempfile::tempdir().unwrap();
    let (obj, _) = scan(root.path(), SKIN_MTL);
    let dir = obj.parent().unwrap();
    // `copy.obj` names `scan.mtl`; decimated into `scan.obj` beside it, its output's own
    // library would be `in/scan.mtl`, the very file the input reads its materials from.
    let beside = root.path().join("in/copy.obj");
    std::fs::copy(&obj, &beside).unwrap();
    let target = dir.join("scan.obj");
    let o = decimate(&beside, &target, &["-p", "50"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("scan.mtl: refusing to write over an input file"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("scan.mtl")).unwrap(),
        SKIN_MTL
    );
    // Asked for, it goes ahead.
    let o = decimate(&beside, &target, &["-p", "50", "--overwrite"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_ne!(
        std::fs::read_to_string(dir.join("scan.mtl")).unwrap(),
        SKIN_MTL
    );
}

#[test]
fn formats_that_cannot_hold_the_texture_say_so() {
    let root = tempfile::tempdir().unwrap();
    let (obj, _) = scan(root.path(), SKIN_MTL);
    let out = root.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    let cases = [
        (
            "scan.stl",
            "STL output keeps no texture coordinates (1 model has them)",
        ),
        (
            "scan.off",
            "OFF output does not name the texture image (1 model has them)",
        ),
    ];
    for (name, expected) in cases {
        let o = decimate(&obj, &out.join(name), &["-p", "50"]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let line = format!("warning: {}: {expected}", out.join(name).display());
        assert!(stderr(&o).contains(&line), "{name}: {}", stderr(&o));
    }
    // PLY names the image, OBJ and VRML keep everything: no warning.
    for name in ["scan.ply", "scan.obj", "scan.wrl"] {
        let o = decimate(&obj, &out.join(name), &["-p", "50"]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        assert!(
            !stderr(&o).contains("output keeps no"),
            "{name}: {}",
            stderr(&o)
        );
        assert!(
            !stderr(&o).contains("does not name"),
            "{name}: {}",
            stderr(&o)
        );
    }
}
