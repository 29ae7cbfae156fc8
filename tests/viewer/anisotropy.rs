//! Anisotropic texture filtering, on lavapipe: a floor of rails seen at a grazing angle keeps
//! its rails into the distance, where trilinear filtering alone (the same render with the
//! device's anisotropy turned off) blurs them into their average colour. What a user sees
//! on a textured scan viewed side-on: detail that holds instead of a smear.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use decimate_core::io::texture_image;
use decimate_core::mesh::{Model, Scene};
use decimate_viewer::render::camera::{Bounds, Camera};
use decimate_viewer::render::commands::Commands;
use decimate_viewer::render::context::{Context, DevicePreference};
use decimate_viewer::render::draw::ViewportDraw;
use decimate_viewer::render::gpu_mesh::GpuScene;
use decimate_viewer::render::offscreen::{OffscreenTarget, RgbaImage, OFFSCREEN_FORMAT};
use decimate_viewer::render::pipeline::Pipelines;
use decimate_viewer::render::texture::Textures;
use decimate_viewer::render::tiles::Rect;
use glam::{Mat4, Quat, Vec3};

use crate::support::shot::{background, close, modes, pixel, write_rgb_png, HEIGHT, WIDTH};

/// Texels across the image, and texels per rail (red, then blue).
const TEXELS: u32 = 256;
const RAIL: u32 = 4;

/// The angle between the line of sight and the floor, in degrees: the footprint of a pixel
/// on the floor is about `1 / sin` times longer along the rails than across them.
const GRAZING_DEG: f32 = 12.0;

/// A fresh scratch folder under target/, so parallel tests never share files.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("shot_anisotropy-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    dir
}

/// A square PNG of vertical rails, `RAIL` texels of red then of blue.
fn write_rails(path: &Path) {
    let mut pixels = Vec::with_capacity((TEXELS * TEXELS * 3) as usize);
    for _ in 0..TEXELS {
        for x in 0..TEXELS {
            pixels.extend_from_slice(if (x / RAIL).is_multiple_of(2) {
                &[230, 20, 20]
            } else {
                &[20, 20, 230]
            });
        }
    }
    write_rgb_png(path, TEXELS, &pixels);
}

/// A 4 × 4 floor textured with `rails.png` (u across, v along the rails), turned so that
/// the default camera sees it at `GRAZING_DEG`, the rails running away from the eye.
fn floor() -> Scene {
    let n = 8;
    let mut model = Model {
        name: "floor".into(),
        texture: Some("rails.png".into()),
        texture_repeat: [true, true],
        diffuse: [1.0, 1.0, 1.0],
        ..Model::default()
    };
    let mut uvs = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            model
                .positions
                .push(Vec3::new(4.0 * u - 2.0, 4.0 * v - 2.0, 0.0));
            uvs.push([u, v]);
        }
    }
    model.texcoords = Some(uvs);
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            model.triangles.push([a, b, c]);
            model.triangles.push([a, c, d]);
        }
    }
    // The camera turns the scene by its default orientation; undo that, then lay the
    // floor down so that +y (along the rails) points away and the floor faces the eye
    // from `GRAZING_DEG` above.
    let camera_turn = Camera::framing(Bounds {
        min: Vec3::splat(-1.0),
        max: Vec3::splat(1.0),
    })
    .view();
    let turn = Quat::from_mat4(&camera_turn).inverse();
    let lay = Quat::from_rotation_x(-(90.0 - GRAZING_DEG).to_radians());
    model.transform = Mat4::from_quat(turn * lay);
    Scene {
        models: vec![model],
    }
}

/// Renders `scene` in-process on lavapipe, with the device's anisotropic filtering or
/// (`anisotropic` false) trilinear filtering only, textures read from `dir`.
fn render(scene: &Scene, dir: &Path, anisotropic: bool) -> RgbaImage {
    let fail = |e: &dyn std::fmt::Display| -> ! {
        panic!(
            "Vulkan rendering is unavailable, so the shot tests cannot run: {e}\n\
             install lavapipe: apt-get install mesa-vulkan-drivers libvulkan1"
        )
    };
    let mut context = Context::new(&[], false, DevicePreference::Cpu).unwrap_or_else(|e| fail(&e));
    let max = context.capabilities.max_anisotropy;
    assert!(
        max.is_some_and(|m| m >= 8.0),
        "lavapipe offers anisotropy up to 16; the device says {max:?}"
    );
    if !anisotropic {
        // Nothing else holds the context yet: the samplers are made without anisotropy.
        let only = Arc::get_mut(&mut context).unwrap_or_else(|| panic!("a shared context"));
        only.capabilities.max_anisotropy = None;
    }
    let commands = Commands::new(&context).unwrap_or_else(|e| fail(&e));
    let pipelines = Pipelines::new(&context, OFFSCREEN_FORMAT).unwrap_or_else(|e| fail(&e));
    let target = OffscreenTarget::new(&context, WIDTH, HEIGHT).unwrap_or_else(|e| fail(&e));
    let draw = modes("triangles,unlit");
    let mut textures = Textures::new(
        &context,
        pipelines.texture_layout,
        texture_image::reader(dir),
    )
    .unwrap_or_else(|e| fail(&e));
    let gpu = GpuScene::upload(&context, &commands, &mut textures, scene, draw.layers())
        .unwrap_or_else(|e| fail(&e));
    let camera = Camera::framing(gpu.bounds);
    let view = ViewportDraw {
        rect: Rect {
            x: 0,
            y: 0,
            width: WIDTH,
            height: HEIGHT,
        },
        scene: &gpu,
        camera: &camera,
        options: draw,
        morph: 1.0,
    };
    target
        .render(&commands, &pipelines, &[view], true)
        .unwrap_or_else(|e| fail(&e))
        .unwrap_or_else(|| panic!("no picture was read back"))
}

/// The rows the floor covers, each with its covered columns, from the top (far) down.
fn floor_rows(image: &RgbaImage) -> Vec<(u32, Vec<u32>)> {
    let bg = background();
    (0..image.height)
        .map(|y| {
            let xs = (0..image.width)
                .filter(|&x| !close(pixel(image, x, y), bg, 6))
                .collect::<Vec<_>>();
            (y, xs)
        })
        .filter(|(_, xs)| xs.len() > 20)
        .collect()
}

/// How far the rails stand apart in row `y` over columns `xs` (the middle half, clear of
/// the floor's sides): the mean of |red − blue| per pixel, 0 for a uniform purple, 210 for
/// rails a pixel wide or more.
fn rail_contrast(image: &RgbaImage, y: u32, xs: &[u32]) -> f64 {
    let (a, b) = (xs.len() / 4, 3 * xs.len() / 4);
    let middle = &xs[a..b];
    let sum: f64 = middle
        .iter()
        .map(|&x| {
            let [r, _, bl, _] = pixel(image, x, y);
            (f64::from(r) - f64::from(bl)).abs()
        })
        .sum();
    sum / middle.len().max(1) as f64
}

/// The red rails row `y` crosses over columns `xs`: runs of pixels clearly redder than blue.
fn red_rails(image: &RgbaImage, y: u32, xs: &[u32]) -> usize {
    let red = |x: u32| {
        let [r, _, b, _] = pixel(image, x, y);
        i32::from(r) > i32::from(b) + 40
    };
    xs.windows(2).filter(|w| !red(w[0]) && red(w[1])).count()
        + usize::from(xs.first().is_some_and(|&x| red(x)))
}

#[test]
fn rails_on_a_floor_seen_side_on_stay_sharp_into_the_distance() {
    let dir = scratch("rails");
    write_rails(&dir.join("rails.png"));
    let scene = floor();
    let sharp = render(&scene, &dir, true);
    let blurred = render(&scene, &dir, false);
    if std::env::var_os("SAVE_SHOTS").is_some() {
        for (name, image) in [("aniso", &sharp), ("trilinear", &blurred)] {
            let path = dir.join(format!("{name}.png"));
            decimate_viewer::app::shot::write_png(image, &path)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            eprintln!("wrote {}", path.display());
        }
    }
    let rows = floor_rows(&sharp);
    assert!(rows.len() >= 16, "the floor covers {} rows", rows.len());
    assert_eq!(
        rows.iter().map(|r| r.0).collect::<Vec<_>>(),
        floor_rows(&blurred).iter().map(|r| r.0).collect::<Vec<_>>(),
        "both renders cover the same rows"
    );
    let (mut r, mut g, mut b, mut count) = (0u64, 0u64, 0u64, 0u64);
    for (y, xs) in &rows {
        let (s, t) = (
            rail_contrast(&sharp, *y, xs),
            rail_contrast(&blurred, *y, xs),
        );
        let rails = red_rails(&sharp, *y, xs);
        // Anisotropic: every rail of the floor, near and far, stands apart.
        assert!(
            rails == (TEXELS / RAIL / 2) as usize && s > 60.0,
            "row {y} ({} px): {rails} red rails, contrast {s:.0} (trilinear {t:.0})",
            xs.len()
        );
        // Trilinear: averaged away (which is what the scene is built to show).
        assert!(
            t < 25.0,
            "row {y}: trilinear contrast {t:.0}: the floor is not side-on"
        );
        for &x in xs {
            let [pr, pg, pb, _] = pixel(&blurred, x, *y).map(u64::from);
            (r, g, b, count) = (r + pr, g + pg, b + pb, count + 1);
        }
    }
    // Averaged, not lost: the rails' purple, as much red as blue, both well above green.
    assert!(
        r.abs_diff(b) * 10 < r + b && r > 2 * g && b > 2 * g,
        "trilinear mean colour {:?}: not the rails' purple",
        [r, g, b].map(|c| c / count.max(1))
    );
}
