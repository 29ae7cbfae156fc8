//! The Vulkan renderer (ash): one file per Vulkan object, each owning its handles and freeing
//! them in `Drop`, plus the CPU-side mesh data, the camera and viewport tiling. Used
//! identically by the headless `shot` action (`offscreen`) and the interactive viewer.

pub mod attachments;
pub mod buffer;
pub mod camera;
pub mod commands;
pub mod context;
pub mod draw;
pub mod error;
pub mod gpu_mesh;
pub mod image;
pub mod mesh_data;
pub mod offscreen;
pub mod picture_cache;
pub mod pipeline;
pub mod shader;
pub mod swapchain;
pub mod texture;
pub mod tiles;

pub use error::{RenderError, Result};
