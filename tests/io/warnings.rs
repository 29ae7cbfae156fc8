//! Reader warnings as the command line prints them: grouped by kind (nodes skipped before
//! attributes, materials, then notes), whatever the order in the file; `-q` keeps only those
//! that lose data.

use decimate_core::io::{parse_str, WarningKind};

use crate::support::binary::decimate;

/// An OBJ whose warnings come in the file in the opposite order to their kinds'.
const MIXED: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nusemtl\nfrob 1\nf 1/1 2/1 3/1\nf 2 4 3\n";

#[test]
fn warnings_are_typed_with_kind_line_and_count() {
    let o = parse_str(MIXED, "m.obj").unwrap();
    let kinds: Vec<WarningKind> = o.warnings.iter().map(|w| w.kind).collect();
    assert_eq!(
        kinds,
        [
            WarningKind::SkippedMaterial,
            WarningKind::SkippedNode,
            WarningKind::SkippedAttribute
        ],
        "{:?}",
        o.warnings
    );
    assert_eq!(o.warnings[0].line, Some(6));
    assert_eq!(o.warnings[1].line, Some(7));
    assert!(o
        .warnings
        .iter()
        .all(|w| w.file.as_deref() == Some("m.obj".as_ref())));
}

#[test]
fn the_binary_prints_warnings_grouped_by_kind_and_q_keeps_the_lossy_ones() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.obj"), MIXED).unwrap();
    let o = decimate(dir.path(), &["m.obj", "nogui", "-p", "0", "-o", "out.ply"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    let at = |needle: &str| {
        err.find(needle)
            .unwrap_or_else(|| panic!("no '{needle}' in {err}"))
    };
    let (node, attribute, material) = (
        at("unknown OBJ statement 'frob'"),
        at("texture coordinates ignored"),
        at("'usemtl' without a material name"),
    );
    assert!(node < attribute && attribute < material, "{err}");

    // A solid without facets is a note: printed, but not under -q.
    let stl = "solid empty\nendsolid empty\nsolid t\nfacet normal 0 0 1\nouter loop\n\
               vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    std::fs::write(dir.path().join("t.stl"), stl).unwrap();
    let loud = decimate(dir.path(), &["t.stl", "nogui", "-p", "0", "-o", "t.ply"]);
    assert!(String::from_utf8_lossy(&loud.stderr).contains("has no facets"));
    let quiet = decimate(
        dir.path(),
        &["t.stl", "nogui", "-q", "-p", "0", "-o", "t.ply"],
    );
    assert!(quiet.status.success());
    assert!(
        quiet.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&quiet.stderr)
    );
}
