//! Textured models through the built binary on lavapipe: the image (PNG or JPEG) a VRML 2.0
//! `ImageTexture` names, read beside the file (not the working folder), drawn the right way
//! up, before and after decimation, on a grid with coordinates and on the primitives that
//! make their own (a sphere, a box); an image that cannot be read leaves the model in its
//! material colour with a warning naming the texture; a fine texture seen from afar shows
//! its average colour (mip levels), not a moiré.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use decimate_viewer::render::offscreen::RgbaImage;

use crate::support::shot::{background, close, pixel, write_rgb_png};

const LAVAPIPE: &str = "/usr/share/vulkan/icd.d/lvp_icd.x86_64.json";

/// A fresh scratch folder under target/, so parallel tests never share files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("shot_textures-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("models/maps"))
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// An 8 × 8 image, the top half red, the bottom half blue: a PNG, or a JPEG when the name
/// ends so.
fn write_texture(path: &Path) {
    let mut pixels = Vec::new();
    for row in 0..8 {
        for _ in 0..8 {
            pixels.extend_from_slice(if row < 4 {
                &[230, 20, 20]
            } else {
                &[20, 20, 230]
            });
        }
    }
    if path.extension().is_some_and(|e| e == "jpg") {
        jpeg_encoder::Encoder::new_file(path, 95)
            .and_then(|e| e.encode(&pixels, 8, 8, jpeg_encoder::ColorType::Rgb))
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        return;
    }
    write_rgb_png(path, 8, &pixels);
}

/// A flat `n × n` grid in the xy plane (y up), its texture coordinates spanning the image
/// (v = 1 at the top, as VRML has it), textured with `maps/{image}`.
fn write_grid(path: &Path, n: usize, image: &str) {
    write_textured_grid(path, n, image, 1.0, "");
}

/// [`write_grid`]'s grid with u running from 0 to `u_span` from left to right, its
/// `ImageTexture` with `fields` added (`repeatS FALSE`, …).
fn write_textured_grid(path: &Path, n: usize, image: &str, u_span: f32, fields: &str) {
    let mut points = String::new();
    let mut uvs = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            points.push_str(&format!("{} {} 0, ", 2.0 * u - 1.0, 2.0 * v - 1.0));
            uvs.push_str(&format!("{} {v}, ", u_span * u));
        }
    }
    let mut faces = String::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            faces.push_str(&format!("{a} {b} {c} -1 {a} {c} {d} -1 "));
        }
    }
    let text = format!(
        "#VRML V2.0 utf8\nShape {{\n  appearance Appearance {{\n    \
         texture ImageTexture {{ url \"maps/{image}\" {fields} }}\n  }}\n  \
         geometry IndexedFaceSet {{\n    coord Coordinate {{ point [ {points} ] }}\n    \
         texCoord TextureCoordinate {{ point [ {uvs} ] }}\n    coordIndex [ {faces} ]\n  }}\n}}\n"
    );
    std::fs::write(path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

/// Takes a shot of `models/grid.wrl` from `dir` (so that relative names must be read beside
/// the file, not from the working folder) and reads it back.
fn shot(dir: &Path, extra: &[&str]) -> (Output, RgbaImage) {
    shot_of(dir, "models/grid.wrl", extra)
}

/// [`shot`] of `file` (relative to `dir`).
fn shot_of(dir: &Path, file: &str, extra: &[&str]) -> (Output, RgbaImage) {
    let out_png = dir.join("shot.png");
    let mut args = vec![file, "shot", "-o", "shot.png", "--size", "320x240"];
    args.extend_from_slice(extra);
    let out = Command::new(env!("CARGO_BIN_EXE_decimate"))
        .args(&args)
        .current_dir(dir)
        .env("VK_ICD_FILENAMES", LAVAPIPE)
        .env("VK_DRIVER_FILES", LAVAPIPE)
        .output()
        .unwrap_or_else(|e| panic!("cannot run decimate: {e}"));
    assert!(
        out.status.success(),
        "decimate failed ({}): {}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&out_png).unwrap_or_else(|e| panic!("{}: {e}", out_png.display())),
    ));
    let mut reader = decoder.read_info().unwrap_or_else(|e| panic!("png: {e}"));
    let mut pixels = vec![0; reader.output_buffer_size().unwrap_or(0)];
    let info = reader
        .next_frame(&mut pixels)
        .unwrap_or_else(|e| panic!("png: {e}"));
    assert_eq!(info.color_type, png::ColorType::Rgba);
    let image = RgbaImage {
        width: info.width,
        height: info.height,
        pixels,
    };
    (out, image)
}

/// The rows of viewport `x0..x1` that the model covers: (first, last).
fn model_rows(image: &RgbaImage, x0: u32, x1: u32) -> (u32, u32) {
    let bg = background();
    let covered = |y: u32| (x0..x1).any(|x| !close(pixel(image, x, y), bg, 6));
    let first = (0..image.height).find(|&y| covered(y));
    let last = (0..image.height).rev().find(|&y| covered(y));
    match (first, last) {
        (Some(a), Some(b)) if b > a + 20 => (a, b),
        _ => panic!("the model is not visible in columns {x0}..{x1}"),
    }
}

/// Counts the model's pixels in rows `y0..y1` of columns `x0..x1` that are mostly red and
/// mostly blue.
fn red_and_blue(image: &RgbaImage, (x0, x1): (u32, u32), (y0, y1): (u32, u32)) -> (usize, usize) {
    let (mut red, mut blue) = (0, 0);
    for y in y0..y1 {
        for x in x0..x1 {
            let [r, g, b, _] = pixel(image, x, y).map(u32::from);
            red += usize::from(r > 2 * b + 20 && r > 2 * g + 20);
            blue += usize::from(b > 2 * r + 20 && b > 2 * g + 20);
        }
    }
    (red, blue)
}

/// Asserts the model in columns `x0..x1` shows the texture the right way up: its upper part
/// red, its lower part blue.
fn assert_red_over_blue(image: &RgbaImage, x0: u32, x1: u32) {
    let (top, bottom) = model_rows(image, x0, x1);
    let third = (bottom - top) / 3;
    let (red_up, blue_up) = red_and_blue(image, (x0, x1), (top, top + third));
    let (red_down, blue_down) = red_and_blue(image, (x0, x1), (bottom - third, bottom));
    assert!(
        red_up > 200 && blue_up < red_up / 20,
        "upper third: {red_up} red, {blue_up} blue pixels"
    );
    assert!(
        blue_down > 200 && red_down < blue_down / 20,
        "lower third: {red_down} red, {blue_down} blue pixels"
    );
}

#[test]
fn a_png_or_jpeg_texture_beside_the_file_is_drawn_the_right_way_up_before_and_after_decimation() {
    for image in ["checker.png", "checker.jpg"] {
        let dir = scratch(image);
        write_texture(&dir.join("models/maps").join(image));
        write_grid(&dir.join("models/grid.wrl"), 12, image);
        // No captions: the model's rows are found by what is not background.
        let (out, image) = shot(&dir, &["--viewports", "2", "-p", "80", "--no-labels"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("not drawn"), "{stderr}");
        // The summary says the grid was decimated: the right viewport shows fewer triangles.
        assert!(stderr.contains("removed"), "{stderr}");
        let half = image.width / 2;
        assert_red_over_blue(&image, 0, half - 2);
        assert_red_over_blue(&image, half + 2, image.width);
        // Textures off (the viewer's T): the grid in its material colour.
        let (_, image) = shot(&dir, &["--mode", "untextured"]);
        let (top, bottom) = model_rows(&image, 0, image.width);
        let (red, blue) = red_and_blue(&image, (0, image.width), (top, bottom));
        assert_eq!((red, blue), (0, 0), "textures off: a grey grid");
    }
}

#[test]
fn a_textured_sphere_and_box_show_the_image_upright_before_and_after_decimation() {
    // VRML 2.0 primitives make their own texture coordinates: the sphere's v runs from the
    // bottom pole to the top, the box's front face maps the image upright.
    let dir = scratch("primitives");
    write_texture(&dir.join("models/maps/halves.png"));
    let shape = |x: f32, geometry: &str| {
        format!(
            "Transform {{ translation {x} 0 0 children Shape {{ appearance Appearance {{ \
             texture ImageTexture {{ url \"maps/halves.png\" }} }} geometry {geometry} }} }}\n"
        )
    };
    let text = format!(
        "#VRML V2.0 utf8\n{}{}",
        shape(-1.5, "Sphere {}"),
        shape(1.5, "Box {}")
    );
    std::fs::write(dir.join("models/shapes.wrl"), text).unwrap();
    let (out, image) = shot_of(
        &dir,
        "models/shapes.wrl",
        &["--viewports", "2", "-p", "50", "--no-labels", "--msaa", "1"],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("removed"), "{stderr}");
    // Each viewport (the right one decimated): the sphere in its left half, red over blue;
    // the box in its right half, seen a little from above: its top face too shows both
    // halves, the far one red, so the box is mostly red above its middle, blue below.
    let quarter = image.width / 4;
    for viewport in [0, 2 * quarter] {
        assert_red_over_blue(&image, viewport + 2, viewport + quarter - 2);
        let columns = (viewport + quarter + 2, viewport + 2 * quarter - 2);
        let (top, bottom) = model_rows(&image, columns.0, columns.1);
        let middle = (top + bottom) / 2;
        let (red_up, blue_up) = red_and_blue(&image, columns, (top, middle));
        let (red_down, blue_down) = red_and_blue(&image, columns, (middle, bottom));
        assert!(
            red_up > 2 * blue_up && blue_down > 2 * red_down && blue_up > 0 && red_down > 0,
            "box: above {red_up} red, {blue_up} blue; below {red_down} red, {blue_down} blue"
        );
    }
}

#[test]
fn an_unreadable_texture_leaves_the_material_colour_and_says_why() {
    let dir = scratch("unreadable");
    write_grid(&dir.join("models/grid.wrl"), 4, "checker.png");
    // Missing, then a GIF, then a JPEG cut short: drawn untextured, with the reason.
    let mut jpeg = Vec::new();
    jpeg_encoder::Encoder::new(&mut jpeg, 90)
        .encode(&[200; 8 * 8 * 3], 8, 8, jpeg_encoder::ColorType::Rgb)
        .unwrap_or_else(|e| panic!("{e}"));
    jpeg.truncate(jpeg.len() / 2);
    for (bytes, reason) in [
        (None, "checker.png"),
        (Some(b"GIF89a".to_vec()), "neither a PNG nor a JPEG"),
        (Some(jpeg), "JPEG"),
    ] {
        if let Some(bytes) = &bytes {
            std::fs::write(dir.join("models/maps/checker.png"), bytes)
                .unwrap_or_else(|e| panic!("{e}"));
        }
        let (out, image) = shot(&dir, &[]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(
            stderr.contains("texture \"maps/checker.png\" not drawn") && stderr.contains(reason),
            "{stderr}"
        );
        let (top, bottom) = model_rows(&image, 0, image.width);
        let (red, blue) = red_and_blue(&image, (0, image.width), (top, bottom));
        assert_eq!((red, blue), (0, 0), "an untextured grid is grey");
    }
}

/// A `size` × `size` PNG of one-texel columns, red and blue in turn.
fn write_stripes(path: &Path, size: u32) {
    let mut pixels = Vec::with_capacity((size * size * 3) as usize);
    for _ in 0..size {
        for x in 0..size {
            pixels.extend_from_slice(if x.is_multiple_of(2) {
                &[230, 20, 20]
            } else {
                &[20, 20, 230]
            });
        }
    }
    write_rgb_png(path, size, &pixels);
}

#[test]
fn a_fine_texture_seen_from_afar_shows_its_average_colour_not_a_moire() {
    let dir = scratch("stripes");
    // 1024 stripes across a grid about 130 pixels wide: eight texels to a pixel.
    write_stripes(&dir.join("models/maps/stripes.png"), 1024);
    write_grid(&dir.join("models/grid.wrl"), 4, "stripes.png");
    let (out, image) = shot(&dir, &[]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("not drawn"), "{stderr}");
    // The middle of the grid, clear of its edges.
    let (top, bottom) = model_rows(&image, 0, image.width);
    let margin = (bottom - top) / 5;
    let (y0, y1) = (top + margin, bottom - margin);
    let bg = background();
    let covered: Vec<u32> = (0..image.width)
        .filter(|&x| !close(pixel(&image, x, (y0 + y1) / 2), bg, 6))
        .collect();
    let (first, last) = match (covered.first(), covered.last()) {
        (Some(&a), Some(&b)) if b > a + 40 => (a, b),
        _ => panic!("the grid is not visible across the middle row"),
    };
    let (x0, x1) = (first + margin, last - margin);
    let pixels = ((x1 - x0) * (y1 - y0)) as usize;
    // Sampled from the full-size image alone, most pixels land on one stripe or the other.
    let (red, blue) = red_and_blue(&image, (x0, x1), (y0, y1));
    assert!(
        red + blue < pixels / 100,
        "{red} red and {blue} blue pixels of {pixels}: the stripes alias"
    );
    // Averaged, they are purple: as much red as blue, both well above green.
    let (mut r, mut g, mut b) = (0u64, 0u64, 0u64);
    for y in y0..y1 {
        for x in x0..x1 {
            let [pr, pg, pb, _] = pixel(&image, x, y).map(u64::from);
            (r, g, b) = (r + pr, g + pg, b + pb);
        }
    }
    assert!(
        r.abs_diff(b) * 10 < r + b && r > 2 * g && b > 2 * g,
        "mean colour {:?}: not the stripes' purple",
        [r, g, b].map(|c| c / pixels as u64)
    );
}

/// An 8 × 8 PNG, its left half red and its right half blue.
fn write_halves(path: &Path) {
    let mut pixels = Vec::new();
    for _ in 0..8 {
        for column in 0..8 {
            pixels.extend_from_slice(if column < 4 {
                &[230, 20, 20]
            } else {
                &[20, 20, 230]
            });
        }
    }
    write_rgb_png(path, 8, &pixels);
}

#[test]
fn a_texture_repeats_unless_the_file_says_it_clamps() {
    // u from 0 to 2: repeating, the grid's quarters are red, blue, red, blue; clamped along
    // u (`repeatS FALSE`), everything right of u = 1 takes the image's right edge: blue.
    for (fields, third_quarter_red) in [("", true), ("repeatS FALSE", false)] {
        let dir = scratch(if fields.is_empty() { "repeat" } else { "clamp" });
        write_halves(&dir.join("models/maps/halves.png"));
        write_textured_grid(&dir.join("models/grid.wrl"), 8, "halves.png", 2.0, fields);
        let (out, image) = shot(&dir, &[]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!stderr.contains("not drawn"), "{stderr}");
        let (top, bottom) = model_rows(&image, 0, image.width);
        let bg = background();
        let middle = (top + bottom) / 2;
        let covered: Vec<u32> = (0..image.width)
            .filter(|&x| !close(pixel(&image, x, middle), bg, 6))
            .collect();
        let (left, right) = match (covered.first(), covered.last()) {
            (Some(&a), Some(&b)) if b > a + 40 => (a, b),
            _ => panic!("the grid is not visible across the middle row"),
        };
        let quarter = (right - left) / 4;
        let rows = (top + 4, bottom - 4);
        // Inside each quarter, clear of the texel edges where filtering blends the colours.
        let inner = |q: u32| {
            (
                left + q * quarter + quarter / 4,
                left + (q + 1) * quarter - quarter / 4,
            )
        };
        let colours: Vec<(usize, usize)> = (0..4)
            .map(|q| red_and_blue(&image, inner(q), rows))
            .collect();
        let is_red = |(red, blue): (usize, usize)| red > 100 && blue < red / 20;
        let is_blue = |(red, blue): (usize, usize)| blue > 100 && red < blue / 20;
        assert!(
            is_red(colours[0]) && is_blue(colours[1]),
            "{fields:?}: {colours:?}"
        );
        assert!(is_blue(colours[3]), "{fields:?}: {colours:?}");
        if third_quarter_red {
            assert!(is_red(colours[2]), "repeating: {colours:?}");
        } else {
            assert!(is_blue(colours[2]), "clamped: {colours:?}");
        }
    }
}
