//! Bad requests and broken work folders: a clear message naming the file, exit 1 for a
//! file at fault, 2 for a request that cannot be met; never a panic.

use crate::common::{decimate, plan, s, sphere_ply};

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn missing_and_unsupported_inputs_name_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let work = tmp.path().join("w");
    let missing = tmp.path().join("nope.ply");
    let o = decimate(
        &["tile", "plan", s(&missing), "--work", s(&work), "-p", "90"],
        &[],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("nope.ply"), "{}", stderr(&o));

    let wrl = tmp.path().join("m.wrl");
    std::fs::write(&wrl, "#VRML V2.0 utf8\n").unwrap();
    let o = decimate(&[s(&wrl), "nogui", "--tiles", "auto", "-p", "90"], &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("m.wrl") && stderr(&o).contains("PLY, STL, OBJ and OFF"));

    let bad = tmp.path().join("bad.ply");
    std::fs::write(
        &bad,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
         0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
    )
    .unwrap();
    let o = decimate(
        &["tile", "plan", s(&bad), "--work", s(&work), "-p", "50"],
        &[],
    );
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("bad.ply:13:") && e.contains("vertex index 7 is out of range"),
        "{e}"
    );

    let short = tmp.path().join("short.ply");
    std::fs::write(
        &short,
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n\
         property float y\nproperty float z\nend_header\n\0\0\0\0",
    )
    .unwrap();
    let o = decimate(
        &["tile", "plan", s(&short), "--work", s(&work), "-p", "50"],
        &[],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("ends inside vertex"), "{}", stderr(&o));
}

#[test]
fn bad_indices_and_broken_manifests_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, _) = sphere_ply(tmp.path());
    let work = tmp.path().join("w");
    plan(&input, &work, 2);
    let o = decimate(&["tile", "run", s(&work), "2"], &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("tile 2 does not exist (the plan has tiles 0 to 1)"));
    let o = decimate(&["tile", "run", s(&work)], &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX"));
    let o = decimate(&["tile", "run", s(&work)], &[("SLURM_ARRAY_TASK_ID", "x")]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("SLURM_ARRAY_TASK_ID='x' is not a tile index"));

    std::fs::write(
        work.join("manifest.json"),
        "{\"format\": \"decimate-tiles\",",
    )
    .unwrap();
    let o = decimate(&["tile", "run", s(&work), "0"], &[]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(e.contains("manifest.json") && e.contains("line 1"), "{e}");
    let o = decimate(&["tile", "status", s(&tmp.path().join("none"))], &[]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("manifest.json"));
}

#[test]
fn command_line_mistakes_exit_2() {
    for (args, says) in [
        (
            &["tile", "plan", "in.ply", "-p", "9"][..],
            "needs --work DIR",
        ),
        (
            &["tile", "plan", "in.ply", "--work", "w"][..],
            "needs a target",
        ),
        (
            &[
                "tile", "plan", "in.ply", "--work", "w", "-p", "9", "--tiles", "0",
            ][..],
            "at least 1",
        ),
        (
            &["tile", "run", "w", "1", "2"][..],
            "unexpected argument '2'",
        ),
        (
            &["tile", "merge", "w", "--tiles", "3"][..],
            "unknown option '--tiles'",
        ),
        (
            &["in.ply", "nogui", "--tiles", "auto", "-v", "9"][..],
            "-p or --keep-triangles",
        ),
        (
            &["in.ply", "--tiles", "2", "-p", "9"][..],
            "option of nogui",
        ),
        (
            &["in.ply", "nogui", "-p", "9", "--memory", "2G"][..],
            "option of --tiles",
        ),
        (
            &[
                "in.ply", "nogui", "-p", "9", "--tiles", "auto", "--memory", "2Q",
            ][..],
            "2G",
        ),
    ] {
        let o = decimate(args, &[]);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
    }
}
