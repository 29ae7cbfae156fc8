//! Speed of Metro (Cignoni, Rocchini, Scopigno 1998) on real scans: builds the two
//! hierarchies and measures both directions, printing the time of each phase.
//!
//! `cargo bench --bench metro -- A B [SAMPLES]` (defaults: the Stanford dragon against its
//! `res2` version from `.cache/`, which `tools/eval/evaluate` downloads, and 10⁶ samples). Files are
//! read with the project's reader; ASCII PLY files that it cannot read yet are parsed here.

use std::path::Path;
use std::time::Instant;

use decimate_core::metro::{compare, Options, Surface};
use glam::DVec3;

fn main() {
    // `cargo bench` passes --bench; `cargo test --all-targets` runs this too, without it, and
    // must not spend minutes of an unoptimised build on the dragon.
    if !std::env::args().any(|a| a == "--bench") {
        println!("metro bench: skipped (run it with cargo bench --bench metro)");
        return;
    }
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let a = args
        .first()
        .cloned()
        .unwrap_or_else(|| ".cache/models/dragon.ply".into());
    let b = args
        .get(1)
        .cloned()
        .unwrap_or_else(|| ".cache/models/dragon_res2.ply".into());
    let samples = args
        .get(2)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let t = Instant::now();
    let (Some(sa), Some(sb)) = (load(&a), load(&b)) else {
        eprintln!(
            "metro bench: cannot read {a} or {b}; run tools/eval/evaluate once to fetch them"
        );
        return;
    };
    println!(
        "read {:.2} s: A {} triangles, B {} triangles",
        t.elapsed().as_secs_f64(),
        sa.triangles.len(),
        sb.triangles.len()
    );
    for _ in 0..2 {
        let t = Instant::now();
        let options = Options {
            samples: Some(samples),
            seed: 1,
            ..Options::default()
        };
        let Ok(c) = compare(&sa, &sb, &options) else {
            eprintln!("metro bench: empty surface");
            return;
        };
        println!(
            "compare {:.3} s on {} threads (hierarchies {:.3}, A->B {:.3} for {} samples, \
             B->A {:.3} for {} samples): Hausdorff {:.6e}, mean A->B {:.6e}",
            t.elapsed().as_secs_f64(),
            rayon::current_num_threads(),
            c.timings.bvh,
            c.timings.a_to_b,
            c.a_to_b.samples(),
            c.timings.b_to_a,
            c.b_to_a.samples(),
            c.hausdorff(),
            c.a_to_b.mean
        );
    }
}

fn load(path: &str) -> Option<Surface> {
    let t = Instant::now();
    if let Ok(outcome) = decimate_core::io::read_scene(Path::new(path)) {
        let parsed = t.elapsed().as_secs_f64();
        let surface = Surface::from_scene(&outcome.scene);
        println!(
            "{path}: parsed in {parsed:.3} s, flattened in {:.3} s",
            t.elapsed().as_secs_f64() - parsed
        );
        return Some(surface);
    }
    let text = std::fs::read_to_string(path).ok()?;
    let (header, body) = text.split_once("end_header")?;
    let count = |what: &str| -> Option<usize> {
        header
            .lines()
            .find_map(|l| l.strip_prefix(what))
            .and_then(|n| n.trim().parse().ok())
    };
    let (nv, nf) = (count("element vertex ")?, count("element face ")?);
    let mut lines = body.lines().filter(|l| !l.trim().is_empty());
    let mut positions = Vec::with_capacity(nv);
    for line in lines.by_ref().take(nv) {
        let v: Vec<f64> = line
            .split_whitespace()
            .take(3)
            .filter_map(|x| x.parse().ok())
            .collect();
        positions.push(DVec3::new(*v.first()?, *v.get(1)?, *v.get(2)?));
    }
    let mut triangles = Vec::with_capacity(nf);
    for line in lines.take(nf) {
        let f: Vec<u32> = line
            .split_whitespace()
            .filter_map(|x| x.parse().ok())
            .collect();
        for k in 2..f.len().saturating_sub(1) {
            triangles.push([f[1], f[k], f[k + 1]]);
        }
    }
    // Round through f32 as every real reader does.
    let positions: Vec<DVec3> = positions
        .into_iter()
        .map(|p| p.as_vec3().as_dvec3())
        .collect();
    Some(Surface::new(&positions, &triangles))
}
