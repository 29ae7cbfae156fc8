//! `ShaderModule`: a `vk::ShaderModule` made from SPIR-V that `build.rs` compiled from
//! `shaders/`, destroyed in `Drop`.

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::{RenderError, Result};

/// SPIR-V of the mesh shaders, compiled by build.rs.
pub const MESH_VERT: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/mesh.vert.spv"));
pub const MESH_FRAG: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/mesh.frag.spv"));

/// A shader module.
pub struct ShaderModule {
    context: Arc<Context>,
    pub handle: vk::ShaderModule,
}

impl ShaderModule {
    pub fn new(context: &Arc<Context>, spirv: &[u8]) -> Result<Self> {
        let mut cursor = std::io::Cursor::new(spirv);
        let code = ash::util::read_spv(&mut cursor)
            .map_err(|e| RenderError::TooLarge(format!("embedded SPIR-V is malformed: {e}")))?;
        let info = vk::ShaderModuleCreateInfo::default().code(&code);
        // SAFETY: `code` is SPIR-V words produced by shaderc at build time.
        let handle = unsafe { context.device.create_shader_module(&info, None)? };
        Ok(Self {
            context: context.clone(),
            handle,
        })
    }
}

impl Drop for ShaderModule {
    fn drop(&mut self) {
        // SAFETY: modules are only needed while pipelines are created; none is in use now.
        unsafe { self.context.device.destroy_shader_module(self.handle, None) };
    }
}
