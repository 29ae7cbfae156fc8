//! Shared by the screenshot tests (`tests/viewer/`): scenes built in code (so the tests do
//! not wait for the file readers), golden-image comparison with a tolerance, and the checks
//! a user would notice (model coverage, background at the corners).
//!
//! Goldens live in `tests/golden/`; `UPDATE_GOLDEN=1 cargo test --test viewer` rewrites
//! them. On a mismatch the actual picture and a diff image go to `target/shot-diffs/`.

use std::path::{Path, PathBuf};

use decimate_core::decimate::{Params, Report};
use decimate_core::mesh::{Model, Scene};
use decimate_viewer::app::shot;
use decimate_viewer::app::shot::ShotOptions;
use decimate_viewer::render::context::DevicePreference;
use decimate_viewer::render::draw::{DrawOptions, BACKGROUND};
use decimate_viewer::render::offscreen::RgbaImage;
use glam::{Mat4, Vec3};

/// Golden picture size: small, so the PNGs stay a few kilobytes.
pub const WIDTH: u32 = 320;
pub const HEIGHT: u32 = 240;

/// A channel may differ by this much before the pixel counts as different.
pub const CHANNEL_TOLERANCE: u8 = 24;
/// At most this fraction of the pixels may differ.
pub const MAX_DIFFERENT_FRACTION: f64 = 0.005;

/// A 2×2×2 cube with `n` segments per edge (test004 is `n = 10`: 602 vertices, 1200
/// triangles), counter-clockwise seen from outside, vertices shared along the edges.
pub fn cube(n: u32) -> Scene {
    let mut model = Model {
        name: format!("cube {n}"),
        ..Model::default()
    };
    // Each face: a normal axis and two in-plane axes with u × v = normal.
    let faces = [
        (Vec3::X, Vec3::Y, Vec3::Z),
        (-Vec3::X, Vec3::Z, Vec3::Y),
        (Vec3::Y, Vec3::Z, Vec3::X),
        (-Vec3::Y, Vec3::X, Vec3::Z),
        (Vec3::Z, Vec3::X, Vec3::Y),
        (-Vec3::Z, Vec3::Y, Vec3::X),
    ];
    let mut index = std::collections::HashMap::new();
    let key = |p: Vec3| (p * n as f32).round().as_ivec3().to_array();
    for (normal, u, v) in faces {
        let mut ids = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let s = i as f32 / n as f32 * 2.0 - 1.0;
                let t = j as f32 / n as f32 * 2.0 - 1.0;
                let p = normal + u * s + v * t;
                let id = *index.entry(key(p)).or_insert_with(|| {
                    model.positions.push(p);
                    model.positions.len() as u32 - 1
                });
                ids.push(id);
            }
        }
        let at = |i: u32, j: u32| ids[(j * (n + 1) + i) as usize];
        for j in 0..n {
            for i in 0..n {
                model
                    .triangles
                    .push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                model
                    .triangles
                    .push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    model.diffuse = [0.75, 0.55, 0.35];
    Scene {
        models: vec![model],
    }
}

/// A UV sphere of radius 1 with `rings` × `segments` quads (2 triangles each), moved by a
/// transform so that world transforms are exercised.
pub fn sphere(rings: u32, segments: u32, transform: Mat4) -> Scene {
    let model = Model {
        transform,
        diffuse: [0.45, 0.65, 0.85],
        ..decimate_core::mesh::shapes::uv_sphere(rings, segments)
    };
    Scene {
        models: vec![model],
    }
}

/// The draw toggles of a `--mode` list, parsed as the command line parses it.
pub fn modes(list: &str) -> DrawOptions {
    decimate::cli::draw_modes(list).unwrap_or_else(|e| panic!("{e}"))
}

/// Renders in-process on lavapipe, without captions; a missing Vulkan is a test failure with
/// the reason.
pub fn render(
    scene: &Scene,
    viewports: u32,
    modes: DrawOptions,
    params: Option<&Params>,
) -> RgbaImage {
    let options = ShotOptions {
        width: WIDTH,
        height: HEIGHT,
        viewports,
        modes,
        labels: Some(false),
        // Goldens are single-sampled unless a test is about anti-aliasing.
        msaa: 1,
        ..ShotOptions::default()
    };
    render_with(scene, &options, params).0
}

/// Renders `options` in-process on lavapipe; the picture and the decimations' reports.
pub fn render_with(
    scene: &Scene,
    options: &ShotOptions,
    params: Option<&Params>,
) -> (RgbaImage, Vec<Report>) {
    match shot::render(scene, options, params, DevicePreference::Cpu) {
        Ok(r) => r,
        Err(e) => panic!(
            "Vulkan rendering is unavailable, so the shot tests cannot run: {e}\n\
             install lavapipe: apt-get install mesa-vulkan-drivers libvulkan1"
        ),
    }
}

pub fn pixel(image: &RgbaImage, x: u32, y: u32) -> [u8; 4] {
    let i = ((y * image.width + x) * 4) as usize;
    [
        image.pixels[i],
        image.pixels[i + 1],
        image.pixels[i + 2],
        image.pixels[i + 3],
    ]
}

/// The background colour as the renderer writes it.
pub fn background() -> [u8; 4] {
    BACKGROUND.map(|c| (c * 255.0).round() as u8)
}

pub fn close(a: [u8; 4], b: [u8; 4], tolerance: u8) -> bool {
    a.iter().zip(&b).all(|(x, y)| x.abs_diff(*y) <= tolerance)
}

/// Fraction of the pixels inside `(x0, y0)..(x1, y1)` that are not background.
pub fn coverage(image: &RgbaImage, x0: u32, y0: u32, x1: u32, y1: u32) -> f64 {
    let bg = background();
    let mut covered = 0usize;
    for y in y0..y1 {
        for x in x0..x1 {
            if !close(pixel(image, x, y), bg, 6) {
                covered += 1;
            }
        }
    }
    covered as f64 / f64::from((x1 - x0) * (y1 - y0))
}

/// Asserts the four corners show the background.
pub fn assert_background_corners(image: &RgbaImage) {
    let (w, h) = (image.width - 1, image.height - 1);
    for (x, y) in [(0, 0), (w, 0), (0, h), (w, h)] {
        let p = pixel(image, x, y);
        assert!(
            close(p, background(), 2),
            "corner ({x}, {y}) is {p:?}, not the background {:?}",
            background()
        );
    }
}

/// Fraction of pixels where some channel differs by more than `tolerance`.
pub fn different_fraction(a: &RgbaImage, b: &RgbaImage, tolerance: u8) -> f64 {
    assert_eq!(
        (a.width, a.height),
        (b.width, b.height),
        "picture sizes differ"
    );
    let differing = a
        .pixels
        .chunks_exact(4)
        .zip(b.pixels.chunks_exact(4))
        .filter(|(p, q)| {
            p.iter()
                .zip(q.iter())
                .any(|(x, y)| x.abs_diff(*y) > tolerance)
        })
        .count();
    differing as f64 / f64::from(a.width * a.height)
}

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(format!("{name}.png"))
}

fn diff_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("target/shot-diffs")
}

pub fn read_png(path: &Path) -> RgbaImage {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let mut reader = decoder
        .read_info()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut pixels = vec![0; reader.output_buffer_size().unwrap_or(0)];
    let info = reader
        .next_frame(&mut pixels)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(
        info.color_type,
        png::ColorType::Rgba,
        "{}: expected RGBA",
        path.display()
    );
    pixels.truncate(info.buffer_size());
    RgbaImage {
        width: info.width,
        height: info.height,
        pixels,
    }
}

/// Compares `actual` with the golden `name`; `UPDATE_GOLDEN=1` rewrites the golden instead.
pub fn assert_matches_golden(name: &str, actual: &RgbaImage) {
    let path = golden_path(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some_and(|v| v == "1") {
        // Under CI a golden rewritten is a comparison skipped: refuse.
        assert!(
            std::env::var_os("CI").is_none(),
            "UPDATE_GOLDEN=1 with CI set: goldens are compared in CI, never rewritten"
        );
        shot::write_png(actual, &path).unwrap_or_else(|e| panic!("{e}"));
        eprintln!("updated {}", path.display());
        return;
    }
    if !path.exists() {
        panic!(
            "{} is missing: run with UPDATE_GOLDEN=1 to create it",
            path.display()
        );
    }
    let golden = read_png(&path);
    let fraction = different_fraction(actual, &golden, CHANNEL_TOLERANCE);
    if fraction > MAX_DIFFERENT_FRACTION {
        let dir = diff_dir();
        let _ = std::fs::create_dir_all(&dir);
        let actual_path = dir.join(format!("{name}.actual.png"));
        let diff_path = dir.join(format!("{name}.diff.png"));
        let _ = shot::write_png(actual, &actual_path);
        let _ = shot::write_png(&diff_image(actual, &golden), &diff_path);
        panic!(
            "{name}: {:.2} % of the pixels differ from {} (allowed {:.2} %); see {} and {}. \
             If the change is intended, run with UPDATE_GOLDEN=1.",
            fraction * 100.0,
            path.display(),
            MAX_DIFFERENT_FRACTION * 100.0,
            actual_path.display(),
            diff_path.display()
        );
    }
}

/// Differing pixels in red over a dimmed copy of the golden.
fn diff_image(actual: &RgbaImage, golden: &RgbaImage) -> RgbaImage {
    let mut pixels = Vec::with_capacity(actual.pixels.len());
    for (p, q) in actual
        .pixels
        .chunks_exact(4)
        .zip(golden.pixels.chunks_exact(4))
    {
        if p.iter()
            .zip(q)
            .any(|(x, y)| x.abs_diff(*y) > CHANNEL_TOLERANCE)
        {
            pixels.extend_from_slice(&[255, 0, 0, 255]);
        } else {
            pixels.extend_from_slice(&[q[0] / 3, q[1] / 3, q[2] / 3, 255]);
        }
    }
    RgbaImage {
        width: actual.width,
        height: actual.height,
        pixels,
    }
}

/// Writes a `size` × `size` RGB PNG.
pub fn write_rgb_png(path: &Path, size: u32, rgb: &[u8]) {
    let file = std::fs::File::create(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut encoder = png::Encoder::new(file, size, size);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder
        .write_header()
        .unwrap_or_else(|e| panic!("png: {e}"));
    writer
        .write_image_data(rgb)
        .unwrap_or_else(|e| panic!("png: {e}"));
}
