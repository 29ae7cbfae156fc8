//! The memory budget of `--tiles`: tiles run in parallel as far as `--memory` allows (the
//! same bytes as one at a time), and welded tiles too big for it are cut again on a shifted
//! grid before the last pass — still one closed mesh at the exact target.

use decimate_core::mesh::measure::{area, edge_counts, invariant_violations, volume};

use crate::common::{decimate, ok, read_model, s, sphere_ply};

/// `nogui --tiles TILES -p 90 --memory MEMORY` on two threads; returns stderr.
fn tiled(input: &std::path::Path, out: &std::path::Path, tiles: &str, memory: &str) -> String {
    tiled_on(input, out, tiles, memory, "2")
}

/// As [`tiled`], on `threads` threads (one tile at a time at most per thread).
fn tiled_on(
    input: &std::path::Path,
    out: &std::path::Path,
    tiles: &str,
    memory: &str,
    threads: &str,
) -> String {
    let o = ok(
        &[
            s(input),
            "nogui",
            "--tiles",
            tiles,
            "-p",
            "90",
            "--memory",
            memory,
            "-o",
            s(out),
        ],
        &[("RAYON_NUM_THREADS", threads)],
    );
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn tiles_run_as_many_at_once_as_the_budget_allows() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, _) = sphere_ply(tmp.path());
    // Six tiles of about 9,600 triangles, 1.9 MiB each in memory (200 bytes a triangle):
    // two fit in 4M, not in 3M; one thread runs one at a time whatever the budget.
    let (one, two) = (tmp.path().join("one.ply"), tmp.path().join("two.ply"));
    let said = tiled_on(&input, &one, "6", "4M", "1");
    assert!(said.contains("running 6 tiles, 1 at once"), "{said}");
    let said = tiled(&input, &two, "6", "4M");
    assert!(said.contains("running 6 tiles, 2 at once"), "{said}");
    for i in 1..=6 {
        assert!(
            said.contains(&format!("tile {i} of 6: triangles")),
            "{said}"
        );
    }
    assert!(std::fs::read(&one).unwrap() == std::fs::read(&two).unwrap());
    let said = tiled(&input, &two, "6", "3M");
    assert!(said.contains("running 6 tiles, 1 at once"), "{said}");
}

#[test]
fn welded_tiles_over_the_budget_are_cut_again_and_stay_one_closed_mesh() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, model) = sphere_ply(tmp.path());
    // 1.5M holds 7,864 triangles: the 5,760 kept, not the ~18,000 the tiles weld into.
    let small = tmp.path().join("small.ply");
    let said = tiled(&input, &small, "auto", "1.5M");
    assert!(
        said.contains("do not fit the memory budget in one piece: cutting them again"),
        "{said}"
    );
    let roomy = tmp.path().join("roomy.ply");
    let said_roomy = tiled(&input, &roomy, "auto", "64M");
    assert!(!said_roomy.contains("cutting them again"), "{said_roomy}");

    let (m, r) = (read_model(&small), read_model(&roomy));
    assert_eq!(m.triangles.len(), 5760);
    let broken = invariant_violations(&model, &m);
    assert!(broken.is_empty(), "{broken:?}");
    let edges = edge_counts(&m);
    assert_eq!((edges.boundary, edges.non_manifold), (0, 0));
    // As close to the input as the one-piece merge: area and volume lost within 1.5 times.
    let lost = |x: &decimate_core::mesh::Model| {
        (
            (area(x) - area(&model)).abs() / area(&model),
            (volume(x) - volume(&model)).abs() / volume(&model),
        )
    };
    let ((sa, sv), (ra, rv)) = (lost(&m), lost(&r));
    assert!(
        sa <= 1.5 * ra + 1e-4 && sv <= 1.5 * rv + 1e-4,
        "re-tiled {sa} {sv}, one piece {ra} {rv}"
    );
    // The work folder (with its re-tiling) is gone.
    let left = std::fs::read_dir(tmp.path()).unwrap().count();
    assert_eq!(left, 3);
}

#[test]
fn the_re_tiling_merge_by_hand_equals_the_one_command_run() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, _) = sphere_ply(tmp.path());
    let work = tmp.path().join("work");
    crate::common::plan(&input, &work, 8);
    for i in 0..8 {
        ok(&["tile", "run", s(&work), &i.to_string()], &[]);
    }
    let by_hand = tmp.path().join("by-hand.ply");
    let o = ok(
        &[
            "tile",
            "merge",
            s(&work),
            "-o",
            s(&by_hand),
            "--memory",
            "1.5M",
        ],
        &[("RAYON_NUM_THREADS", "2")],
    );
    let said = String::from_utf8_lossy(&o.stderr);
    assert!(said.contains("cutting them again"), "{said}");
    let one = tmp.path().join("one.ply");
    tiled(&input, &one, "8", "1.5M");
    assert!(std::fs::read(&by_hand).unwrap() == std::fs::read(&one).unwrap());
}

#[test]
fn a_target_too_big_for_the_budget_is_refused_before_the_tiles_run() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, _) = sphere_ply(tmp.path());
    let out = tmp.path().join("out.ply");
    let o = decimate(
        &[
            s(&input),
            "nogui",
            "--tiles",
            "4",
            "-p",
            "90",
            "--memory",
            "500K",
            "-o",
            s(&out),
        ],
        &[],
    );
    assert_eq!(o.status.code(), Some(2));
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        e.contains("keeping 5760 triangles needs about 1.1 MiB") && e.contains("raise --memory"),
        "{e}"
    );
    assert!(!e.contains("tile 1 of 4"), "{e}");
    assert!(!out.exists());
}
