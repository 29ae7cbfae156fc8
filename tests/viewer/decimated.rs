//! Golden screenshots of decimated meshes: the Stanford bunny (assets/bunny.ply) and the
//! 10×10-segment cube, each algorithm, the original beside its levels at 60, 80 and 90 % of
//! the vertices removed. Besides the pictures: each level keeps exactly the vertices asked
//! for, keeps the original's silhouette (its coverage of the tile) and looks different from
//! the original and from the other levels.

use std::path::Path;

use decimate_core::decimate::{Algorithm, Params, Target};
use decimate_core::mesh::Scene;
use decimate_viewer::app::shot::ShotOptions;
use decimate_viewer::render::offscreen::RgbaImage;

use crate::support::shot::*;

const LEVELS: [f64; 3] = [60.0, 80.0, 90.0];
const SIZE: (u32, u32) = (640, 480);

fn bunny() -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.ply");
    decimate_core::io::read_scene(&path)
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

/// Tile `k` (0: the original, then the levels) of a 2×2 picture.
fn tile(image: &RgbaImage, k: u32) -> RgbaImage {
    let (hw, hh) = (image.width / 2, image.height / 2);
    let (x0, y0) = ((k % 2) * hw, (k / 2) * hh);
    let mut pixels = Vec::with_capacity((hw * hh * 4) as usize);
    for y in y0..y0 + hh {
        let row = ((y * image.width + x0) * 4) as usize;
        pixels.extend_from_slice(&image.pixels[row..row + (hw * 4) as usize]);
    }
    RgbaImage {
        width: hw,
        height: hh,
        pixels,
    }
}

/// Renders `scene` and its three levels under `algorithm`, checks what a user would see,
/// and compares the picture with the golden `name`.
fn levels_match_their_golden(scene: &Scene, algorithm: Algorithm, name: &str) {
    let options = ShotOptions {
        width: SIZE.0,
        height: SIZE.1,
        viewports: 4,
        modes: modes("triangles,edges"),
        labels: Some(false),
        targets: LEVELS.map(Target::RemovePercent).to_vec(),
        msaa: 1,
        ..ShotOptions::default()
    };
    let params = Params {
        algorithm,
        ..Params::default()
    };
    let (image, reports) = render_with(scene, &options, Some(&params));
    assert_background_corners(&image);
    // Exactly the vertices asked for: n less p % of n, rounded.
    let n: usize = scene.models.iter().map(|m| m.used_vertex_count()).sum();
    let left: Vec<usize> = reports
        .iter()
        .map(|r| r.models.iter().map(|m| m.vertices_after).sum())
        .collect();
    let asked: Vec<usize> = LEVELS
        .iter()
        .map(|p| n - (n as f64 * p / 100.0).round() as usize)
        .collect();
    assert_eq!(left, asked, "{name}: vertices left at {LEVELS:?} % of {n}");
    // The silhouette stays: a lost part or triangles turned away (culled) would uncover
    // the tile. A coarser level differs more from the original, and the levels differ.
    let tiles: Vec<RgbaImage> = (0..4).map(|k| tile(&image, k)).collect();
    let covered = |t: &RgbaImage| coverage(t, 0, 0, t.width, t.height);
    let original = covered(&tiles[0]);
    for (t, p) in tiles[1..].iter().zip(LEVELS) {
        let c = covered(t);
        assert!(
            (c - original).abs() < 0.1 * original,
            "{name} at {p} %: covers {:.1} % of its tile, the original {:.1} %",
            c * 100.0,
            original * 100.0
        );
    }
    for i in 0..4 {
        for j in i + 1..4 {
            let d = different_fraction(&tiles[i], &tiles[j], CHANNEL_TOLERANCE);
            assert!(d > 0.01, "{name}: tiles {i} and {j} look alike ({d:.4})");
        }
    }
    assert_matches_golden(name, &image);
}

#[test]
fn the_bunny_decimated_by_schroeder_matches_its_golden() {
    levels_match_their_golden(&bunny(), Algorithm::Schroeder, "bunny_schroeder_p60_80_90");
}

#[test]
fn the_bunny_decimated_by_qem_matches_its_golden() {
    levels_match_their_golden(&bunny(), Algorithm::Qem, "bunny_qem_p60_80_90");
}

#[test]
fn the_cube_decimated_by_schroeder_matches_its_golden() {
    levels_match_their_golden(
        &cube(10),
        Algorithm::Schroeder,
        "cube10_schroeder_p60_80_90",
    );
}

#[test]
fn the_cube_decimated_by_qem_matches_its_golden() {
    levels_match_their_golden(&cube(10), Algorithm::Qem, "cube10_qem_p60_80_90");
}
