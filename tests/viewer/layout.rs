//! The viewer's layout, painted by the window's own overlay code through `shot`: the status
//! line in a strip of its own below the viewports (never under a caption), the help overlay
//! over the captions, the heat-map legend inside each heat-mapped viewport with its units and
//! ticks. Goldens at the window's default size.

use decimate_core::decimate::{Params, Target};
use decimate_core::mesh::Scene;
use decimate_viewer::app::error_map::ramp;
use decimate_viewer::app::overlay::{status_strip, STATUS_POINTS};
use decimate_viewer::app::shot::ShotOptions;
use decimate_viewer::render::offscreen::RgbaImage;
use decimate_viewer::render::tiles::tiles;

use crate::support::shot::*;

const W: u32 = 640;
const H: u32 = 480;

fn four_up(scene: &Scene, modes_list: &str, status: Option<&str>, help: bool) -> RgbaImage {
    let options = ShotOptions {
        width: W,
        height: H,
        viewports: 4,
        modes: modes(modes_list),
        labels: Some(true),
        msaa: 1,
        targets: [60.0, 80.0, 90.0].map(Target::RemovePercent).to_vec(),
        status: status.map(str::to_string),
        help,
        ..ShotOptions::default()
    };
    let params = Params::default();
    render_with(scene, &options, Some(&params)).0
}

#[test]
fn the_status_line_has_a_strip_of_its_own_below_the_captions() {
    let long = "viewport 3/4: 90 % removed: 61 vertices, 118 triangles left in 0.004 s — \
                qem, feature angle 45°, border free, error 0.0123 (0.61 % of the diagonal) \
                — and more words than the window is wide";
    let image = four_up(&cube(10), "triangles", Some(long), false);
    let strip = status_strip(H, 1.0);
    assert_eq!(strip, STATUS_POINTS as u32);
    // The viewports end above the strip.
    let rects = tiles(4, W, H - strip);
    assert!(rects.iter().all(|r| r.y + r.height <= H - strip));
    // No pixel of the strip shows a viewport's background or a caption's box: only the
    // strip's colour and the status text.
    let bg = background();
    let strip_colour = [24, 24, 28, 255];
    let mut text = 0;
    for y in H - strip..H {
        for x in 0..W {
            let p = pixel(&image, x, y);
            assert!(
                !close(p, bg, 4),
                "viewport background at ({x}, {y}) in the strip"
            );
            if !close(p, strip_colour, 8) {
                text += 1;
            }
        }
    }
    assert!(text > 500, "the status text is missing ({text} pixels)");
    // The text reaches the right end (a long message is cut there, not hidden).
    let right = (H - strip..H)
        .filter(|&y| (W - 40..W).any(|x| !close(pixel(&image, x, y), strip_colour, 8)))
        .count();
    assert!(
        right > 0,
        "the long status line does not reach the right edge"
    );
    // Each bottom viewport's caption sits inside it, right above the strip.
    for r in &rects[2..] {
        let caption_rows = (r.y + r.height - 40..r.y + r.height)
            .filter(|&y| (r.x + r.width - 60..r.x + r.width).any(|x| pixel(&image, x, y)[0] > 200))
            .count();
        assert!(caption_rows > 5, "no caption at the bottom of {r:?}");
    }
    assert_matches_golden("cube10_4viewports_status", &image);
}

#[test]
fn the_help_overlay_covers_the_captions_not_the_other_way() {
    let without = four_up(
        &cube(10),
        "triangles",
        Some("viewport 1/4: original"),
        false,
    );
    let with = four_up(&cube(10), "triangles", Some("viewport 1/4: original"), true);
    assert_matches_golden("cube10_help_over_captions", &with);
    // Viewport 2's caption (top-right tile, bottom-right corner) is under the help: the
    // help's box is drawn there, so those pixels change to the help's opaque frame.
    let r = tiles(4, W, H - status_strip(H, 1.0))[1];
    let (x0, y0) = (r.x + r.width - 120, r.y + r.height - 30);
    let mut changed = 0;
    for y in y0..r.y + r.height - 4 {
        for x in x0..r.x + r.width - 8 {
            if !close(pixel(&with, x, y), pixel(&without, x, y), 24) {
                changed += 1;
            }
        }
    }
    assert!(
        changed > 500,
        "the help does not cover viewport 2's caption ({changed})"
    );
    assert_matches_golden("cube10_help_over_captions", &with);
}

#[test]
fn the_legend_sits_inside_each_heat_mapped_viewport() {
    let image = four_up(&sphere(16, 32, glam::Mat4::IDENTITY), "error", None, false);
    assert_matches_golden("sphere_error_legend_4viewports", &image);
    let rects = tiles(4, W, H);
    let [hot, cold] = [ramp(1.0), ramp(0.0)].map(|c| c.map(|x| (x * 255.0).round() as u8));
    let has = |r: &decimate_viewer::render::tiles::Rect, rgb: [u8; 3]| {
        let rgba = [rgb[0], rgb[1], rgb[2], 255];
        (r.y..r.y + 40).any(|y| (r.x..r.x + r.width).any(|x| close(pixel(&image, x, y), rgba, 12)))
    };
    // Viewport 3 of 4 (bottom-left, decimated by 80 %) holds the bar's ends near its top.
    let third = &rects[2];
    assert!(
        has(third, hot) && has(third, cold),
        "no legend in viewport 3"
    );
    // The original (viewport 1) has none.
    assert!(!has(&rects[0], hot), "a legend on the original");
}

/// White text pixels (captions) in the picture.
fn text_pixels(image: &RgbaImage) -> usize {
    (image.pixels.chunks_exact(4))
        .filter(|p| p[0] > 200 && p[1] > 200 && p[2] > 200)
        .count()
}

#[test]
fn captions_grow_with_the_picture() {
    let shot = |width, height| {
        let options = ShotOptions {
            width,
            height,
            viewports: 2,
            modes: modes("triangles"),
            labels: Some(true),
            msaa: 1,
            ..ShotOptions::default()
        };
        render_with(&cube(10), &options, Some(&Params::default())).0
    };
    let (small, large) = (shot(640, 480), shot(1600, 1200));
    // At 1600 × 1200 the text is 1200 / 720 times as tall and wide: its area about 2.8
    // times; at one size for both it would be the same.
    let ratio = text_pixels(&large) as f64 / text_pixels(&small) as f64;
    assert!(
        (2.0..4.0).contains(&ratio),
        "caption text covers {ratio:.2} times as many pixels at 1600 × 1200 as at 640 × 480"
    );
}
