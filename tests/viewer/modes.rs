//! Golden screenshots on lavapipe, one per draw mode, of a 10×10-segment cube (test004's
//! shape) built in code, plus what a user would notice: the model fills a sensible part of
//! the picture, the corners show the background, each mode looks different — except smooth
//! and flat shading of a cube, which must look the same (its edges are creases), while on a
//! sphere they must not.

use crate::support::shot::*;

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
            if (MODES[i], MODES[j]) == ("triangles", "triangles,flat") {
                // Smooth shading keeps creases sharp: a cube's faces stay flat.
                assert!(
                    d < 0.005,
                    "a smooth-shaded cube looks rounded ({:.2} % differ from flat)",
                    d * 100.0
                );
                continue;
            }
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
fn smooth_and_flat_shading_differ_on_a_sphere() {
    // A coarse sphere, compared closely: facets differ by a few levels of grey.
    let scene = sphere(6, 12, glam::Mat4::IDENTITY);
    let smooth = render(&scene, 1, modes("triangles"), None);
    let flat = render(&scene, 1, modes("triangles,flat"), None);
    let d = different_fraction(&smooth, &flat, 4);
    assert!(
        d > 0.05,
        "smooth and flat spheres look alike ({:.2} % differ)",
        d * 100.0
    );
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
