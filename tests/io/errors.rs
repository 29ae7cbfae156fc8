//! Malformed files: each gives a `ReadError` naming the file (and the line where there is
//! one), never a panic or a stack overflow.

use decimate_core::io::{parse_bytes, parse_str, read_scene, ReadError};
use std::path::Path;

/// Parses `src` as `bad.wrl`, expecting an error; returns (line, message as displayed).
fn fail(src: &str) -> (Option<usize>, String) {
    match parse_str(src, "bad.wrl") {
        Ok(o) => panic!("expected an error, parsed {} models", o.scene.models.len()),
        Err(e) => {
            let text = e.to_string();
            assert!(
                text.starts_with("bad.wrl"),
                "message does not name the file: {text}"
            );
            let line = match e {
                ReadError::Syntax { line, .. } => Some(line),
                _ => None,
            };
            (line, text)
        }
    }
}

#[test]
fn wrong_bracket_after_a_node_name() {
    let (line, msg) = fail("#VRML V1.0 ascii\n\nSeparator [\n}");
    assert_eq!(line, Some(3));
    assert_eq!(msg, "bad.wrl:3: expected '{' after 'Separator', found '['");
}

#[test]
fn truncated_file() {
    let (line, msg) =
        fail("#VRML V1.0 ascii\nSeparator {\n  Coordinate3 { point [ 0 0 0,\n 1 0 0,");
    assert_eq!(line, Some(4));
    assert!(msg.contains("end of file"), "{msg}");
    let (_, msg) = fail("#VRML V2.0 utf8\nTransform {\n children [\n");
    assert!(msg.contains("end of file"), "{msg}");
}

#[test]
fn out_of_range_coordinate_index_names_the_coord_index_line() {
    let (line, msg) = fail(
        "#VRML V1.0 ascii\nSeparator {\n Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n IndexedFaceSet {\n  coordIndex [ 0, 1, 3, -1 ]\n }\n}",
    );
    assert_eq!(line, Some(5));
    assert!(
        msg.contains("index 3") && msg.contains("out of range"),
        "{msg}"
    );
    let (_, msg) = fail("#VRML V1.0 ascii\nSeparator { IndexedFaceSet { coordIndex [ 0 1 -5 ] } }");
    assert!(msg.contains("-5"), "{msg}");
    let (_, msg) = fail(
        "#VRML V1.0 ascii\nSeparator { Coordinate3 { point [ 0 0 0 ] } FaceSet { numVertices [ 3 ] } }",
    );
    assert!(msg.contains("numVertices"), "{msg}");
}

#[test]
fn nan_and_infinite_coordinates() {
    let (line, msg) = fail("#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n coord Coordinate { point [ 0 0 nan ] } } }");
    assert_eq!(line, Some(3));
    assert!(
        msg.contains("expected a number") && msg.contains("'nan'"),
        "{msg}"
    );
    let (line, msg) = fail("#VRML V1.0 ascii\nCoordinate3 {\n point [ 0 0 1e39 ] }");
    assert_eq!(line, Some(3));
    assert!(msg.contains("not finite"), "{msg}");
}

#[test]
fn unbalanced_braces() {
    let (line, msg) = fail("#VRML V1.0 ascii\nSeparator {\n Group { }\n}\n}\n");
    assert_eq!(line, Some(5));
    assert!(msg.contains("found '}'"), "{msg}");
    let (line, msg) = fail("#VRML V1.0 ascii\nSeparator {\n Group {\n}\n");
    assert!(
        msg.contains("expected '}' to close 'Separator' opened at line 2"),
        "{msg}"
    );
    assert_eq!(line, Some(5));
    // Inside a skipped unknown node too.
    let (_, msg) = fail("#VRML V1.0 ascii\nMystery { a [ 1 2 }\n");
    assert!(msg.contains("expected ']'"), "{msg}");
}

#[test]
fn undefined_use() {
    let (line, msg) = fail("#VRML V1.0 ascii\nSeparator {\n\n USE Nowhere\n}");
    assert_eq!(line, Some(4));
    assert!(msg.contains("Nowhere"), "{msg}");
}

#[test]
fn unterminated_string() {
    let (line, msg) = fail("#VRML V1.0 ascii\nSeparator {\n Info { string \"never closed }\n}\n");
    assert_eq!(line, Some(3));
    assert!(msg.contains("unterminated string"), "{msg}");
}

#[test]
fn very_deep_nesting_is_an_error_not_a_stack_overflow() {
    let n = 100_000;
    let src = format!(
        "#VRML V1.0 ascii\n{}{}",
        "Separator {\n".repeat(n),
        "}\n".repeat(n)
    );
    let (line, msg) = fail(&src);
    assert!(msg.contains("nested deeper than"), "{msg}");
    assert_eq!(line, Some(258));
    let src = format!(
        "#VRML V2.0 utf8\n{}{}",
        "Transform { children [\n".repeat(n),
        "] }\n".repeat(n)
    );
    let (_, msg) = fail(&src);
    assert!(msg.contains("nested deeper than"), "{msg}");
    // Unknown nodes are skipped without recursion: deep nesting of them is fine.
    let src = format!(
        "#VRML V1.0 ascii\nCube {{ }}\n{}{}",
        "Mystery {\n".repeat(n),
        "}\n".repeat(n)
    );
    assert!(parse_str(&src, "deep.wrl").is_ok());
}

#[test]
fn def_use_chain_is_refused_not_walked_quadratically() {
    // Each DEF uses the one before and is itself placed in the scene: n shapes, but n²/2
    // node visits. Refused with the line of the walk's last node, not a minutes-long hang.
    let n = 4_000;
    let mut src = String::from("#VRML V1.0 ascii\nSeparator {\nDEF n0 Separator { Cube { } }\n");
    for k in 1..n {
        src += &format!("DEF n{k} Separator {{ USE n{} }}\n", k - 1);
    }
    src += "}\n";
    let (line, msg) = fail(&src);
    assert!(msg.contains("DEF/USE chain"), "{msg}");
    assert!(line.is_some_and(|l| l > 3 && l <= n + 2), "{line:?}");
    // A shorter chain reads: every DEF is drawn once where it stands, so n shapes.
    let mut src = String::from("#VRML V1.0 ascii\nSeparator {\nDEF n0 Separator { Cube { } }\n");
    for k in 1..200 {
        src += &format!("DEF n{k} Separator {{ USE n{} }}\n", k - 1);
    }
    src += "}\n";
    let scene = parse_str(&src, "chain.wrl").map(|o| o.scene);
    assert!(scene.is_ok_and(|s| s.models.len() == 200));
}

#[test]
fn binary_inventor_asks_for_ivcat() {
    let e = parse_bytes(
        b"#Inventor V2.1 binary  \n\0\0\0\x05".to_vec(),
        Path::new("m.iv"),
    )
    .unwrap_err();
    assert!(matches!(e, ReadError::Unsupported { .. }));
    assert_eq!(
        e.to_string(),
        "m.iv: binary Inventor is not supported (convert it with ivcat)"
    );
}

#[test]
fn empty_and_foreign_files() {
    let (line, msg) = fail("");
    assert_eq!(line, Some(1));
    assert!(msg.contains("empty"), "{msg}");
    let (_, msg) = fail("hello world\n");
    assert!(
        msg.contains("not a VRML") && msg.contains("glTF") && msg.contains("hello world"),
        "{msg}"
    );
    // A binary start is shown escaped, not echoed as raw bytes.
    let e = parse_bytes(b"\x7fELF\x02\x01\x01\0\0\0".to_vec(), Path::new("a.bin"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("\\u{7f}ELF\\u{2}"), "{e}");
    assert!(!e.chars().any(|c| c.is_control() && c != '\n'), "{e}");
    // STL is read now (tests/io/formats.rs): a cut-off ASCII solid names its last line.
    let (line, msg) = fail("solid cube\n facet normal 0 0 1\n");
    assert_eq!(line, Some(2), "{msg}");
    assert!(msg.contains("expected 'outer'"), "{msg}");
    let e = parse_bytes(vec![0x1f, 0x8b, 8, 0, 1, 2], Path::new("t.wrl.gz")).unwrap_err();
    assert!(
        e.to_string().starts_with("t.wrl.gz:1: the gzip stream"),
        "{e}"
    );
}

#[test]
fn missing_file_is_an_io_error_naming_it() {
    let e = read_scene(Path::new("/nonexistent/dir/model.wrl")).unwrap_err();
    assert!(matches!(e, ReadError::Io { .. }));
    assert!(
        e.to_string().starts_with("/nonexistent/dir/model.wrl: "),
        "{e}"
    );
}

#[test]
fn bad_field_values() {
    let (line, msg) = fail("#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n ccw MAYBE } }");
    assert_eq!(line, Some(3));
    assert!(
        msg.contains("TRUE or FALSE") && msg.contains("'MAYBE'"),
        "{msg}"
    );
    let (_, msg) = fail("#VRML V1.0 ascii\nIndexedFaceSet { coordIndex [ 0 1 2.5 ] }");
    assert!(msg.contains("expected an integer"), "{msg}");
    let (_, msg) = fail("#VRML V1.0 ascii\nMatrixTransform { matrix 1 0 0 }");
    assert!(msg.contains("16 numbers"), "{msg}");
    let (_, msg) = fail("#VRML V1.0 ascii\nMaterialBinding { value SOMETIMES }");
    assert!(msg.contains("SOMETIMES"), "{msg}");
}

#[test]
fn instancing_bombs_are_refused() {
    // Each level doubles the shapes: 2^25 instances would exhaust memory.
    let mut src = String::from(
        "#VRML V1.0 ascii\nDEF L0 Separator { Coordinate3 { point [ 0 0 0, 1 0 0, 0 1 0 ] } IndexedFaceSet { coordIndex [ 0 1 2 ] } }\n",
    );
    for i in 1..=25 {
        src.push_str(&format!(
            "DEF L{i} Separator {{ USE L{} USE L{} }}\n",
            i - 1,
            i - 1
        ));
    }
    // Either bound may trip first: the shapes made or the nodes walked.
    let (_, msg) = fail(&src);
    assert!(
        msg.contains("expands to more than") || msg.contains("walked more than"),
        "{msg}"
    );
}

#[test]
fn a_texture_url_that_is_not_a_string_names_its_line() {
    let (line, msg) = fail(
        "#VRML V2.0 utf8\nShape {\n appearance Appearance { texture ImageTexture {\n  url [ \"a.png\" 3 ] } }\n}",
    );
    assert_eq!(line, Some(4));
    assert!(msg.contains("a string or ']' in 'url'"), "{msg}");
    let (line, msg) = fail("#Inventor V2.1 ascii\nSeparator {\n Texture2 { filename wood.png }\n}");
    assert_eq!(line, Some(3));
    assert!(msg.contains("a string for 'filename'"), "{msg}");
}

#[test]
fn bad_texture_coordinate_indices_drop_the_coordinates_with_a_warning() {
    // Index 5 of three pairs: the shape is read, without texture coordinates.
    let src = "#VRML V2.0 utf8\nShape { geometry IndexedFaceSet {\n coord Coordinate { point [ 0 0 0, 1 0 0, 0 1 0 ] }\n coordIndex [ 0 1 2 -1 ]\n texCoord TextureCoordinate { point [ 0 0, 1 0, 0 1 ] }\n texCoordIndex [ 0 1 5 -1 ] } }";
    let out = parse_str(src, "t.wrl").unwrap();
    assert_eq!(out.scene.models[0].triangles.len(), 1);
    assert_eq!(out.scene.models[0].texcoords, None);
    assert!(
        out.warnings.iter().any(|w| w
            .message
            .contains("texture coordinate index 5 is out of range")),
        "{:?}",
        out.warnings
    );
}
