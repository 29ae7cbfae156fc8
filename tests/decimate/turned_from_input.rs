//! Quadric edge collapse never turns a triangle more than a right angle from the input
//! surface it stands for, even over many collapses in a row that each turn it a little
//! (docs/design.md#qem-input-surface): checked geometrically, each output triangle against
//! the input triangles nearest to points on it.

use decimate_core::decimate::{simplify_scene, Algorithm, Params, Target};
use decimate_core::mesh::{shapes, Model, Scene};
use glam::Vec3;

use crate::support::rng::Rng;

fn qem(model: &Model, triangles: usize) -> Model {
    let mut scene = Scene {
        models: vec![model.clone()],
    };
    let params = Params {
        target: Target::KeepTriangles(triangles),
        algorithm: Algorithm::Qem,
        ..Params::default()
    };
    simplify_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

/// A rough scan of a flat sheet: an `n` × `n` grid of unit squares whose heights are
/// random within ±`rough`, so that no two input triangles overlap seen from above.
fn rough_sheet(rng: &mut Rng, n: u32, rough: f32) -> Model {
    let heights: Vec<f32> = (0..(n + 1) * (n + 1))
        .map(|_| rng.signed() * rough)
        .collect();
    shapes::height_grid(n, |x, y| heights[(y * (n + 1) + x) as usize])
}

/// The closest point to `p` on the triangle `t`'s plane clamped into it, as a squared
/// distance (Ericson's region test, by barycentric coordinates).
fn distance2(p: Vec3, [a, b, c]: [Vec3; 3]) -> f32 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length_squared();
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length_squared();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return (p - (a + ab * (d1 / (d1 - d3)))).length_squared();
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length_squared();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return (p - (a + ac * (d2 / (d2 - d6)))).length_squared();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + (c - b) * w)).length_squared();
    }
    let denom = 1.0 / (va + vb + vc);
    (p - (a + ab * (vb * denom) + ac * (vc * denom))).length_squared()
}

/// Output triangles that face more than a right angle away from the input surface under
/// them: the unit normals of the input triangles nearest to its centroid and to three
/// points halfway from it to the corners, summed, have a negative dot product with its
/// normal. Brute force: for small meshes only.
fn folded(input: &Model, output: &Model) -> usize {
    let corners = |m: &Model, t: &[u32; 3]| t.map(|v| m.positions[v as usize]);
    let normal = |[a, b, c]: [Vec3; 3]| (b - a).cross(c - a);
    let inputs: Vec<[Vec3; 3]> = input.triangles.iter().map(|t| corners(input, t)).collect();
    output
        .triangles
        .iter()
        .filter(|t| {
            let tri = corners(output, t);
            let centroid = (tri[0] + tri[1] + tri[2]) / 3.0;
            let samples = [centroid]
                .into_iter()
                .chain(tri.map(|p| (p + centroid) / 2.0));
            let under: Vec3 = samples
                .map(|p| {
                    let nearest = inputs
                        .iter()
                        .min_by(|x, y| distance2(p, **x).total_cmp(&distance2(p, **y)));
                    nearest.map_or(Vec3::ZERO, |&x| normal(x).normalize_or_zero())
                })
                .sum();
            normal(tri).dot(under) < 0.0
        })
        .count()
}

#[test]
fn qem_keeps_every_triangle_of_a_rough_sheet_facing_its_input() {
    // Each by-step check only: these cases turned one or two triangles over their input
    // (the rough sheet of seed 3 kept at 25 %, of seeds 4 and 6 at 10 %).
    for (seed, percent) in [(3, 25), (4, 10), (6, 10)] {
        let input = rough_sheet(&mut Rng(seed), 30, 0.5);
        assert_eq!(input.triangles.len(), 1800);
        let keep = input.triangles.len() * percent / 100;
        let output = qem(&input, keep);
        assert!(
            output.triangles.len().abs_diff(keep) <= 1,
            "seed {seed}: {} triangles for {keep}",
            output.triangles.len()
        );
        assert_eq!(folded(&input, &output), 0, "seed {seed} at {percent} %");
    }
}
