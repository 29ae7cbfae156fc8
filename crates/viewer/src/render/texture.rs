//! `Textures`: the images models' texture coordinates map, each loaded once per name (the
//! caller decodes them, `io::texture_image`), uploaded once and bound through one descriptor
//! set; a 1×1 white image stands for "no texture", so every draw binds a set and untextured
//! models come out exactly as before. A name that cannot be loaded is drawn in its material
//! colour, and the reason is given once per name on stderr.
//! Each image is uploaded with its chain of mip levels (box-filtered here, on the CPU, so that
//! every driver shows the same) and sampled trilinearly, and anisotropically where the device
//! can: a textured scan seen from afar shows its texture's average colours instead of
//! shimmering. A texture repeats or clamps to its edge texels along u and v as the model says
//! (`Model::texture_repeat`). An image larger than `MAX_SIDE`
//! starts at its first level that fits, as every device takes that size.

use std::collections::HashMap;
use std::sync::Arc;

use ash::vk;

use super::buffer::Uploader;
use super::context::Context;
use super::error::Result;
use super::image::Image;
use decimate_core::mesh::rgba_image::RgbaImage;

/// Largest side uploaded: `maxImageDimension2D` is at least 4096 on every Vulkan device.
pub const MAX_SIDE: u32 = 4096;

/// Distinct textures one viewer or shot can hold (descriptor sets in the pool); more are
/// drawn in their material colour, with a warning.
const MAX_TEXTURES: u32 = 256;

/// Texture images are sampled as stored, like vertex colours (UNORM, no sRGB decoding), so
/// that a texel's bytes reach the screen as the file gave them.
const FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

/// One uploaded image and the set that binds it.
struct Entry {
    _image: Image,
    set: vk::DescriptorSet,
}

/// A model's texture as a draw binds it.
#[derive(Debug, Clone, Copy)]
pub struct Binding {
    pub set: vk::DescriptorSet,
    /// True when an image was found and drawn; false: the white stand-in.
    pub textured: bool,
}

/// Every texture uploaded so far, by name and wrapping, and the white stand-in.
/// Gives a texture's decoded image by its name, or why it cannot be drawn.
pub type LoadImage = Box<dyn FnMut(&str) -> std::result::Result<RgbaImage, String>>;

pub struct Textures {
    context: Arc<Context>,
    layout: vk::DescriptorSetLayout,
    pool: vk::DescriptorPool,
    /// One sampler per wrapping: index `repeat u + 2 × repeat v` ([`sampler_index`]).
    samplers: [vk::Sampler; 4],
    load: LoadImage,
    white: Option<Entry>,
    /// `None`: the name could not be drawn (said once, then the stand-in is used). The same
    /// image wrapped two ways is two entries (two sets; rare enough not to share the image).
    by_name: HashMap<(String, [bool; 2]), Option<Entry>>,
}

/// The sampler for a texture that repeats (or else clamps to its edge texels) along u and
/// along v, as `Model::texture_repeat` says.
fn sampler_index(repeat: [bool; 2]) -> usize {
    usize::from(repeat[0]) + 2 * usize::from(repeat[1])
}

impl Textures {
    /// An empty set of textures for sets of `layout` (binding 0: a combined image sampler),
    /// whose images `load` gives by name (decoded by the caller: the renderer reads no file).
    pub fn new(
        context: &Arc<Context>,
        layout: vk::DescriptorSetLayout,
        load: impl FnMut(&str) -> std::result::Result<RgbaImage, String> + 'static,
    ) -> Result<Self> {
        let device = &context.device;
        let sizes = [vk::DescriptorPoolSize::default()
            .ty(vk::DescriptorType::COMBINED_IMAGE_SAMPLER)
            .descriptor_count(MAX_TEXTURES + 1)];
        let pool_info = vk::DescriptorPoolCreateInfo::default()
            .max_sets(MAX_TEXTURES + 1)
            .pool_sizes(&sizes);
        // SAFETY: valid create info on a live device.
        let pool = unsafe { device.create_descriptor_pool(&pool_info, None)? };
        let mut this = Self {
            context: context.clone(),
            layout,
            pool,
            samplers: [vk::Sampler::null(); 4],
            load: Box::new(load),
            white: None,
            by_name: HashMap::new(),
        };
        // Trilinear filtering over every mip level, anisotropic where the device can (a
        // textured floor seen at a grazing angle stays sharp instead of blurring into its
        // smallest levels); repeating or clamped to the edge texels along each direction.
        let anisotropy = context.capabilities.max_anisotropy;
        for (i, sampler) in this.samplers.iter_mut().enumerate() {
            let mode = |repeat: bool| {
                if repeat {
                    vk::SamplerAddressMode::REPEAT
                } else {
                    vk::SamplerAddressMode::CLAMP_TO_EDGE
                }
            };
            let sampler_info = vk::SamplerCreateInfo::default()
                .mag_filter(vk::Filter::LINEAR)
                .min_filter(vk::Filter::LINEAR)
                .mipmap_mode(vk::SamplerMipmapMode::LINEAR)
                .address_mode_u(mode(i & 1 != 0))
                .address_mode_v(mode(i & 2 != 0))
                .address_mode_w(vk::SamplerAddressMode::REPEAT)
                .anisotropy_enable(anisotropy.is_some())
                .max_anisotropy(anisotropy.unwrap_or(1.0))
                .min_lod(0.0)
                .max_lod(vk::LOD_CLAMP_NONE);
            // SAFETY: valid create info on a live device; anisotropy is enabled only when the
            // device was created with `samplerAnisotropy` (`Capabilities::max_anisotropy`).
            // A sampler made before an error is destroyed with the others in `drop`.
            *sampler = unsafe { device.create_sampler(&sampler_info, None)? };
        }
        Ok(this)
    }

    /// The binding for `texture` (a model's image, when it has coordinates) wrapped as
    /// `repeat` says (`Model::texture_repeat`), uploading the image through `up` the first
    /// time a name is met with that wrapping.
    pub fn binding(
        &mut self,
        up: &mut Uploader<'_>,
        texture: Option<&str>,
        repeat: [bool; 2],
    ) -> Result<Binding> {
        if let Some(name) = texture {
            let key = (name.to_owned(), repeat);
            if !self.by_name.contains_key(&key) {
                let sampler = self.samplers[sampler_index(repeat)];
                let entry = match (self.load)(name) {
                    Ok(image) if self.by_name.len() < MAX_TEXTURES as usize => {
                        Some(self.upload(up, name, image, sampler)?)
                    }
                    Ok(_) => {
                        eprintln!(
                            "decimate: warning: texture {:?} not drawn: more than \
                             {MAX_TEXTURES} textures",
                            shown(name)
                        );
                        None
                    }
                    Err(why) => {
                        eprintln!(
                            "decimate: warning: texture {:?} not drawn: {why}",
                            shown(name)
                        );
                        None
                    }
                };
                self.by_name.insert(key.clone(), entry);
            }
            if let Some(Some(entry)) = self.by_name.get(&key) {
                return Ok(Binding {
                    set: entry.set,
                    textured: true,
                });
            }
        }
        Ok(Binding {
            set: self.white(up)?,
            textured: false,
        })
    }

    /// The white stand-in's set: what an untextured model binds, and a textured one when
    /// textures are off.
    pub fn white(&mut self, up: &mut Uploader<'_>) -> Result<vk::DescriptorSet> {
        if self.white.is_none() {
            let white = RgbaImage {
                width: 1,
                height: 1,
                pixels: vec![255; 4],
            };
            let sampler = self.samplers[sampler_index([true; 2])];
            self.white = Some(self.upload(up, "white texture", white, sampler)?);
        }
        Ok(self
            .white
            .as_ref()
            .map_or(vk::DescriptorSet::null(), |e| e.set))
    }

    /// Uploads `image` with its mip levels and writes a set that samples it with `sampler`.
    fn upload(
        &self,
        up: &mut Uploader<'_>,
        name: &str,
        image: RgbaImage,
        sampler: vk::Sampler,
    ) -> Result<Entry> {
        let image = up.upload_image(name, FORMAT, &mip_chain(image))?;
        let layouts = [self.layout];
        let alloc = vk::DescriptorSetAllocateInfo::default()
            .descriptor_pool(self.pool)
            .set_layouts(&layouts);
        let device = &self.context.device;
        // SAFETY: the pool and layout are alive; the pool has room (`MAX_TEXTURES` + 1 sets,
        // checked by the caller).
        let set = unsafe { device.allocate_descriptor_sets(&alloc)? }[0];
        let info = [vk::DescriptorImageInfo::default()
            .sampler(sampler)
            .image_view(image.view)
            .image_layout(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL)];
        let write = [vk::WriteDescriptorSet::default()
            .dst_set(set)
            .dst_binding(0)
            .descriptor_type(vk::DescriptorType::COMBINED_IMAGE_SAMPLER)
            .image_info(&info)];
        // SAFETY: the set is not in use by any command yet; the view and sampler are alive
        // for as long as the set is (both owned here).
        unsafe { device.update_descriptor_sets(&write, &[]) };
        Ok(Entry { _image: image, set })
    }
}

/// Most characters of a texture name a warning shows: a `data:` URI (an image embedded in
/// a glTF file) can run to megabytes.
const SHOWN_NAME: usize = 80;

/// `name` as a warning shows it: cut to [`SHOWN_NAME`] characters, with its length.
fn shown(name: &str) -> std::borrow::Cow<'_, str> {
    match name.char_indices().nth(SHOWN_NAME) {
        Some((cut, _)) => format!("{}… ({} characters)", &name[..cut], name.len()).into(),
        None => name.into(),
    }
}

impl Drop for Textures {
    fn drop(&mut self) {
        // SAFETY: owners wait for the GPU before dropping; destroying the pool frees its sets,
        // the images are dropped after (fields), and nothing samples them any more.
        unsafe {
            self.context.device.destroy_descriptor_pool(self.pool, None);
            for &sampler in &self.samplers {
                // Destroying a null handle (a sampler never made) is a no-op.
                self.context.device.destroy_sampler(sampler, None);
            }
        }
    }
}

/// The mip levels of `image` that fit `MAX_SIDE`, down to 1 × 1: each level's sides are
/// half the previous level's, rounded down (at least 1), as Vulkan sizes an image's levels.
/// An image too large to upload starts at its first level that fits.
fn mip_chain(image: RgbaImage) -> Vec<RgbaImage> {
    let fits = |l: &RgbaImage| l.width <= MAX_SIDE && l.height <= MAX_SIDE;
    let mut image = image;
    while !fits(&image) {
        image = next_level(&image);
    }
    let mut levels = vec![image];
    while let Some(last) = levels.last().filter(|l| l.width > 1 || l.height > 1) {
        let next = next_level(last);
        levels.push(next);
    }
    levels
}

/// The mip level below `image`: sides halved, rounded down (at least 1); each texel the
/// rounded mean of the texels of `image` it covers (two by two; along an odd side, the last
/// texel of the level takes in three, so that no texel is left out).
fn next_level(image: &RgbaImage) -> RgbaImage {
    let (w, h) = (image.width, image.height);
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    // Texels `span(i)` of a side of `n` cover texel `i` of the side of `m` below it.
    let span = |i: u32, n: u32, m: u32| {
        let (a, b) = (u64::from(i) * u64::from(n), u64::from(i + 1) * u64::from(n));
        (a / u64::from(m)) as u32..(b / u64::from(m)) as u32
    };
    let mut pixels = Vec::with_capacity(nw as usize * nh as usize * 4);
    for y in 0..nh {
        let rows = span(y, h, nh);
        for x in 0..nw {
            let columns = span(x, w, nw);
            let mut sum = [0u32; 4];
            let mut count = 0u32;
            for sy in rows.clone() {
                for sx in columns.clone() {
                    let at = (sy as usize * w as usize + sx as usize) * 4;
                    for (total, &value) in sum.iter_mut().zip(&image.pixels[at..at + 4]) {
                        *total += u32::from(value);
                    }
                    count += 1;
                }
            }
            let count = count.max(1);
            pixels.extend(sum.map(|total| ((total + count / 2) / count) as u8));
        }
    }
    RgbaImage {
        width: nw,
        height: nh,
        pixels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_too_large_to_upload_starts_at_its_first_level_that_fits() {
        // 8200 × 3: two levels down (2050 × 1) is the first that fits 4096.
        let texel = |x: u32| {
            if x.is_multiple_of(2) {
                [0, 0, 0, 255]
            } else {
                [100, 60, 20, 255]
            }
        };
        let pixels = (0..3).flat_map(|_| (0..8200).flat_map(texel)).collect();
        let chain = mip_chain(RgbaImage {
            width: 8200,
            height: 3,
            pixels,
        });
        let sizes: Vec<(u32, u32)> = chain.iter().take(3).map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(2050, 1), (1025, 1), (512, 1)]);
        assert_eq!(chain.last().map(|l| (l.width, l.height)), Some((1, 1)));
        // Every texel the mean of the stripes it stands for.
        assert!(chain[0].pixels.chunks(4).all(|t| t == [50, 30, 10, 255]));
    }

    #[test]
    fn mip_levels_halve_down_to_one_texel_and_keep_the_mean_colour() {
        // A 6 × 3 checker of single black and white texels, with a red first column.
        let mut pixels = Vec::new();
        for y in 0..3u32 {
            for x in 0..6u32 {
                pixels.extend_from_slice(&match (x, (x + y) % 2) {
                    (0, _) => [255, 0, 0, 255],
                    (_, 0) => [0, 0, 0, 255],
                    _ => [255, 255, 255, 255],
                });
            }
        }
        let chain = mip_chain(RgbaImage {
            width: 6,
            height: 3,
            pixels,
        });
        // Vulkan's sizes: each side halved, rounded down, at least 1.
        let sizes: Vec<(u32, u32)> = chain.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(6, 3), (3, 1), (1, 1)]);
        for level in &chain {
            assert_eq!(
                level.pixels.len(),
                (level.width * level.height * 4) as usize
            );
        }
        // Level 1: the odd row count puts all three rows in each texel; columns two by two.
        // The first texel: three red texels and the checker's column 1 (white, black, white).
        let level1 = &chain[1].pixels;
        assert_eq!(&level1[..4], &[213, 85, 85, 255]);
        // The others: three black and three white texels, mid grey.
        assert_eq!(&level1[4..8], &[128, 128, 128, 255]);
        assert_eq!(&level1[8..12], &[128, 128, 128, 255]);
        // The last level: the mean of the level above.
        assert_eq!(&chain[2].pixels[..], &[156, 114, 114, 255]);
        // One texel has no level below; a 1-wide strip halves along its length only.
        assert_eq!(
            mip_chain(RgbaImage {
                width: 1,
                height: 1,
                pixels: vec![9; 4]
            })
            .len(),
            1
        );
        let strip = mip_chain(RgbaImage {
            width: 1,
            height: 4,
            pixels: vec![7; 16],
        });
        let sizes: Vec<(u32, u32)> = strip.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(sizes, [(1, 4), (1, 2), (1, 1)]);
        assert!(strip.iter().all(|l| l.pixels.iter().all(|&v| v == 7)));
    }
}
