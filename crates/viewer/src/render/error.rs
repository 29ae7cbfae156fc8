//! `RenderError`: everything the renderer can fail with, typed, so the binary can say what went
//! wrong (no Vulkan loader, no device, out of GPU memory) instead of panicking.

use ash::vk;

/// A renderer failure.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// `libvulkan.so.1` could not be opened.
    #[error(
        "cannot load the Vulkan loader (libvulkan.so.1): {0}; install libvulkan1 and a driver \
         such as mesa-vulkan-drivers (lavapipe)"
    )]
    Loader(#[from] ash::LoadingError),
    /// A Vulkan call returned an error code.
    #[error("Vulkan call failed: {0}")]
    Vulkan(#[from] vk::Result),
    /// No physical device offers what the renderer needs.
    #[error("no usable Vulkan device: {0}")]
    NoDevice(String),
    /// gpu-allocator could not place a buffer or image.
    #[error("GPU memory allocation failed: {0}")]
    Allocation(#[from] gpu_allocator::AllocationError),
    /// A mesh or image is larger than the renderer supports.
    #[error("{0}")]
    TooLarge(String),
    /// Pipelines and a target disagree on the samples per pixel.
    #[error("{0}")]
    SampleCount(String),
    /// An image's levels do not have the sizes Vulkan gives an image's mip levels.
    #[error("{0}")]
    BadLevels(String),
    /// A thread panicked while holding the memory allocator.
    #[error("the GPU memory allocator is unusable after a panic")]
    AllocatorPoisoned,
    /// The text overlay (egui's renderer) failed to upload or draw.
    #[error("text overlay: {0}")]
    Overlay(String),
    /// A window-system call (surface creation) failed.
    #[error("window system: {0}")]
    Window(String),
}

/// Renderer result.
pub type Result<T, E = RenderError> = std::result::Result<T, E>;
