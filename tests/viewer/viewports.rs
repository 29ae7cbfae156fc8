//! Golden screenshots of tiled viewports: one, two side by side, four in a 2×2 grid, each
//! framing the whole model; the world transform of a model is honoured when framing; the
//! report's four-up figure, each viewport with its own target and a caption.

use decimate_core::decimate::{Params, Target};
use decimate_core::mesh::Scene;
use decimate_viewer::app::shot::ShotOptions;
use decimate_viewer::render::offscreen::RgbaImage;
use glam::{Mat4, Vec3};

use crate::support::shot::*;

#[test]
fn four_viewports_tile_the_picture_and_each_shows_the_model() {
    let scene = cube(10);
    let image = render(&scene, 4, modes("triangles,edges"), None);
    assert_background_corners(&image);
    let (hw, hh) = (WIDTH / 2, HEIGHT / 2);
    for (x, y) in [(0, 0), (hw, 0), (0, hh), (hw, hh)] {
        let covered = coverage(&image, x + 4, y + 4, x + hw - 4, y + hh - 4);
        assert!(
            (0.2..0.8).contains(&covered),
            "tile at ({x}, {y}) is {:.0} % covered",
            covered * 100.0
        );
    }
    assert_matches_golden("cube10_4viewports", &image);
}

#[test]
fn two_viewports_sit_side_by_side() {
    let scene = cube(10);
    let image = render(&scene, 2, modes("triangles"), None);
    assert_background_corners(&image);
    // The separator column between the halves is not background.
    let mid = pixel(&image, WIDTH / 2, HEIGHT / 2);
    assert!(
        !close(mid, background(), 6),
        "no separator between the viewports: {mid:?}"
    );
    assert_matches_golden("cube10_2viewports", &image);
}

#[test]
fn a_transformed_model_is_framed_where_it_is() {
    // A sphere far from the origin and scaled: still centred and fully in view.
    let transform =
        Mat4::from_translation(Vec3::new(50.0, -20.0, 7.0)) * Mat4::from_scale(Vec3::splat(3.0));
    let scene = sphere(24, 48, transform);
    let image = render(&scene, 1, modes("triangles"), None);
    assert_background_corners(&image);
    let centre = pixel(&image, WIDTH / 2, HEIGHT / 2);
    assert!(
        !close(centre, background(), 6),
        "the sphere is not at the centre"
    );
    let covered = coverage(&image, 0, 0, WIDTH, HEIGHT);
    assert!(
        (0.1..0.8).contains(&covered),
        "the sphere covers {:.0} %",
        covered * 100.0
    );
    assert_matches_golden("sphere_transformed", &image);
}

/// Pixels inside `(x0, y0)..(x1, y1)` where `a` and `b` differ by more than `tolerance`.
fn differing(a: &RgbaImage, b: &RgbaImage, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> usize {
    let mut n = 0;
    for y in y0..y1 {
        for x in x0..x1 {
            if !close(pixel(a, x, y), pixel(b, x, y), 24) {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn the_report_figure_captions_each_viewport_with_its_own_target() {
    // decimate assets/test006.wrl shot --viewports 4 -p 60,80,90 --mode triangles,edges
    let scene = Scene {
        models: vec![decimate_core::mesh::shapes::test006()],
    };
    let (width, height) = (640, 480);
    let mut options = ShotOptions {
        width,
        height,
        viewports: 4,
        modes: modes("triangles,edges"),
        targets: [60.0, 80.0, 90.0].map(Target::RemovePercent).to_vec(),
        msaa: 1,
        ..ShotOptions::default()
    };
    let params = Params {
        target: Target::RemovePercent(60.0),
        ..Params::default()
    };
    let (labelled, reports) = render_with(&scene, &options, Some(&params));
    // One decimation per target, each coarser than the one before.
    let left: Vec<usize> = reports
        .iter()
        .map(|r| r.models.iter().map(|m| m.vertices_after).sum())
        .collect();
    let n = scene.models[0].used_vertex_count();
    assert_eq!(left.len(), 3);
    for (kept, p) in left.iter().zip([60.0, 80.0, 90.0]) {
        let asked = n - (n as f64 * p / 100.0).round() as usize;
        assert_eq!(*kept, asked, "{p} %: {kept} of {n} left");
    }
    // Captions are on by default with four viewports; without them the picture differs only
    // in each tile's bottom-right corner, where its caption sits.
    options.labels = Some(false);
    let (bare, _) = render_with(&scene, &options, Some(&params));
    let (hw, hh) = (width / 2, height / 2);
    for (x, y) in [(0, 0), (hw, 0), (0, hh), (hw, hh)] {
        let corner = (x + hw - 170, y + hh - 45, x + hw, y + hh);
        let caption = differing(&labelled, &bare, corner);
        assert!(
            caption > 300,
            "tile at ({x}, {y}): {caption} caption pixels"
        );
        let whole = differing(&labelled, &bare, (x, y, x + hw, y + hh));
        assert_eq!(
            whole, caption,
            "tile at ({x}, {y}) changed outside its caption"
        );
    }
    assert_matches_golden("test006_report_figure", &labelled);
}

#[test]
fn measured_captions_add_each_levels_metro_error() {
    // decimate assets/test006.wrl shot --viewports 2 -p 90 --measure
    let scene = Scene {
        models: vec![decimate_core::mesh::shapes::test006()],
    };
    let (width, height) = (640, 320);
    let mut options = ShotOptions {
        width,
        height,
        viewports: 2,
        measure: true,
        ..ShotOptions::default()
    };
    let params = Params {
        target: Target::RemovePercent(90.0),
        ..Params::default()
    };
    let (measured, _) = render_with(&scene, &options, Some(&params));
    options.measure = false;
    let (counted, _) = render_with(&scene, &options, Some(&params));
    // The original's caption is the same; the decimated one grows a line above its counts
    // (captions sit in the bottom-right corner), and nothing else changes.
    let half = width / 2;
    assert_eq!(differing(&measured, &counted, (0, 0, half, height)), 0);
    let caption = (half, height - 70, width, height);
    let grown = differing(&measured, &counted, caption);
    assert!(grown > 300, "{grown} caption pixels changed");
    assert_eq!(
        differing(&measured, &counted, (half, 0, width, height)),
        grown,
        "the decimated tile changed outside its caption"
    );
    assert_matches_golden("test006_measured", &measured);
}

#[test]
fn three_viewports_leave_no_empty_quadrant_and_the_background_is_asked_for() {
    let options = ShotOptions {
        width: 480,
        height: HEIGHT,
        viewports: 3,
        modes: modes("triangles"),
        labels: Some(true),
        msaa: 1,
        targets: [60.0, 90.0].map(Target::RemovePercent).to_vec(),
        background: Some([1.0, 1.0, 1.0]),
        ..ShotOptions::default()
    };
    let (image, reports) = render_with(&cube(10), &options, Some(&Params::default()));
    assert_eq!(reports.len(), 2);
    // Each quadrant of the picture shows some of a model (no black or empty quarter).
    let (hw, hh) = (image.width / 2, image.height / 2);
    let white = [255, 255, 255, 255];
    for (x, y) in [(0, 0), (hw, 0), (0, hh), (hw, hh)] {
        let drawn = (y..y + hh)
            .flat_map(|py| (x..x + hw).map(move |px| (px, py)))
            .filter(|&(px, py)| !close(pixel(&image, px, py), white, 6))
            .count();
        assert!(
            drawn * 20 > (hw * hh) as usize,
            "the quadrant at ({x}, {y}) is nearly empty: {drawn} pixels drawn"
        );
    }
    // The corners show the background asked for.
    for (x, y) in [(0, 0), (image.width - 1, 0)] {
        assert!(close(pixel(&image, x, y), white, 2), "corner ({x}, {y})");
    }
    assert_matches_golden("cube10_3viewports_white", &image);
}
