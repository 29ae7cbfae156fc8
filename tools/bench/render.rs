//! Frame-time benchmark of the renderer: draws a large mesh offscreen — a generated UV sphere
//! (about one million triangles by default) or any file `decimate` reads, such as the
//! Stanford dragon — once per draw mode, and prints a table of frame times without and with
//! 4× multisample anti-aliasing (the two alternate frame by frame). No readback is timed: a
//! frame is record + submit + wait, as in the viewer. Then it turns the camera as a drag does
//! and prints the viewer's moving (1×) and at-rest (4×) frames. Then it moves the
//! level-of-detail slider as the viewer does and prints what each move costs: the new level,
//! its upload (filled triangles), one frame, and for a coarsening move the second upload
//! when the geomorph ends.
//!
//! ```text
//! cargo run --release --example bench-render -- [TRIANGLES | FILE] [WxH] [FRAMES]
//! VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json cargo run --release --example bench-render
//! ```

use std::process::ExitCode;
use std::time::Instant;

use decimate_core::decimate::Params;
use decimate_core::io::texture_image;
use decimate_core::mesh::Scene;
use decimate_viewer::app::lod::LodView;
use decimate_viewer::render::camera::Camera;
use decimate_viewer::render::commands::Commands;
use decimate_viewer::render::context::{Context, DevicePreference};
use decimate_viewer::render::draw::{DrawOptions, ViewportDraw};
use decimate_viewer::render::gpu_mesh::GpuScene;
use decimate_viewer::render::mesh_data::Layers;
use decimate_viewer::render::offscreen::{OffscreenTarget, OFFSCREEN_FORMAT};
use decimate_viewer::render::pipeline::{Pipelines, DEFAULT_MSAA};
use decimate_viewer::render::texture::Textures;
use decimate_viewer::render::tiles::tiles;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    // A number is a sphere's triangle count; anything else names a file.
    let source = match args.first() {
        Some(a) => a
            .parse()
            .map_or_else(|_| Source::File(a.clone()), Source::Sphere),
        None => Source::Sphere(1_000_000),
    };
    let (width, height) = args
        .get(1)
        .and_then(|s| s.split_once('x'))
        .and_then(|(w, h)| Some((w.parse().ok()?, h.parse().ok()?)))
        .unwrap_or((1024, 768));
    let frames: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(5);
    match run(source, width, height, frames) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("bench-render: {e}");
            ExitCode::FAILURE
        }
    }
}

/// What to draw.
enum Source {
    Sphere(usize),
    File(String),
}

fn run(
    source: Source,
    width: u32,
    height: u32,
    frames: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    let folder = match &source {
        Source::File(path) => {
            decimate_core::io::texture_path::folder_of(std::path::Path::new(path)).to_path_buf()
        }
        Source::Sphere(_) => std::path::PathBuf::from("."),
    };
    let scene = match source {
        Source::Sphere(triangles) => {
            // rings × segments × 2 ≈ triangles, with twice as many segments as rings.
            let rings = ((triangles as f64 / 4.0).sqrt().max(3.0)) as u32;
            sphere(rings, rings * 2)
        }
        Source::File(path) => {
            let outcome = decimate_core::io::read_scene(std::path::Path::new(&path))?;
            decimate_core::mesh::build::build_scene(outcome.scene, true)
        }
    };
    let context = Context::new(&[], false, DevicePreference::Fastest)?;
    let commands = Commands::new(&context)?;
    let pipelines = Pipelines::new(&context, OFFSCREEN_FORMAT)?;
    let target = OffscreenTarget::new(&context, width, height)?;
    let msaa_pipelines = Pipelines::with_samples(&context, OFFSCREEN_FORMAT, DEFAULT_MSAA)?;
    let msaa_target =
        OffscreenTarget::with_samples(&context, width, height, msaa_pipelines.samples)?;
    let msaa = msaa_pipelines.samples.as_raw();
    let mut textures = Textures::new(
        &context,
        pipelines.texture_layout,
        texture_image::reader(&folder),
    )?;
    // What a viewport drawing filled triangles uploads, then everything (the table's modes).
    let started = Instant::now();
    drop(GpuScene::upload(
        &context,
        &commands,
        &mut textures,
        &scene,
        DrawOptions::default().layers(),
    )?);
    let upload_filled = started.elapsed().as_secs_f64() * 1e3;
    let started = Instant::now();
    let gpu = GpuScene::upload(&context, &commands, &mut textures, &scene, Layers::ALL)?;
    let upload = started.elapsed().as_secs_f64() * 1e3;
    let camera = Camera::framing(gpu.bounds);
    println!(
        "device: {}\nmesh: {} vertices, {} triangles (upload {upload_filled:.0} ms filled only, {upload:.0} ms with every list)\nimage: {width}x{height}, {frames} frames per mode after one warm-up\n",
        context.device_name, gpu.vertex_count, gpu.triangle_count
    );
    println!(
        "{:<26} {:>10} {:>10} {:>10} {:>12} {:>10} {:>10}",
        "mode",
        "median ms",
        "min ms",
        "max ms",
        format!("{msaa}x med ms"),
        format!("{msaa}x fps"),
        format!("{msaa}x / 1x")
    );
    let base = DrawOptions::default();
    let modes = [
        ("triangles (smooth)", base),
        (
            "triangles (flat)",
            DrawOptions {
                smooth: false,
                ..base
            },
        ),
        (
            "triangles (unlit)",
            DrawOptions {
                lighting: false,
                ..base
            },
        ),
        (
            "edges",
            DrawOptions {
                triangles: false,
                edges: true,
                ..base
            },
        ),
        (
            "triangles + edges",
            DrawOptions {
                edges: true,
                ..base
            },
        ),
        (
            "points",
            DrawOptions {
                triangles: false,
                points: true,
                ..base
            },
        ),
        (
            "triangles + face normals",
            DrawOptions {
                face_normals: true,
                ..base
            },
        ),
        ("triangles, 4 viewports", base),
    ];
    for (name, options) in modes {
        let count = if name.contains("4 viewports") { 4 } else { 1 };
        let views: Vec<_> = tiles(count, width, height)
            .into_iter()
            .map(|rect| ViewportDraw {
                rect,
                scene: &gpu,
                camera: &camera,
                options,
                morph: 1.0,
            })
            .collect();
        target.render(&commands, &pipelines, &views, false)?;
        msaa_target.render(&commands, &msaa_pipelines, &views, false)?;
        let mut times = Vec::with_capacity(frames);
        let mut msaa_times = Vec::with_capacity(frames);
        for _ in 0..frames.max(1) {
            let t = Instant::now();
            target.render(&commands, &pipelines, &views, false)?;
            times.push(t.elapsed().as_secs_f64() * 1e3);
            let t = Instant::now();
            msaa_target.render(&commands, &msaa_pipelines, &views, false)?;
            msaa_times.push(t.elapsed().as_secs_f64() * 1e3);
        }
        times.sort_by(f64::total_cmp);
        msaa_times.sort_by(f64::total_cmp);
        let (median, msaa_median) = (times[times.len() / 2], msaa_times[msaa_times.len() / 2]);
        println!(
            "{name:<26} {median:>10.1} {:>10.1} {:>10.1} {msaa_median:>12.1} {:>10.1} {:>10.2}",
            times[0],
            times[times.len() - 1],
            1e3 / msaa_median,
            msaa_median / median
        );
    }
    let single = (&pipelines, &target);
    let multi = (&msaa_pipelines, &msaa_target);
    turning(&commands, single, multi, &gpu, &camera, frames)?;
    let gpu = (&context, &commands, &pipelines, &target);
    slider_moves(gpu, &mut textures, &scene, &camera)
}

/// Frames drawn while the camera turns, for each frame at rest (the viewer's settle time
/// is longer than this many moving frames at the frame rates measured).
const MOVES_PER_REST: usize = 10;

/// What the viewer draws while the user turns the model: single-sampled frames with the
/// camera moving each frame, then the one multisampled frame once the view rests
/// (docs/design.md#msaa); beside them, multisampled frames while moving, as the viewer drew
/// before. The three alternate round by round, so that the machine's load touches each alike.
fn turning(
    commands: &Commands,
    single: (&Pipelines, &OffscreenTarget),
    multi: (&Pipelines, &OffscreenTarget),
    gpu: &GpuScene,
    camera: &Camera,
    rounds: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    let (width, height) = (single.1.extent.width, single.1.extent.height);
    let msaa = multi.0.samples.as_raw();
    let mut camera = camera.clone();
    let frame = |(pipelines, target): (&Pipelines, &OffscreenTarget),
                 camera: &Camera|
     -> Result<f64, Box<dyn std::error::Error>> {
        let views: Vec<_> = tiles(1, width, height)
            .into_iter()
            .map(|rect| ViewportDraw {
                rect,
                scene: gpu,
                camera,
                options: DrawOptions::default(),
                morph: 1.0,
            })
            .collect();
        let t = Instant::now();
        target.render(commands, pipelines, &views, false)?;
        Ok(t.elapsed().as_secs_f64() * 1e3)
    };
    let (mut moving, mut moving_msaa, mut rest) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..rounds.max(1) {
        for _ in 0..MOVES_PER_REST {
            camera.drag(glam::Vec2::new(8.0, 0.0));
            moving.push(frame(single, &camera)?);
        }
        rest.push(frame(multi, &camera)?);
        for _ in 0..MOVES_PER_REST {
            camera.drag(glam::Vec2::new(8.0, 0.0));
            moving_msaa.push(frame(multi, &camera)?);
        }
    }
    println!(
        "\nviewer, turning the model (8 px of drag per frame; {MOVES_PER_REST} moving frames per rest, {} rounds, alternating)",
        rounds.max(1)
    );
    println!(
        "{:<36} {:>10} {:>10} {:>10} {:>8}",
        "frames", "median ms", "max ms", "fps", "count"
    );
    for (name, mut times) in [
        ("moving, 1x (what the viewer draws)".to_string(), moving),
        (format!("at rest, {msaa}x (one frame)"), rest),
        (format!("moving, {msaa}x (without settling)"), moving_msaa),
    ] {
        times.sort_by(f64::total_cmp);
        let median = times[times.len() / 2];
        println!(
            "{name:<36} {median:>10.1} {:>10.1} {:>10.1} {:>8}",
            times[times.len() - 1],
            1e3 / median,
            times.len()
        );
    }
    Ok(())
}

/// The slider's moves, timed: down to three quarters, half, a quarter and the base of the
/// progressive mesh, then back up to half and the original.
fn slider_moves(
    (context, commands, pipelines, target): (
        &std::sync::Arc<Context>,
        &Commands,
        &Pipelines,
        &OffscreenTarget,
    ),
    textures: &mut Textures,
    scene: &Scene,
    camera: &Camera,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut lod = LodView::new(scene, &Params::default());
    let (lo, hi) = lod.range();
    println!(
        "\nlevel-of-detail slider: {lo} to {hi} vertices, progressive mesh built in {:.2} s",
        lod.build_seconds
    );
    println!(
        "{:<22} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "move to", "level ms", "upload ms", "frame ms", "settle ms", "total ms"
    );
    let layers = DrawOptions::default().layers();
    let (width, height) = (target.extent.width, target.extent.height);
    for fraction in [0.75, 0.5, 0.25, 0.0, 0.5, 1.0] {
        let vertices = lo + ((hi - lo) as f64 * fraction) as usize;
        let started = Instant::now();
        lod.set_vertices(vertices, started);
        let level = started.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let gpu = GpuScene::upload_morphing(
            context,
            commands,
            textures,
            lod.scene(),
            lod.morph_from(),
            layers,
        )?;
        let upload = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let views: Vec<_> = tiles(1, width, height)
            .into_iter()
            .map(|rect| ViewportDraw {
                rect,
                scene: &gpu,
                camera,
                options: DrawOptions::default(),
                morph: 0.5,
            })
            .collect();
        target.render(commands, pipelines, &views, false)?;
        let frame = t.elapsed().as_secs_f64() * 1e3;
        drop(views);
        drop(gpu);
        let t = Instant::now();
        if lod.settle() {
            drop(GpuScene::upload(
                context,
                commands,
                textures,
                lod.scene(),
                layers,
            )?);
        }
        let settle = t.elapsed().as_secs_f64() * 1e3;
        let total = started.elapsed().as_secs_f64() * 1e3;
        println!(
            "{:<22} {level:>9.1} {upload:>9.1} {frame:>9.1} {settle:>9.1} {total:>9.1}",
            format!("{:.0} % ({})", fraction * 100.0, lod.vertex_count())
        );
    }
    Ok(())
}

/// A unit UV sphere with `rings` × `segments` quads.
fn sphere(rings: u32, segments: u32) -> Scene {
    Scene {
        models: vec![decimate_core::mesh::shapes::uv_sphere(rings, segments)],
    }
}
