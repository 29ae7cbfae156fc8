//! Decimation of many random meshes, deterministic by seed (a fuzz target in test form):
//! noisy grids and spheres at every roughness keep every invariant at any target, and
//! random triangle soups — duplicated, degenerate, non-manifold, inconsistently oriented —
//! never panic and never get worse: no more defective (non-manifold or misoriented) edges
//! than before, no index out of range. (A three-triangle edge that loses one triangle may
//! become a two-triangle edge of one direction: one defect traded for another.)

use decimate::decimate::{decimate_scene, Params, Target};
use decimate::mesh::{measure, shapes, Model, Scene};
use glam::Vec3;

/// xorshift64*: small, deterministic, good enough to shake meshes.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    /// Uniform in [-1, 1).
    fn signed(&mut self) -> f32 {
        (self.next() >> 40) as f32 / (1u64 << 23) as f32 - 1.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

fn run(model: Model, target: Target, feature_angle_deg: f64) -> Model {
    let mut scene = Scene {
        models: vec![model],
    };
    let params = Params {
        target,
        feature_angle_deg,
        ..Params::default()
    };
    decimate_scene(&mut scene, &params, &mut |_| {});
    scene.models.pop().unwrap_or_default()
}

fn random_target(rng: &mut Rng, vertices: usize) -> Target {
    match rng.below(4) {
        0 => Target::RemovePercent(rng.below(101) as f64),
        1 => Target::RemoveVertices(rng.below(vertices as u64 + 10) as usize),
        2 => Target::KeepVertices(rng.below(vertices as u64) as usize),
        _ => Target::KeepTriangles(rng.below(2 * vertices as u64) as usize),
    }
}

#[test]
fn noisy_grids_and_spheres_keep_every_invariant() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for case in 0..200 {
        let roughness = [0.0, 0.001, 0.01, 0.1, 0.5][case % 5];
        let mut model = if case % 2 == 0 {
            shapes::test003()
        } else {
            shapes::uv_sphere(6 + rng.below(10) as u32, 8 + rng.below(16) as u32)
        };
        for p in &mut model.positions {
            *p += Vec3::new(rng.signed(), rng.signed(), rng.signed()) * roughness;
        }
        let before = model.clone();
        let target = random_target(&mut rng, before.positions.len());
        let angle = [10.0, 30.0, 60.0, 180.0][rng.below(4) as usize];
        let after = run(model, target, angle);
        let what = format!("case {case}: roughness {roughness}, {target:?}, angle {angle}");
        if after.triangles.is_empty() {
            continue; // dropped under four vertices: allowed
        }
        let broken = measure::invariant_violations(&before, &after);
        assert!(broken.is_empty(), "{what}: {broken:?}");
        if let Target::RemovePercent(p) = target {
            let asked = ((p / 100.0) * before.positions.len() as f64).round() as usize;
            let removed = before.positions.len() - after.positions.len();
            assert!(removed <= asked, "{what}: removed {removed} > {asked}");
        }
    }
}

#[test]
fn random_triangle_soups_never_panic_or_get_worse() {
    let mut rng = Rng(0x0123_4567_89ab_cdef);
    for case in 0..1000 {
        let n = 4 + rng.below(40) as usize;
        // Few distinct positions (on a coarse lattice): coincident and collinear points.
        let positions: Vec<Vec3> = (0..n)
            .map(|_| {
                Vec3::new(
                    rng.below(4) as f32,
                    rng.below(4) as f32,
                    rng.below(3) as f32,
                )
            })
            .collect();
        let triangles: Vec<[u32; 3]> = (0..rng.below(3 * n as u64) + 1)
            .map(|_| [0; 3].map(|_| rng.below(n as u64) as u32))
            .collect();
        let model = Model {
            positions,
            triangles,
            ..Model::default()
        };
        let before = measure::edge_counts(&model);
        let target = random_target(&mut rng, n);
        let after = run(model, target, 30.0);
        let what = format!("case {case}: {target:?}");
        assert!(
            after
                .triangles
                .iter()
                .flatten()
                .all(|&v| (v as usize) < after.positions.len()),
            "{what}: index out of range"
        );
        let e = measure::edge_counts(&after);
        assert!(
            e.non_manifold + e.misoriented <= before.non_manifold + before.misoriented,
            "{what}: {e:?} vs {before:?}"
        );
    }
}
