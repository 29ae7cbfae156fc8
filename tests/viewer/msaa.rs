//! Multisample anti-aliasing on lavapipe: a slanted edge gets pixels of intermediate colour
//! with 4× MSAA and none without, and a golden of a cube's edges over its faces with 4× MSAA.

use decimate_core::mesh::{Model, Scene};
use decimate_viewer::app::shot::ShotOptions;
use decimate_viewer::render::offscreen::RgbaImage;
use glam::Vec3;

use crate::support::shot::*;

/// One flat, unlit triangle whose edges are neither horizontal nor vertical.
fn slanted_triangle() -> Scene {
    let model = Model {
        name: "slanted".into(),
        positions: vec![
            Vec3::new(-1.0, -0.8, 0.0),
            Vec3::new(1.0, -0.5, 0.0),
            Vec3::new(-0.3, 1.0, 0.0),
        ],
        triangles: vec![[0, 1, 2]],
        diffuse: [0.9, 0.9, 0.9],
        ..Model::default()
    };
    Scene {
        models: vec![model],
    }
}

fn shoot(scene: &Scene, mode: &str, msaa: u32) -> RgbaImage {
    let options = ShotOptions {
        width: WIDTH,
        height: HEIGHT,
        modes: modes(mode),
        labels: Some(false),
        msaa,
        ..ShotOptions::default()
    };
    render_with(scene, &options, None).0
}

/// Pixels that are neither the background nor the triangle's own colour: the blend of the
/// two that only anti-aliasing makes along its edges.
fn intermediate_pixels(image: &RgbaImage, face: [u8; 4]) -> usize {
    let bg = background();
    image
        .pixels
        .chunks_exact(4)
        .map(|p| [p[0], p[1], p[2], p[3]])
        .filter(|&p| !close(p, bg, 2) && !close(p, face, 2))
        .count()
}

/// The colour most pixels that are not background have.
fn face_colour(image: &RgbaImage) -> [u8; 4] {
    let bg = background();
    let mut counts = std::collections::HashMap::new();
    for p in image.pixels.chunks_exact(4) {
        let p = [p[0], p[1], p[2], p[3]];
        if !close(p, bg, 2) {
            *counts.entry(p).or_insert(0usize) += 1;
        }
    }
    counts
        .into_iter()
        .max_by_key(|&(_, n)| n)
        .map(|(p, _)| p)
        .unwrap_or_else(|| panic!("the triangle is not in the picture"))
}

#[test]
fn a_slanted_edge_is_smoothed_with_msaa_and_stair_stepped_without() {
    let scene = slanted_triangle();
    let aliased = shoot(&scene, "triangles,unlit", 1);
    let smoothed = shoot(&scene, "triangles,unlit", 4);
    let face = face_colour(&aliased);
    assert!(
        close(face, [230, 230, 230, 255], 2),
        "unlit triangle is {face:?}"
    );
    assert_eq!(
        intermediate_pixels(&aliased, face),
        0,
        "without MSAA every pixel is the face or the background"
    );
    // The three edges run over a few hundred pixels; each crosses a blended pixel per row
    // or column, so at least one edge's worth of them must be blended.
    let blended = intermediate_pixels(&smoothed, face);
    assert!(
        blended > 100,
        "4× MSAA blends only {blended} pixels along the edges"
    );
    // Inside and outside are unchanged: anti-aliasing touches edges only.
    assert!(different_fraction(&aliased, &smoothed, 2) < 0.05);
}

#[test]
fn msaa_edges_over_faces_match_their_golden() {
    let image = shoot(&cube(10), "triangles,edges", 4);
    assert_background_corners(&image);
    assert_matches_golden("cube10_triangles_edges_msaa4", &image);
}
