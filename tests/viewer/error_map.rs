//! The error heat-map (`--mode error`): a vertex moved far from the original gets the hot end
//! of the ramp, the original is drawn in neutral grey, decimated viewports in ramp colours
//! with a legend; and a golden of a decimated sphere beside its original.

use decimate_core::decimate::{Params, Target};
use decimate_core::mesh::Attribute;
use decimate_core::metro::field::error_field;
use decimate_viewer::app::error_map::{self, heat_scene, neutral_scene, ramp, Legend};
use decimate_viewer::app::shot::ShotOptions;
use decimate_viewer::render::offscreen::RgbaImage;
use glam::Vec3;

use crate::support::shot::*;

#[test]
fn a_vertex_moved_far_gets_the_hot_end_of_the_ramp() {
    let original = cube(10);
    let mut moved = original.clone();
    // A corner vertex of the 2×2×2 cube pushed one unit further out along its diagonal.
    let corner = (moved.models[0].positions.iter())
        .position(|p| *p == Vec3::ONE)
        .unwrap_or_else(|| panic!("the cube has no (1, 1, 1) corner"));
    moved.models[0].positions[corner] = Vec3::splat(1.0 + 1.0 / 3f32.sqrt());
    let field = error_field(&original, &moved);
    assert!(
        (field.max - 1.0).abs() < 1e-4,
        "the moved corner is 1 unit away, max {}",
        field.max
    );
    let legend = Legend::spanning([&field]);
    let heat = heat_scene(&moved, &field, &legend);
    let Some(Attribute::PerVertex(colours)) = &heat.models[0].colors else {
        panic!("the heat-map gives no per-vertex colours");
    };
    assert_eq!(colours.len(), moved.models[0].positions.len());
    let near = |a: [f32; 3], b: [f32; 3]| a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-3);
    assert!(
        near(colours[corner], ramp(1.0)),
        "the moved corner is {:?}, not the hot end",
        colours[corner]
    );
    // Vertices away from it (beyond the faces it moved) kept their place: the cold end.
    for (v, p) in original.models[0].positions.iter().enumerate() {
        if p.distance(Vec3::ONE) > 0.5 {
            assert!(near(colours[v], ramp(0.0)), "vertex {v} at {p} is coloured");
        }
    }
    let neutral = neutral_scene(&original);
    assert!(neutral.models[0].colors.is_none());
    assert_eq!(neutral.models[0].diffuse, error_map::NEUTRAL);
}

/// How far a pixel is from grey: its largest channel minus its smallest.
fn saturation(p: [u8; 4]) -> u8 {
    p[..3].iter().max().unwrap_or(&0) - p[..3].iter().min().unwrap_or(&0)
}

fn pixels_in(image: &RgbaImage, x0: u32, y0: u32, x1: u32, y1: u32) -> Vec<[u8; 4]> {
    (y0..y1)
        .flat_map(|y| (x0..x1).map(move |x| (x, y)))
        .map(|(x, y)| pixel(image, x, y))
        .collect()
}

#[test]
fn decimated_viewports_are_heat_mapped_with_a_legend_and_the_original_stays_grey() {
    let scene = sphere(16, 32, glam::Mat4::IDENTITY);
    let options = ShotOptions {
        width: 2 * WIDTH,
        height: HEIGHT,
        viewports: 2,
        modes: modes("error"),
        labels: Some(true),
        msaa: 1,
        ..ShotOptions::default()
    };
    let params = Params {
        target: Target::RemovePercent(90.0),
        ..Params::default()
    };
    let (image, reports) = render_with(&scene, &options, Some(&params));
    assert_eq!(reports.len(), 1);
    let half = image.width / 2;
    // The original, in grey: no pixel of it is coloured (the caption is grey on black too).
    let left = pixels_in(&image, 0, 0, half - 1, image.height);
    let coloured = left.iter().filter(|&&p| saturation(p) > 16).count();
    assert_eq!(coloured, 0, "{coloured} coloured pixels on the original");
    assert!(coverage(&image, 0, 0, half - 1, image.height) > 0.1);
    // The decimated sphere is coloured along the ramp, from cold (blue) to warm.
    let right = pixels_in(&image, half + 1, 60, image.width, image.height - 40);
    let ramp_coloured = right.iter().filter(|&&p| saturation(p) > 60).count();
    assert!(
        ramp_coloured as f64 > 0.1 * right.len() as f64,
        "only {ramp_coloured} of {} pixels are heat-mapped",
        right.len()
    );
    // The legend at the top right shows both ends of the ramp.
    let legend = pixels_in(&image, half + 1, 0, image.width, 50);
    let [hot, cold] = [ramp(1.0), ramp(0.0)].map(|c| c.map(|x| (x * 255.0).round() as u8));
    for (name, end) in [("hot", hot), ("cold", cold)] {
        let rgba = [end[0], end[1], end[2], 255];
        assert!(
            legend.iter().any(|&p| close(p, rgba, 12)),
            "the legend lacks its {name} end {rgba:?}"
        );
    }
    assert_matches_golden("sphere_error_map_p90", &image);
}
