//! Models of four or five vertices cut by a count short of "all of them": the result stops
//! at four vertices (the floor a count never crosses) instead of vanishing. Only `-p 100`
//! or an error bound alone may take a model under four, which the scene then drops.

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::io::read_scene;
use decimate_core::mesh::{Model, Scene};
use glam::Vec3;

use crate::support::binary;

/// Three triangles on the edge 0–1 (a fin): 5 vertices.
fn fin() -> Model {
    Model {
        name: "fin".into(),
        positions: vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 1.0, 0.0),
            Vec3::new(0.5, -1.0, 0.0),
            Vec3::new(0.5, 0.0, 1.0),
        ],
        triangles: vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
        ..Model::default()
    }
}

/// Two triangles folded along their shared edge: 4 vertices.
fn folded_pair() -> Model {
    Model {
        name: "pair".into(),
        positions: vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 1.0, 0.0),
            Vec3::new(0.5, -1.0, 0.2),
        ],
        triangles: vec![[0, 1, 2], [1, 0, 3]],
        ..Model::default()
    }
}

fn decimate(model: &Model, algorithm: Algorithm, target: Target) -> Option<Model> {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target,
        algorithm,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop()
}

#[test]
fn a_count_short_of_all_stops_at_four_vertices() {
    let targets = [
        Target::RemovePercent(50.0),
        Target::RemovePercent(75.0),
        Target::RemoveVertices(3),
        Target::KeepVertices(2),
        Target::KeepTriangles(1),
    ];
    for model in [fin(), folded_pair()] {
        for algorithm in [Algorithm::Schroeder, Algorithm::Qem] {
            for target in targets {
                let what = format!("{} {algorithm:?} {target:?}", model.name);
                let after = decimate(&model, algorithm, target).expect(&what);
                let used = (0..after.positions.len() as u32)
                    .filter(|v| after.triangles.iter().any(|t| t.contains(v)))
                    .count();
                assert_eq!(used, 4, "{what}");
                assert_eq!(after.triangles.len(), 2, "{what}");
            }
        }
    }
}

#[test]
fn the_binary_writes_the_fin_at_fifty_percent_as_four_vertices() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let off = "OFF\n5 3 0\n0 0 0\n1 0 0\n0.5 1 0\n0.5 -1 0\n0.5 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n";
    std::fs::write(dir.path().join("fin.off"), off).expect("write the input");
    let run = binary::decimate(
        dir.path(),
        &["fin.off", "nogui", "-q", "-p", "50", "-o", "out.off"],
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let read = read_scene(&dir.path().join("out.off")).expect("the output reads");
    let after = &read.scene.models[0];
    assert_eq!((after.positions.len(), after.triangles.len()), (4, 2));
}
