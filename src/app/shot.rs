//! The `shot` action: render the scene offscreen — no window, no display — with exactly the
//! viewer's renderer, viewports tiled as in the viewer (the first shows the original scene,
//! the others the decimated one), and write a PNG through a temporary file and a rename.

use std::path::Path;

use crate::cli::{ShotModes, ShotOptions};
use crate::decimate::{simplify_scene, Params, Report};
use crate::io::texture_image;
use crate::mesh::Scene;
use crate::render::camera::Camera;
use crate::render::commands::Commands;
use crate::render::context::{Context, DevicePreference};
use crate::render::draw::{DrawOptions, ViewportDraw};
use crate::render::gpu_mesh::GpuScene;
use crate::render::offscreen::{OffscreenTarget, RgbaImage, OFFSCREEN_FORMAT};
use crate::render::pipeline::Pipelines;
use crate::render::texture::Textures;
use crate::render::tiles::tiles;
use crate::render::RenderError;

/// What can go wrong taking a shot.
#[derive(Debug, thiserror::Error)]
pub enum ShotError {
    #[error(transparent)]
    Render(#[from] RenderError),
    #[error("{file}: {source}")]
    Write {
        file: std::path::PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{file}: PNG encoding failed: {source}")]
    Encode {
        file: std::path::PathBuf,
        #[source]
        source: png::EncodingError,
    },
}

/// The draw toggles a `--mode` list asks for.
pub fn draw_options(modes: &ShotModes) -> DrawOptions {
    DrawOptions {
        triangles: modes.triangles,
        edges: modes.edges,
        points: modes.points,
        face_normals: modes.face_normals,
        vertex_normals: modes.vertex_normals,
        lighting: !modes.unlit,
        smooth: !modes.flat,
        textures: !modes.untextured,
    }
}

/// A picture of `scene` and, when `params` is given, of its decimated copy.
///
/// Viewport 1 shows the original and viewports 2–4 the decimated scene; with a single
/// viewport and a target, that viewport shows the decimated scene (otherwise the target would
/// be ignored). Every viewport uses the same camera, framed on the original.
pub fn render(
    scene: &Scene,
    options: &ShotOptions,
    params: Option<&Params>,
    device: DevicePreference,
) -> Result<(RgbaImage, Option<Report>), RenderError> {
    let context = Context::new(&[], false, device)?;
    let commands = Commands::new(&context)?;
    let pipelines = Pipelines::new(&context, OFFSCREEN_FORMAT)?;
    let target = OffscreenTarget::new(&context, options.width, options.height)?;

    let draw = draw_options(&options.modes);
    let mut textures = Textures::new(
        &context,
        pipelines.texture_layout,
        texture_image::reader(&options.texture_dir),
    )?;
    let original = GpuScene::upload(&context, &commands, &mut textures, scene, draw.layers())?;
    let (decimated, report) = match params {
        Some(params) => {
            let mut copy = scene.clone();
            let report = simplify_scene(&mut copy, params, &mut |_| {});
            (
                Some(GpuScene::upload(
                    &context,
                    &commands,
                    &mut textures,
                    &copy,
                    draw.layers(),
                )?),
                Some(report),
            )
        }
        None => (None, None),
    };
    let camera = Camera::framing(original.bounds);
    let rects = tiles(options.viewports as usize, options.width, options.height);
    let views: Vec<_> = rects
        .iter()
        .enumerate()
        .map(|(i, &rect)| {
            let shows_decimated = i > 0 || rects.len() == 1;
            let scene = match (&decimated, shows_decimated) {
                (Some(d), true) => d,
                _ => &original,
            };
            ViewportDraw {
                rect,
                scene,
                camera: &camera,
                options: draw,
                morph: 1.0,
            }
        })
        .collect();
    let image = target.render(&commands, &pipelines, &views, true)?;
    let image = image.ok_or_else(|| RenderError::TooLarge("no picture was read back".into()))?;
    Ok((image, report))
}

/// Writes `image` as an RGBA PNG through [`crate::io::replace::replace_file`]: a temporary
/// file renamed over `path`, so a crash never leaves half a file under the real name.
pub fn write_png(image: &RgbaImage, path: &Path) -> Result<(), ShotError> {
    // The encoder's own error is kept aside: `replace_file` passes on I/O errors only.
    let mut encoding = None;
    let written = crate::io::replace::replace_file(path, |out| {
        let mut encoder = png::Encoder::new(out, image.width, image.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let result = encoder.write_header().and_then(|mut writer| {
            writer.write_image_data(&image.pixels)?;
            writer.finish()
        });
        result.map_err(|e| {
            let message = e.to_string();
            encoding = Some(e);
            std::io::Error::other(message)
        })
    });
    match (written, encoding) {
        (Ok(()), _) => Ok(()),
        (Err(_), Some(source)) => Err(ShotError::Encode {
            file: path.to_path_buf(),
            source,
        }),
        (Err(source), None) => Err(ShotError::Write {
            file: path.to_path_buf(),
            source,
        }),
    }
}
