//! Texture seams never fold a closed shape: a textured Inventor sphere (poles split into
//! one copy per slice, a seam down its back), a latitude–longitude textured OBJ sphere and
//! a textured cone and cylinder (apex and rims junctions and seams), decimated by both
//! algorithms, stay closed and manifold once welded by position, face outwards
//! everywhere, keep their volume and their texture coordinates in range, and stay about as
//! close to the input as the same shape decimated without a texture. A pole's first ring
//! goes into the pole across two of its copies (docs/design.md#texture-seams).

use std::path::Path;

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::io::read_scene;
use decimate_core::mesh::build::build_scene;
use decimate_core::mesh::Scene;
use decimate_core::metro::{compare, Options, Surface};
use glam::DVec3;

/// The share of the input's volume a decimated sphere keeps at least (an untextured one
/// keeps 88 % or more at 95 %: see docs/design.md#texture-seams).
const MIN_VOLUME_SHARE: f64 = 0.8;

/// The textured result's mean distance to the input may be this many times the untextured
/// result's (plus a hundredth of a percent of the diagonal, for results that are both
/// nearly exact).
const ERROR_RATIO: f64 = 2.0;

/// A unit sphere in latitude–longitude texture coordinates as an OBJ: `rings` × `segments`
/// quads, each pole a row of `segments + 1` vertices at one point (one per slice), the
/// u = 0 / u = 1 column a seam. Positions are written to six decimals, so the copies of a
/// point are the same point exactly.
pub(crate) fn lat_long_sphere_obj(rings: usize, segments: usize) -> String {
    use std::f64::consts::PI;
    let (mut v, mut vt, mut f) = (String::new(), String::new(), String::new());
    for j in 0..=rings {
        let theta = PI * j as f64 / rings as f64;
        for i in 0..=segments {
            let phi = 2.0 * PI * i as f64 / segments as f64;
            let (x, y, z) = (
                theta.sin() * phi.cos(),
                theta.cos(),
                -theta.sin() * phi.sin(),
            );
            v += &format!("v {x:.6} {y:.6} {z:.6}\n");
            vt += &format!(
                "vt {} {}\n",
                i as f64 / segments as f64,
                1.0 - j as f64 / rings as f64
            );
        }
    }
    let corner = |k: usize| format!("{0}/{0}", k + 1);
    for j in 0..rings {
        for i in 0..segments {
            let a = j * (segments + 1) + i;
            let (b, c, d) = (a + 1, a + segments + 2, a + segments + 1);
            // Each pole's triangles have one corner there (the other would have no area).
            if j + 1 < rings {
                f += &format!("f {} {} {}\n", corner(a), corner(d), corner(c));
            }
            if j > 0 {
                f += &format!("f {} {} {}\n", corner(a), corner(c), corner(b));
            }
        }
    }
    v + &vt + &f
}

/// The scene in `text`, written to `name` in a temporary folder and read back as the
/// binary reads it (welded).
pub(crate) fn scene_from(name: &str, text: &str) -> Scene {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let path = dir.path().join(name);
    std::fs::write(&path, text).expect("the scene written");
    let outcome = read_scene(Path::new(&path)).expect("the scene read");
    build_scene(outcome.scene, true)
}

/// The textured Inventor sphere at Complexity 1 (the texture file need not exist).
fn inventor_sphere() -> Scene {
    let text = "#Inventor V2.1 ascii\nSeparator { Texture2 { filename \"c.png\" } \
                Complexity { value 1 } Sphere {} }\n";
    scene_from("sphere.iv", text)
}

fn obj_sphere() -> Scene {
    scene_from("sphere.obj", &lat_long_sphere_obj(24, 48))
}

/// `scene` without texture coordinates: the same surface, no seams.
fn untextured(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    for m in &mut s.models {
        m.texcoords = None;
    }
    build_scene(s, true)
}

fn decimated(scene: &Scene, algorithm: Algorithm, percent: f64) -> Scene {
    let mut out = scene.clone();
    let params = Params {
        target: Target::RemovePercent(percent),
        algorithm,
        ..Params::default()
    };
    simplify_scene(&mut out, &params, &mut |_| {});
    out
}

/// Triangles of a convex shape that face inwards (towards the mean of their corners, a
/// point inside: the origin on a sphere about it) or have no area. A cone left with four
/// vertices is a tetrahedron that may lean off the axis (docs/design.md#schroeder-loosen).
fn inward_triangles(s: &Surface) -> usize {
    let corners = s
        .triangles
        .iter()
        .flatten()
        .map(|&v| s.positions[v as usize]);
    let centre = corners.sum::<DVec3>() / (3 * s.triangles.len()).max(1) as f64;
    s.triangles
        .iter()
        .filter(|t| {
            let [a, b, c] = t.map(|v| s.positions[v as usize] - centre);
            (b - a).cross(c - a).dot(a + b + c) <= 0.0
        })
        .count()
}

/// What a decimated shape must keep besides being closed, manifold and outward.
#[derive(Clone, Copy, PartialEq)]
enum Bars {
    /// Its volume's sign only: a shape left with a handful of vertices (a cone or
    /// cylinder of 40 slices at 90 %, 8 points or fewer) cannot keep more, textured or not.
    VolumeSign,
    /// [`MIN_VOLUME_SHARE`] of its volume.
    Volume,
    /// That, and a mean distance to the input within [`ERROR_RATIO`] of the untextured
    /// result's.
    VolumeAndError,
}

/// Every fault of `out` (welded by position) against `input` under `bars`, its error
/// measured against the untextured result `plain`.
fn faults(input: &Surface, out: &Surface, plain: &Surface, bars: Bars) -> Vec<String> {
    let mut faults = Vec::new();
    if !out.is_closed() || out.nonmanifold_edges > 0 || out.misoriented_edges > 0 {
        faults.push(format!(
            "open or non-manifold: {} border, {} non-manifold, {} misoriented edges",
            out.boundary_edges, out.nonmanifold_edges, out.misoriented_edges
        ));
    }
    let inward = inward_triangles(out);
    if inward > 0 {
        faults.push(format!("{inward} triangles face inwards or are flat"));
    }
    let (v0, v) = (input.volume().unwrap_or(0.0), out.volume().unwrap_or(0.0));
    let share = if bars == Bars::VolumeSign {
        0.0
    } else {
        MIN_VOLUME_SHARE
    };
    if v * v0.signum() <= share * v0.abs() {
        faults.push(format!("volume {v:.4} of {v0:.4}"));
    }
    let mean = |s: &Surface| {
        let c = compare(input, s, &Options::default()).expect("both have triangles");
        c.symmetric().mean / input.diagonal()
    };
    let (mine, theirs) = if bars == Bars::VolumeAndError {
        (mean(out), mean(plain))
    } else {
        (0.0, 0.0)
    };
    if mine > ERROR_RATIO * theirs + 1e-4 {
        faults.push(format!(
            "mean error {:.3} % of the diagonal, untextured {:.3} %",
            100.0 * mine,
            100.0 * theirs
        ));
    }
    faults
}

/// How many of `out`'s texture coordinates lie outside the box of `input`'s.
fn texcoords_outside(input: &Scene, out: &Scene) -> usize {
    let all = |s: &Scene| -> Vec<[f32; 2]> {
        (s.models.iter())
            .flat_map(|m| m.texcoords.iter().flatten().copied())
            .collect()
    };
    let (before, after) = (all(input), all(out));
    let (mut lo, mut hi) = ([f32::INFINITY; 2], [f32::NEG_INFINITY; 2]);
    for t in &before {
        for k in 0..2 {
            lo[k] = lo[k].min(t[k]);
            hi[k] = hi[k].max(t[k]);
        }
    }
    assert!(!after.is_empty(), "the result has texture coordinates");
    after
        .iter()
        .filter(|t| (0..2).any(|k| !(lo[k]..=hi[k]).contains(&t[k])))
        .count()
}

/// Checks `scene` decimated by both algorithms to each of `percents`, with `bars`.
fn check(name: &str, scene: &Scene, percents: &[f64], bars: Bars) {
    assert!(
        scene.models.iter().all(|m| m.texcoords.is_some()),
        "{name} is textured"
    );
    let input = Surface::from_scene(scene);
    assert!(
        input.is_closed() && input.nonmanifold_edges == 0,
        "{name} closed"
    );
    assert_eq!(inward_triangles(&input), 0, "{name} faces outwards");
    let plain_input = untextured(scene);
    let mut all = Vec::new();
    for algorithm in [Algorithm::Qem, Algorithm::Schroeder] {
        for &percent in percents {
            let plain = Surface::from_scene(&decimated(&plain_input, algorithm, percent));
            assert!(
                plain.is_closed() && inward_triangles(&plain) == 0,
                "{name}, {algorithm:?}, {percent} %: untextured is closed"
            );
            let out_scene = decimated(scene, algorithm, percent);
            let out = Surface::from_scene(&out_scene);
            let outside = texcoords_outside(scene, &out_scene);
            if outside > 0 {
                all.push(format!(
                    "{name}, {algorithm:?}, {percent} %: {outside} texture coordinates out of range"
                ));
            }
            all.extend(
                faults(&input, &out, &plain, bars)
                    .into_iter()
                    .map(|f| format!("{name}, {algorithm:?}, {percent} %: {f}")),
            );
        }
    }
    assert!(all.is_empty(), "{all:#?}");
}

#[test]
fn textured_spheres_stay_closed_outward_and_full_at_80_percent() {
    check("Inventor sphere", &inventor_sphere(), &[80.0], Bars::Volume);
    check("OBJ sphere", &obj_sphere(), &[80.0], Bars::Volume);
}

#[test]
fn textured_spheres_stay_closed_and_near_the_untextured_result_down_to_95_percent() {
    let percents = [80.0, 90.0, 95.0];
    check(
        "Inventor sphere",
        &inventor_sphere(),
        &percents,
        Bars::VolumeAndError,
    );
    check("OBJ sphere", &obj_sphere(), &percents, Bars::VolumeAndError);
}

/// A textured Inventor `shape` at Complexity 1 (40 slices).
fn inventor_shape(shape: &str) -> Scene {
    let text = format!(
        "#Inventor V2.1 ascii\nSeparator {{ Texture2 {{ filename \"c.png\" }} \
         Complexity {{ value 1 }} {shape} {{}} }}\n"
    );
    scene_from("shape.iv", &text)
}

#[test]
fn a_textured_cone_and_cylinder_stay_closed_and_outward_down_to_95_percent() {
    for shape in ["Cone", "Cylinder"] {
        let scene = inventor_shape(shape);
        check(shape, &scene, &[80.0], Bars::VolumeAndError);
        check(shape, &scene, &[90.0, 95.0], Bars::VolumeSign);
    }
}

#[test]
fn a_copy_a_pole_collapse_drops_counts_so_the_count_target_is_met_exactly() {
    for (name, scene) in [("Inventor", inventor_sphere()), ("OBJ", obj_sphere())] {
        // Counted in points: a seam's or a pole's copies of one point once.
        let points = |m: &decimate_core::mesh::Model| {
            (m.positions.iter())
                .map(|p| p.to_array().map(|c| (c + 0.0).to_bits()))
                .collect::<std::collections::HashSet<_>>()
                .len()
        };
        let before = points(&scene.models[0]);
        let target = (0.9 * before as f64).round() as usize;
        for algorithm in [Algorithm::Qem, Algorithm::Schroeder] {
            let out = decimated(&scene, algorithm, 90.0);
            let m = &out.models[0];
            assert_eq!(points(m), before - target, "{name} sphere, {algorithm:?}");
            assert_eq!(m.positions.len(), m.used_vertex_count(), "no unused vertex");
        }
    }
}

#[test]
fn textured_spheres_of_many_resolutions_stay_closed_manifold_and_outward_from_50_to_95_percent() {
    let inventor = |complexity: &str| {
        let text = format!(
            "#Inventor V2.1 ascii\nSeparator {{ Texture2 {{ filename \"c.png\" }} \
             Complexity {{ value {complexity} }} Sphere {{}} }}\n"
        );
        (
            format!("Inventor sphere at {complexity}"),
            scene_from("s.iv", &text),
        )
    };
    let obj = |rings: usize| {
        let text = lat_long_sphere_obj(rings, 2 * rings);
        (
            format!("{rings} × {} OBJ sphere", 2 * rings),
            scene_from("s.obj", &text),
        )
    };
    let spheres = ["0.3", "0.5", "0.8"].map(inventor).into_iter();
    let mut faults = Vec::new();
    for (name, scene) in spheres.chain([8, 12, 16, 32].map(obj)) {
        let percents = [50.0, 70.0, 90.0, 95.0];
        for algorithm in [Algorithm::Qem, Algorithm::Schroeder] {
            for percent in percents {
                let out = Surface::from_scene(&decimated(&scene, algorithm, percent));
                let inward = inward_triangles(&out);
                if !out.is_closed() || out.nonmanifold_edges > 0 || inward > 0 {
                    faults.push(format!(
                        "{name}, {algorithm:?}, {percent} %: {} border, {} non-manifold \
                         edges, {inward} inward or flat triangles",
                        out.boundary_edges, out.nonmanifold_edges
                    ));
                }
            }
        }
    }
    assert!(faults.is_empty(), "{faults:#?}");
}
