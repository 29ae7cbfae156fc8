//! Texture images read from files: a texture name resolved beside the model's file (or as a
//! `file:` URL), and PNG (any colour type and depth) or JPEG bytes decoded to 8-bit RGBA.
//! Other URLs are not fetched (a `data:` URI is decoded: it holds the image); other formats
//! are refused with the reason.

use std::path::{Path, PathBuf};

use crate::io::texture_path::has_url_scheme;
use crate::mesh::rgba_image::RgbaImage;

/// The file a texture name points at, or why it is not read.
pub fn resolve(name: &str, folder: &Path) -> Result<PathBuf, String> {
    if let Some(rest) = name.strip_prefix("file://") {
        // `file:///abs/path` or `file://localhost/abs/path`.
        let path = rest.strip_prefix("localhost").unwrap_or(rest);
        return Ok(PathBuf::from(path));
    }
    if let Some(rest) = name.strip_prefix("file:") {
        return Ok(folder.join(rest));
    }
    if has_url_scheme(name) {
        return Err("URLs are not fetched".into());
    }
    Ok(folder.join(name.replace('\\', "/")))
}

/// What reads the images of a scene whose file lies in `folder` (a renderer's image source).
pub fn reader(folder: &Path) -> impl FnMut(&str) -> Result<RgbaImage, String> + 'static {
    let folder = folder.to_path_buf();
    move |name| read(name, &folder)
}

/// Reads and decodes the image `name` names (relative to `folder`), or holds itself (a
/// `data:` URI: an image embedded in a glTF file, see `io::data_uri`).
pub fn read(name: &str, folder: &Path) -> Result<RgbaImage, String> {
    if let Some(embedded) = crate::io::data_uri::parse(name) {
        return decode(&embedded?.bytes);
    }
    let path = resolve(name, folder)?;
    let bytes = crate::io::file_limits::read_regular(&path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    decode(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// Decodes a PNG (any colour type and depth) or JPEG image into 8-bit RGBA.
pub fn decode(bytes: &[u8]) -> Result<RgbaImage, String> {
    if bytes.starts_with(&[0xff, 0xd8, 0xff]) {
        return decode_jpeg(bytes);
    }
    if !bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        return Err("neither a PNG nor a JPEG image: only those are drawn".into());
    }
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    // Palettes and low depths expanded to 8 bits, 16 bits stripped to 8.
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| "image too large".to_string())?;
    let mut buffer = vec![0; size];
    let frame = reader.next_frame(&mut buffer).map_err(|e| e.to_string())?;
    let (width, height) = (frame.width, frame.height);
    let data = &buffer[..frame.buffer_size()];
    let rows = frame.line_size;
    let channels = match frame.color_type {
        png::ColorType::Grayscale => 1,
        png::ColorType::GrayscaleAlpha => 2,
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        png::ColorType::Indexed => return Err("palette left unexpanded".into()),
    };
    let mut pixels = Vec::with_capacity(width as usize * height as usize * 4);
    for row in data.chunks_exact(rows).take(height as usize) {
        for px in row.chunks_exact(channels).take(width as usize) {
            pixels.extend_from_slice(&match *px {
                [g] => [g, g, g, 255],
                [g, a] => [g, g, g, a],
                [r, g, b] => [r, g, b, 255],
                [r, g, b, a] => [r, g, b, a],
                _ => [0, 0, 0, 255],
            });
        }
    }
    Ok(RgbaImage {
        width,
        height,
        pixels,
    })
}

/// Decodes a JPEG image (baseline or progressive, colour or grey) into 8-bit RGBA.
fn decode_jpeg(bytes: &[u8]) -> Result<RgbaImage, String> {
    let options = zune_core::options::DecoderOptions::default()
        .jpeg_set_out_colorspace(zune_core::colorspace::ColorSpace::RGBA);
    let mut decoder =
        zune_jpeg::JpegDecoder::new_with_options(std::io::Cursor::new(bytes), options);
    let pixels = decoder.decode().map_err(|e| format!("JPEG: {e:?}"))?;
    let info = decoder.info().ok_or("JPEG: no image header")?;
    let (width, height) = (u32::from(info.width), u32::from(info.height));
    if pixels.len() != width as usize * height as usize * 4 {
        return Err(format!(
            "JPEG: {} bytes decoded for {width} × {height} RGBA texels",
            pixels.len()
        ));
    }
    Ok(RgbaImage {
        width,
        height,
        pixels,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png_of(width: u32, height: u32, color: png::ColorType, data: &[u8]) -> Vec<u8> {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, width, height);
        encoder.set_color(color);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder
            .write_header()
            .unwrap_or_else(|e| panic!("header: {e}"));
        writer
            .write_image_data(data)
            .unwrap_or_else(|e| panic!("data: {e}"));
        drop(writer);
        out
    }

    #[test]
    fn png_images_of_every_colour_type_decode_to_rgba() {
        let rgb = png_of(2, 1, png::ColorType::Rgb, &[255, 0, 0, 0, 0, 255]);
        let image = decode(&rgb).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((image.width, image.height), (2, 1));
        assert_eq!(image.pixels, [255, 0, 0, 255, 0, 0, 255, 255]);
        let gray = png_of(1, 2, png::ColorType::Grayscale, &[10, 200]);
        let image = decode(&gray).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(image.pixels, [10, 10, 10, 255, 200, 200, 200, 255]);
        let rgba = png_of(1, 1, png::ColorType::Rgba, &[1, 2, 3, 4]);
        assert_eq!(decode(&rgba).map(|i| i.pixels), Ok(vec![1, 2, 3, 4]));
    }

    #[test]
    fn jpeg_images_decode_to_rgba_near_their_colours() {
        // 16 × 8: left half red, right half blue (JPEG is lossy: compared within a margin).
        let mut rgb = Vec::new();
        for _ in 0..8 {
            for x in 0..16 {
                rgb.extend_from_slice(if x < 8 {
                    &[220, 30, 30]
                } else {
                    &[30, 30, 220]
                });
            }
        }
        let mut bytes = Vec::new();
        jpeg_encoder::Encoder::new(&mut bytes, 95)
            .encode(&rgb, 16, 8, jpeg_encoder::ColorType::Rgb)
            .unwrap_or_else(|e| panic!("{e}"));
        let image = decode(&bytes).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((image.width, image.height), (16, 8));
        let texel = |x: usize, y: usize| &image.pixels[(y * 16 + x) * 4..][..4];
        let near = |a: &[u8], b: [u8; 4]| a.iter().zip(b).all(|(&a, b)| a.abs_diff(b) <= 12);
        assert!(near(texel(2, 3), [220, 30, 30, 255]), "{:?}", texel(2, 3));
        assert!(near(texel(13, 5), [30, 30, 220, 255]), "{:?}", texel(13, 5));
        // Cut short, it fails with the reason instead of panicking.
        let cut = decode(&bytes[..bytes.len() / 2]);
        assert!(cut.as_ref().is_err_and(|e| e.contains("JPEG")), "{cut:?}");
    }

    #[test]
    fn other_bytes_are_refused_with_the_reason() {
        let junk = decode(b"GIF89a").err().unwrap_or_default();
        assert!(junk.contains("neither a PNG nor a JPEG"), "{junk}");
        // A PNG cut short fails to decode instead of panicking.
        let rgb = png_of(4, 4, png::ColorType::Rgb, &[7; 48]);
        assert!(decode(&rgb[..rgb.len() / 2]).is_err());
    }

    #[test]
    fn names_resolve_beside_the_file_and_urls_are_not_fetched() {
        let folder = Path::new("/models/scan");
        assert_eq!(resolve("skin.png", folder), Ok(folder.join("skin.png")));
        assert_eq!(
            resolve("maps\\skin.png", folder),
            Ok(folder.join("maps/skin.png"))
        );
        assert_eq!(
            resolve("file:///tmp/a.png", folder),
            Ok(PathBuf::from("/tmp/a.png"))
        );
        assert_eq!(
            resolve("/abs/a.png", folder),
            Ok(PathBuf::from("/abs/a.png"))
        );
        assert!(resolve("http://example.com/a.png", folder).is_err());
        let missing = read("nowhere.png", Path::new("/nonexistent-folder"))
            .err()
            .unwrap_or_default();
        assert!(missing.contains("nowhere.png"), "{missing}");
    }
}
