//! Far VRML 2.0 geometry that is not a point list: an ElevationGrid whose heights are at
//! 1e6 and an Extrusion whose spine is at 1e7 (see docs/design.md#far-coordinates). Each is
//! decimated by the binary with both algorithms, at the origin and far; the far run's OBJ
//! output, read back in f64 (`georef::read_output`) and moved back, must be the origin
//! run's: the same triangles, every point within 1e-6. Read in f32, the grid's heights at
//! 1e6 are rounded to 0.0625 and the spine's points at 1e7 to whole units.
//!
//! Every number is a multiple of 2^-12, so the shape's offsets from its far corner are the
//! same f32 numbers as at the origin: both runs decimate the same numbers.

use std::fmt::Write as _;
use std::path::Path;

use crate::georef::{assert_same_as_the_origin_run, decimated_moved_back, Mesh};
use crate::support::rng::Rng;

/// `v` rounded to a multiple of 2^-12.
fn dyadic(v: f64) -> f64 {
    (v * 4096.0).round() / 4096.0
}

/// An ElevationGrid of 25 x 25 heights `lift` plus bumps and seeded noise of a few
/// millimetres, 1/64 apart.
fn elevation_grid(lift: f64) -> String {
    let n = 25;
    let mut rng = Rng(56);
    let mut heights = String::new();
    for j in 0..n {
        for i in 0..n {
            let (x, z) = (f64::from(i) / 64.0, f64::from(j) / 64.0);
            let bump = 0.01 * (x * 40.0).sin() * (z * 30.0).cos();
            let h = dyadic(bump + 0.002 * f64::from(rng.signed()));
            let _ = write!(heights, "{} ", lift + h);
        }
    }
    format!(
        "#VRML V2.0 utf8\nShape {{ geometry ElevationGrid {{ xDimension {n} zDimension {n}\n\
         xSpacing 0.015625 zSpacing 0.015625 solid FALSE\nheight [ {heights} ] }} }}\n"
    )
}

/// A closed tube of radius 1/16 swept along a bent spine of 24 points that starts at `at`.
fn extrusion(at: [f64; 3]) -> String {
    let mut spine = String::new();
    for i in 0..24 {
        let a = f64::from(i) * 0.1;
        let p = [0.25 * a.sin(), f64::from(i) / 32.0, 0.25 * (1.0 - a.cos())].map(dyadic);
        let _ = write!(
            spine,
            "{} {} {}, ",
            at[0] + p[0],
            at[1] + p[1],
            at[2] + p[2]
        );
    }
    let mut section = String::new();
    for k in 0..=12 {
        let a = std::f64::consts::TAU * f64::from(k % 12) / 12.0;
        let c = [a.cos(), a.sin()].map(|v| dyadic(v / 16.0));
        let _ = write!(section, "{} {}, ", c[0], c[1]);
    }
    format!(
        "#VRML V2.0 utf8\nShape {{ geometry Extrusion {{ solid FALSE\n\
         spine [ {spine} ]\ncrossSection [ {section} ] }} }}\n"
    )
}

/// Runs the binary on `text` and returns its OBJ output moved back by `t`.
fn run(dir: &Path, text: &str, t: [f64; 3], algorithm: &[&str]) -> Mesh {
    std::fs::write(dir.join("shape.wrl"), text).unwrap();
    decimated_moved_back(dir, "shape.wrl", "out.obj", t, algorithm)
}

/// The far run of each shape must be the origin run moved: same triangles, same points.
fn check(what: &str, shape: impl Fn([f64; 3]) -> String, far: [f64; 3], least: usize) {
    let dir = tempfile::tempdir().unwrap();
    for algorithm in [&[][..], &["-a", "qem"][..]] {
        let near = run(dir.path(), &shape([0.0; 3]), [0.0; 3], algorithm);
        assert!(
            near.triangles.len() >= least,
            "{what} {algorithm:?}: {} triangles",
            near.triangles.len()
        );
        let moved = run(dir.path(), &shape(far), far, algorithm);
        assert_same_as_the_origin_run(&format!("{what} {algorithm:?} at {far:?}"), &near, &moved);
    }
}

#[test]
fn an_elevation_grid_at_a_height_of_1e6_decimates_as_it_does_at_zero() {
    // 24 x 24 quads: 1152 triangles, 20 % of them kept.
    check(
        "ElevationGrid",
        |t| elevation_grid(t[1]),
        [0.0, 1.0e6, 0.0],
        200,
    );
}

#[test]
fn an_extrusion_along_a_spine_at_1e7_decimates_as_it_does_at_zero() {
    // 23 x 12 quads and two 12-gon caps: 572 triangles, 20 % of them kept.
    check("Extrusion", extrusion, [1.0e7, -1.0e7, 1.0e7], 100);
}
