//! Plan, run (separately, in any order, some twice) and merge: one welded mesh with no
//! cracks, the same as `nogui --tiles`, close to the in-core result.

use decimate_core::mesh::measure::{area, edge_counts, invariant_violations, volume};

use crate::common::{decimate, ok, one_command, plan, read_model, s, sphere_ply};

#[test]
fn tiles_cover_the_input_exactly_with_shared_border_positions() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, model) = sphere_ply(tmp.path());
    let work = tmp.path().join("work");
    plan(&input, &work, 6);
    let manifest = std::fs::read_to_string(work.join("manifest.json")).unwrap();
    assert!(
        manifest.contains("\"format\": \"decimate-tiles\""),
        "{manifest}"
    );
    assert!(manifest.contains("\"triangles\": 57600"), "{manifest}");
    assert!(
        manifest.contains("\"target_triangles\": 5760"),
        "{manifest}"
    );
    // All tiles welded together again are the input: every triangle once, no vertex moved,
    // so the border vertices are bit-identical in the tiles that share them.
    let mut all = decimate_core::mesh::Model::default();
    let mut sizes = Vec::new();
    for i in 0..6 {
        let t = read_model(&work.join(format!("tile-{i:05}.ply")));
        sizes.push(t.triangles.len());
        let base = all.positions.len() as u32;
        all.positions.extend(&t.positions);
        all.triangles
            .extend(t.triangles.iter().map(|t| t.map(|v| v + base)));
    }
    decimate_core::mesh::weld::weld(&mut all, 0.0);
    assert_eq!(all.triangles.len(), model.triangles.len());
    assert_eq!(all.positions.len(), model.positions.len());
    assert!(invariant_violations(&model, &all).is_empty());
    assert!((area(&all) - area(&model)).abs() < 1e-9 * area(&model));
    // Balanced: no tile has more than twice its even share.
    let even = model.triangles.len() / 6;
    assert!(
        sizes.iter().all(|&n| n > even / 2 && n < even * 2),
        "{sizes:?}"
    );
    assert!(!work.join("tile-00006.ply").exists());
}

#[test]
fn separate_jobs_in_any_order_equal_the_one_command_run() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, model) = sphere_ply(tmp.path());
    let work = tmp.path().join("work");
    plan(&input, &work, 5);
    let status = ok(&["tile", "status", s(&work)], &[]);
    let text = String::from_utf8_lossy(&status.stdout);
    assert!(text.contains("0 of 5 tiles done"), "{text}");
    let out = tmp.path().join("merged.ply");
    let early = decimate(&["tile", "merge", s(&work), "-o", s(&out)], &[]);
    assert_eq!(early.status.code(), Some(2));
    let msg = String::from_utf8_lossy(&early.stderr);
    assert!(msg.contains("tiles not run yet: 0, 1, 2, 3, 4"), "{msg}");
    assert!(!out.exists());

    // Reverse order, one re-run (a pre-empted job run again), indices from the schedulers'
    // variables as well as from the argument.
    ok(&["tile", "run", s(&work), "4"], &[]);
    ok(&["tile", "run", s(&work)], &[("SLURM_ARRAY_TASK_ID", "3")]);
    ok(&["tile", "run", s(&work)], &[("JOB_COMPLETION_INDEX", "2")]);
    ok(&["tile", "run", s(&work), "1"], &[]);
    let text = String::from_utf8_lossy(&ok(&["tile", "status", s(&work)], &[]).stdout).into_owned();
    assert!(
        text.contains("4 of 5 tiles done") && text.contains("tile 0: pending"),
        "{text}"
    );
    ok(&["tile", "run", s(&work), "0"], &[]);
    ok(&["tile", "run", s(&work), "3"], &[]);
    ok(&["tile", "merge", s(&work), "-o", s(&out)], &[]);

    let one = tmp.path().join("one.ply");
    one_command(&input, 5, &one);
    assert_eq!(std::fs::read(&out).unwrap(), std::fs::read(&one).unwrap());
    // The one-command run cleans its work folder up.
    let left: Vec<_> = std::fs::read_dir(tmp.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left.len(), 4, "{left:?}");

    let merged = read_model(&out);
    assert_eq!(merged.triangles.len(), 5760);
    // One closed, welded mesh: no crack (boundary edge), nothing flipped or degenerate.
    let broken = invariant_violations(&model, &merged);
    assert!(broken.is_empty(), "{broken:?}");
    assert_eq!(edge_counts(&merged).boundary, 0);
    let (v0, v1) = (volume(&model), volume(&merged));
    assert!((v1 - v0).abs() < 0.01 * v0, "volume {v0} -> {v1}");
}

#[test]
fn tiled_result_is_as_close_as_the_in_core_one() {
    let tmp = tempfile::tempdir().unwrap();
    let (input, model) = sphere_ply(tmp.path());
    let tiled = tmp.path().join("tiled.ply");
    let whole = tmp.path().join("whole.ply");
    ok(
        &[
            s(&input),
            "nogui",
            "--tiles",
            "8",
            "--keep-triangles",
            "3000",
            "-o",
            s(&tiled),
            "-q",
        ],
        &[],
    );
    ok(
        &[
            s(&input),
            "nogui",
            "-a",
            "qem",
            "--keep-triangles",
            "3000",
            "-o",
            s(&whole),
            "-q",
        ],
        &[],
    );
    let (t, w) = (read_model(&tiled), read_model(&whole));
    assert_eq!(t.triangles.len(), 3000);
    let broken = invariant_violations(&model, &t);
    assert!(broken.is_empty(), "{broken:?}");
    // Area and volume lost by the tiled run: no more than 1.5 times the in-core run's.
    let lost = |m: &decimate_core::mesh::Model| {
        (
            (area(m) - area(&model)).abs() / area(&model),
            (volume(m) - volume(&model)).abs() / volume(&model),
        )
    };
    let ((ta, tv), (wa, wv)) = (lost(&t), lost(&w));
    assert!(
        ta <= 1.5 * wa + 1e-4 && tv <= 1.5 * wv + 1e-4,
        "tiled {ta} {tv}, in-core {wa} {wv}"
    );
}

#[test]
fn stl_and_obj_inputs_plan_like_the_ply() {
    let tmp = tempfile::tempdir().unwrap();
    let (ply, model) = sphere_ply(tmp.path());
    let scene = decimate_core::mesh::Scene {
        models: vec![model.clone()],
    };
    let stl = tmp.path().join("sphere.stl");
    let obj = tmp.path().join("sphere.obj");
    decimate_core::io::write_stl(&scene, &stl).unwrap();
    decimate_core::io::write_obj(&scene, &obj).unwrap();
    let mut outs = Vec::new();
    for input in [&ply, &stl, &obj] {
        let out = tmp.path().join(format!(
            "out-{}.ply",
            input.extension().unwrap().to_str().unwrap()
        ));
        ok(
            &[
                s(input),
                "nogui",
                "--tiles",
                "3",
                "-p",
                "80",
                "-o",
                s(&out),
                "-q",
            ],
            &[],
        );
        let m = read_model(&out);
        assert_eq!(m.triangles.len(), 11520, "{}", input.display());
        assert!(
            invariant_violations(&model, &m).is_empty(),
            "{}",
            input.display()
        );
        outs.push(m);
    }
    // OBJ writes decimal text: the same mesh within its printed precision.
    assert_eq!(outs[0], outs[1]);
    assert_eq!(outs[0].triangles.len(), outs[2].triangles.len());
}
