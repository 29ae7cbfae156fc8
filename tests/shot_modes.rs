//! Golden screenshots on lavapipe, one per draw mode, of a 10×10-segment cube (test004's
//! shape) built in code, plus what a user would notice: the model fills a sensible part of
//! the picture, the corners show the background, and each mode looks different.

mod shot_support;

use shot_support::*;

const MODES: [&str; 8] = [
    "triangles",
    "triangles,flat",
    "triangles,unlit",
    "edges",
    "triangles,edges",
    "points",
    "triangles,normals",
    "triangles,vertex-normals",
];

#[test]
fn every_draw_mode_matches_its_golden() {
    let scene = cube(10);
    for mode in MODES {
        let image = render(&scene, 1, modes(mode), None);
        assert_background_corners(&image);
        let covered = coverage(&image, 0, 0, WIDTH, HEIGHT);
        // Filled modes cover the cube's silhouette; lines and points leave gaps between them.
        let least = if mode.starts_with("triangles") {
            0.2
        } else {
            0.05
        };
        assert!(
            (least..0.8).contains(&covered),
            "{mode}: the model covers {:.0} % of the picture",
            covered * 100.0
        );
        assert_matches_golden(&format!("cube10_{}", mode.replace(',', "_")), &image);
    }
}

#[test]
fn each_mode_looks_different_from_the_others() {
    let scene = cube(10);
    let images: Vec<_> = MODES
        .iter()
        .map(|m| render(&scene, 1, modes(m), None))
        .collect();
    for i in 0..MODES.len() {
        for j in i + 1..MODES.len() {
            let d = different_fraction(&images[i], &images[j], CHANNEL_TOLERANCE);
            assert!(
                d > 0.01,
                "{} and {} look alike ({:.2} % differ)",
                MODES[i],
                MODES[j],
                d * 100.0
            );
        }
    }
}

#[test]
fn edges_alone_show_the_background_between_them() {
    let scene = cube(10);
    let solid = render(&scene, 1, modes("triangles"), None);
    let wire = render(&scene, 1, modes("edges"), None);
    // At the centre the solid cube is opaque; the wireframe lets the background through.
    let solid_centre = coverage(&solid, 140, 100, 180, 140);
    let wire_centre = coverage(&wire, 140, 100, 180, 140);
    assert!(solid_centre > 0.99, "solid centre covered {solid_centre}");
    assert!(wire_centre < 0.6, "wireframe centre covered {wire_centre}");
}
