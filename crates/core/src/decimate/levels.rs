//! Which level of each model of a progressive scene (`FILE.pm`) meets a count target: the
//! splits are the recorded decimation's collapses in reverse, so a level is that decimation
//! as it stood once it had removed that many vertices (or come down to that many
//! triangles). Counts are shared among the models as [`super::simplify_scene`] shares them,
//! in proportion to the full meshes' sizes (`Shares`). A level never goes below the base mesh, the
//! coarsest the file holds, and never splits one side of a texture seam without the other
//! (it keeps one vertex fewer instead).

use super::{Shares, Target};
use crate::mesh::progressive::ProgressiveScene;

/// The level (splits applied to the base) of each model of `pm` for `target`; `None` for a
/// target that is no count (an error bound alone: the file records no errors).
pub fn levels_for(pm: &ProgressiveScene, target: Target) -> Option<Vec<usize>> {
    if target == Target::ErrorOnly {
        return None;
    }
    let vertices: Vec<usize> = pm.models.iter().map(|m| m.full_vertex_count()).collect();
    let triangles: Vec<usize> = pm.models.iter().map(|m| m.full_face_count()).collect();
    let shares = Shares::of(target, &vertices, &triangles);
    let levels = pm.models.iter().enumerate().map(|(i, m)| {
        let splits = m.splits.len();
        let level = if let Target::KeepTriangles(_) = target {
            // Faces only grow with the level: the finest level within the share.
            let keep = shares.keep_triangles[i];
            let mut faces = m.base.triangles.len();
            m.splits
                .iter()
                .take_while(|s| {
                    faces += s.added.len();
                    faces <= keep
                })
                .count()
        } else {
            splits - shares.removals[i].min(splits)
        };
        // Never half of a seam's two splits: one vertex fewer rather than a crack.
        m.whole_level(level)
    });
    Some(levels.collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::decimate::{simplify_scene_progressive, Params};
    use crate::mesh::{shapes, Scene};

    /// A scene of two spheres of different sizes, decimated to 10 % with a record.
    fn recorded() -> (Scene, ProgressiveScene) {
        let mut scene = Scene {
            models: vec![shapes::uv_sphere(20, 40), shapes::uv_sphere(10, 20)],
        };
        let params = Params {
            target: Target::RemovePercent(90.0),
            ..Params::default()
        };
        let original = scene.clone();
        let (_, pm) = simplify_scene_progressive(&mut scene, &params, &mut |_| {});
        (original, pm)
    }

    #[test]
    fn levels_keep_the_counts_a_decimation_of_the_full_mesh_keeps() {
        let (original, pm) = recorded();
        let full: Vec<usize> = pm.models.iter().map(|m| m.full_vertex_count()).collect();
        let used: Vec<usize> = original
            .models
            .iter()
            .map(|m| m.used_vertex_count())
            .collect();
        assert_eq!(full, used);
        for p in [0.0, 25.0, 50.0, 80.0] {
            let levels = levels_for(&pm, Target::RemovePercent(p)).unwrap_or_default();
            for ((m, level), n) in pm.models.iter().zip(&levels).zip(&full) {
                let removed = ((p / 100.0) * *n as f64).round() as usize;
                assert_eq!(m.base.positions.len() + level, n - removed, "{p} %");
            }
        }
        // Past the base: the base.
        let levels = levels_for(&pm, Target::RemovePercent(99.0)).unwrap_or_default();
        assert_eq!(levels, vec![0, 0]);
        let total: usize = full.iter().sum();
        let levels = levels_for(&pm, Target::KeepVertices(total - 100)).unwrap_or_default();
        let kept: usize = pm
            .models
            .iter()
            .zip(&levels)
            .map(|(m, l)| m.base.positions.len() + l)
            .sum();
        assert_eq!(kept, total - 100);
        assert_eq!(levels_for(&pm, Target::ErrorOnly), None);
    }

    #[test]
    fn a_triangle_target_takes_the_finest_level_within_it() {
        let (_, pm) = recorded();
        let faces: usize = pm.models.iter().map(|m| m.full_face_count()).sum();
        let keep = faces / 2 + 1; // odd shares: some level must stop one face short
        let levels = levels_for(&pm, Target::KeepTriangles(keep)).unwrap_or_default();
        let mut total = 0;
        for (m, &level) in pm.models.iter().zip(&levels) {
            let at = |l: usize| {
                m.base.triangles.len() + m.splits[..l].iter().map(|s| s.added.len()).sum::<usize>()
            };
            total += at(level);
            assert!(level < m.splits.len(), "not the full mesh");
            assert!(at(level + 1) > at(level));
        }
        assert!(total <= keep && total + 4 > keep, "{total} of {keep}");
    }
}
