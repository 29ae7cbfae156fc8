//! Build script: compiles every top-level `shaders/*.vert|*.frag` GLSL file to SPIR-V in `OUT_DIR` with
//! shaderc, so the renderer embeds them with `include_bytes!` and no shader tool is needed at
//! run time.
//!
//! Link trap (PLATFORM.md): Debian 12's `libshaderc.so.1` is under-linked, so shaderc is linked
//! statically; `.cargo/config.toml` overrides shaderc-sys's library probe with the static
//! glslang / SPIRV-Tools archives, because this script is the program that links shaderc and
//! a build script cannot add link arguments to its own link.

use std::path::{Path, PathBuf};

fn main() {
    if let Err(e) = compile_shaders(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders")) {
        // A broken shader is a build error with the compiler's message, not a panic trace.
        println!("cargo:warning={e}");
        std::process::exit(1);
    }
}

fn compile_shaders(dir: &Path) -> Result<(), String> {
    println!("cargo:rerun-if-changed={}", dir.display());
    let out_dir = PathBuf::from(std::env::var("OUT_DIR").map_err(|e| format!("OUT_DIR: {e}"))?);
    let compiler = shaderc::Compiler::new().map_err(|e| format!("shaderc: {e}"))?;
    let mut options = shaderc::CompileOptions::new().map_err(|e| format!("shaderc: {e}"))?;
    options.set_target_env(
        shaderc::TargetEnv::Vulkan,
        shaderc::EnvVersion::Vulkan1_3 as u32,
    );
    options.set_optimization_level(shaderc::OptimizationLevel::Performance);
    options.set_warnings_as_errors();

    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for entry in entries {
        let path = entry.map_err(|e| format!("{}: {e}", dir.display()))?.path();
        let kind = match path.extension().and_then(|e| e.to_str()) {
            Some("vert") => shaderc::ShaderKind::Vertex,
            Some("frag") => shaderc::ShaderKind::Fragment,
            _ => continue,
        };
        println!("cargo:rerun-if-changed={}", path.display());
        let source =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let name = path.display().to_string();
        let artifact = compiler
            .compile_into_spirv(&source, kind, &name, "main", Some(&options))
            .map_err(|e| format!("{name}: {e}"))?;
        let file = path.file_name().map(|f| f.to_string_lossy().into_owned());
        let out = out_dir.join(format!("{}.spv", file.unwrap_or_default()));
        std::fs::write(&out, artifact.as_binary_u8())
            .map_err(|e| format!("{}: {e}", out.display()))?;
    }
    Ok(())
}
