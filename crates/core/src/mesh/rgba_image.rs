//! An 8-bit RGBA picture: what texture files decode to (`io::texture_image`), what the
//! renderer uploads and what an offscreen render reads back (`render::offscreen`).

/// A picture: `width * height` RGBA8 pixels, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbaImage {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// `width * height * 4` bytes, RGBA, rows top to bottom.
    pub pixels: Vec<u8>,
}
