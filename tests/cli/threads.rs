//! `--threads N`: the same result, byte for byte, on one thread and on two; a count that
//! is no thread count refused.

use std::path::Path;

use crate::support::binary::decimate;

/// A sphere of `rings × segments` quads with a bumpy radius, as an OFF file: a mesh large
/// enough that every parallel step splits its work, with many equal costs (its symmetry)
/// where an order that depends on the threads would show.
fn bumpy_sphere_off(rings: u32, segments: u32) -> String {
    let mut v = Vec::new();
    for r in 1..rings {
        let theta = std::f64::consts::PI * f64::from(r) / f64::from(rings);
        for s in 0..segments {
            let phi = std::f64::consts::TAU * f64::from(s) / f64::from(segments);
            let radius = 1.0 + 0.05 * (5.0 * theta).sin() * (7.0 * phi).cos();
            v.push([
                radius * theta.sin() * phi.cos(),
                radius * theta.sin() * phi.sin(),
                radius * theta.cos(),
            ]);
        }
    }
    let (north, south) = (v.len(), v.len() + 1);
    v.push([0.0, 0.0, 1.0]);
    v.push([0.0, 0.0, -1.0]);
    let at = |r: u32, s: u32| ((r - 1) * segments + s % segments) as usize;
    let mut f = Vec::new();
    for s in 0..segments {
        f.push([north, at(1, s), at(1, s + 1)]);
        f.push([south, at(rings - 1, s + 1), at(rings - 1, s)]);
        for r in 1..rings - 1 {
            let (a, b, c, d) = (at(r, s), at(r + 1, s), at(r + 1, s + 1), at(r, s + 1));
            f.push([a, b, c]);
            f.push([a, c, d]);
        }
    }
    let mut off = format!("OFF\n{} {} 0\n", v.len(), f.len());
    for p in &v {
        off.push_str(&format!("{} {} {}\n", p[0], p[1], p[2]));
    }
    for t in &f {
        off.push_str(&format!("3 {} {} {}\n", t[0], t[1], t[2]));
    }
    off
}

fn decimated(dir: &Path, algorithm: &str, threads: &str) -> Vec<u8> {
    let out = format!("{algorithm}-{threads}.ply");
    let run = decimate(
        dir,
        &[
            "sphere.off",
            "nogui",
            "-q",
            "-a",
            algorithm,
            "-p",
            "90",
            "--threads",
            threads,
            "-o",
            &out,
        ],
    );
    assert!(
        run.status.success(),
        "{algorithm} --threads {threads}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    std::fs::read(dir.join(out)).unwrap()
}

#[test]
fn one_thread_and_two_write_the_same_bytes() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("sphere.off"), bumpy_sphere_off(60, 120)).unwrap();
    for algorithm in ["qem", "schroeder"] {
        let one = decimated(dir.path(), algorithm, "1");
        let two = decimated(dir.path(), algorithm, "2");
        assert!(one.len() > 100, "{algorithm}: an output was written");
        assert!(one == two, "{algorithm}: --threads 1 and 2 differ");
    }
}

#[test]
fn a_thread_count_of_zero_or_not_a_number_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("sphere.off"), bumpy_sphere_off(8, 16)).unwrap();
    for bad in ["0", "two"] {
        let run = decimate(
            dir.path(),
            &["sphere.off", "nogui", "-p", "50", "--threads", bad],
        );
        let err = String::from_utf8_lossy(&run.stderr);
        assert_eq!(run.status.code(), Some(2), "--threads {bad}: {err}");
        assert!(err.contains("--threads"), "--threads {bad}: {err}");
        assert!(!dir.path().join("out.wrl").exists(), "--threads {bad}");
    }
}
