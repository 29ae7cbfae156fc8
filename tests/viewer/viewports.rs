//! Golden screenshots of tiled viewports: one, two side by side, four in a 2×2 grid, each
//! framing the whole model; and the world transform of a model is honoured when framing.

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
