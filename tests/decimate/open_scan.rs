//! Schroeder vertex removal on an open, rough scanned grid (a stand-in for the Cyberware
//! heads: a 40×40 grid where many vertices are "corners" at the 30° feature angle).
//! What a user notices: the count asked for, an error below the bound the early relaxation
//! of the feature angle brings (docs/design.md#schroeder-relax-early), the outline kept
//! (one border loop, the grid's whole footprint) and no triangle flipped; and the real
//! heads cut to 1 %.

use std::path::Path;

use crate::support::binary;
use crate::support::inventor::{ascii_copy, MODELS};
use crate::support::metro::compare_models;
use decimate_core::decimate::{simplify_scene, Params, Report, Target};
use decimate_core::io::read_scene;
use decimate_core::mesh::{measure, shapes, Model, Scene};

use crate::support::rng::Rng;

/// A grid of `n`×`n` unit quads: two broad hills plus per-vertex roughness of about a
/// third of the spacing, so that many of its vertices are corners at 30°.
fn rough_grid(n: u32) -> Model {
    let mut rng = Rng(0x5eed_0040);
    let roughness: Vec<f32> = (0..(n + 1) * (n + 1)).map(|_| rng.signed()).collect();
    let pi = std::f32::consts::PI;
    shapes::height_grid(n, |x, y| {
        let (u, v) = (x as f32 / n as f32, y as f32 / n as f32);
        let hills = 0.15 * n as f32 * (3.0 * pi * u).sin() * (2.0 * pi * v).sin();
        hills + 0.35 * roughness[(y * (n + 1) + x) as usize]
    })
}

fn decimate(model: &Model, keep: usize) -> (Model, Report) {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target: Target::KeepTriangles(keep),
        ..Params::default()
    };
    let report = simplify_scene(&mut scene, &params, &mut |_| {});
    (scene.models.pop().unwrap_or_default(), report)
}

/// Metro's symmetric mean error as a fraction of the bounding-box diagonal.
fn mean_error(before: &Model, after: &Model) -> f64 {
    let c = compare_models(before, after);
    c.relative(c.symmetric().mean)
}

/// The area of the mesh's shadow on the xy plane: the grid's footprint.
fn footprint(m: &Model) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize].as_dvec3());
            (b - a).cross(c - a).z / 2.0
        })
        .sum()
}

fn check(keep: usize, bound: f64) {
    let before = rough_grid(39);
    let (after, report) = decimate(&before, keep);
    let left = after.triangles.len();
    // One triangle over, only a border vertex's removal (one triangle) lands on the count;
    // one under when no border vertex may go (at 2 % the outline's last vertices are
    // corners, which stay).
    assert!(
        left == keep || left + 1 == keep,
        "{left} triangles for {keep} asked"
    );
    let broken = measure::invariant_violations(&before, &after);
    assert!(broken.is_empty(), "{broken:?}");
    // The outline: the border's corners and lines stay, so the shadow on the grid's plane
    // (signed: a fold would not add to it) is the whole square.
    let kept = footprint(&after) / footprint(&before);
    assert!(
        (kept - 1.0).abs() < 1e-6,
        "{:.3} % of the footprint kept",
        100.0 * kept
    );
    let error = mean_error(&before, &after);
    eprintln!(
        "{keep}: {left} triangles, mean error {:.4} %, feature angle {}",
        100.0 * error,
        report.models[0].feature_angle_deg
    );
    assert!(
        error < bound,
        "mean error {:.4} % of the diagonal",
        100.0 * error
    );
}

#[test]
fn a_rough_open_grid_at_ten_percent_keeps_its_outline_and_a_low_error() {
    // Relaxing the feature angle only once out of candidates gave 0.47 %.
    check(304, 0.0035);
}

#[test]
fn a_rough_open_grid_at_two_percent_keeps_its_outline_and_a_low_error() {
    // Relaxing the feature angle only once out of candidates gave 1.47 %.
    check(61, 0.012);
}

/// The Cyberware heads of Debian's `inventor-data` (open 40×40 grids of rough scans), cut
/// to 1 % by the binary as a user would, with either algorithm: the count asked for
/// exactly, no triangle folded, and the face kept; at 10 % the count exactly too. Taking
/// the few dear candidates the feature angle left, instead of loosening it
/// (docs/design.md#schroeder-loosen), cut josie's face by a chord: 7.8 % mean error, 30 %
/// max.
#[test]
fn the_cyberware_heads_at_one_percent_keep_their_faces() {
    let dir = std::env::temp_dir().join(format!("decimate-heads-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for head in ["josie", "paul", "rikk"] {
        let src = Path::new(MODELS).join(format!("CyberHeads/{head}.iv"));
        let ascii = ascii_copy(&src, &dir);
        let ascii = ascii.to_string_lossy();
        let read = |args: &[&str], out: &str| {
            let mut all = vec![&*ascii, "nogui", "-q", "--overwrite", "-o", out];
            all.extend_from_slice(args);
            let run = binary::decimate(&dir, &all);
            assert!(
                run.status.success(),
                "{head}: {}",
                String::from_utf8_lossy(&run.stderr)
            );
            let mut scene = read_scene(&dir.join(out)).unwrap().scene;
            scene.models.pop().unwrap()
        };
        let before = read(&["-p", "0"], "before.ply");
        assert_eq!(before.triangles.len(), 3042, "{head}");
        for algorithm in ["schroeder", "qem"] {
            // Exactly: one triangle over, a border vertex's removal or a border edge's
            // collapse (one triangle) lands on it where an inner one's (two) went one under
            // (josie gave 29 with both, and 303 for 304 within a pass).
            let at_ten = read(&["-a", algorithm, "--keep-triangles", "304"], "ten.ply");
            assert_eq!(at_ten.triangles.len(), 304, "{head} {algorithm}");
            let after = read(&["-a", algorithm, "--keep-triangles", "30"], "after.ply");
            assert_eq!(after.triangles.len(), 30, "{head} {algorithm}");
            for (kept, cut) in [(&at_ten, "10 %"), (&after, "1 %")] {
                let broken = measure::invariant_violations(&before, kept);
                assert!(broken.is_empty(), "{head} {algorithm} {cut}: {broken:?}");
            }
            let c = compare_models(&before, &after);
            let (mean, max) = (
                c.relative(c.symmetric().mean),
                c.relative(c.symmetric().max),
            );
            eprintln!(
                "{head} {algorithm}: mean {:.3} %, max {:.2} %",
                100.0 * mean,
                100.0 * max
            );
            assert!(mean < 0.03 && max < 0.15, "{head}: mean {mean}, max {max}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
