//! `AppError`: what ends the interactive viewer with a message — the window system, the GPU
//! or the UI layer failing. Quitting is no error: callbacks return `Flow::Quit` for it.

use crate::render::RenderError;

/// A failure of the viewer, reported by `main` as `decimate: …` with a non-zero exit.
#[derive(Debug, thiserror::Error)]
pub enum AppError {
    /// No X11 display to open a window on.
    #[error("cannot open the X11 display ({display}): {message}")]
    Display { display: String, message: String },
    /// The window or its Vulkan surface could not be made.
    #[error("cannot create the window: {0}")]
    Window(String),
    /// winit's event loop failed.
    #[error("event loop: {0}")]
    EventLoop(String),
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The egui layer (menu, field, status line) failed to upload or draw.
    #[error("{what}: {message}")]
    Ui { what: &'static str, message: String },
}

impl AppError {
    /// A UI-layer failure of `what` (e.g. "egui textures").
    pub fn ui(what: &'static str, message: impl std::fmt::Display) -> Self {
        Self::Ui {
            what,
            message: message.to_string(),
        }
    }
}
