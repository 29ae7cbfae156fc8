//! A small GLUT-like layer over winit 0.30's `ApplicationHandler`: the viewer registers one
//! object implementing [`Callbacks`] (display, reshape, keyboard, special keys, mouse, motion,
//! wheel — the original program's callbacks) and [`main_loop`] creates the window and feeds it
//! events until a callback asks to quit. X11 is forced (Xvfb in CI; XWayland elsewhere).

use std::sync::Arc;

use winit::application::ApplicationHandler;
use winit::dpi::{LogicalSize, PhysicalPosition};
use winit::event::{ElementState, MouseScrollDelta, StartCause, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key as WinitKey, NamedKey};
use winit::window::{Window, WindowId};

use super::app_error::AppError;
use super::menu::Key;

/// Mouse buttons, as GLUT names them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Button {
    Left,
    Middle,
    Right,
}

/// Keys GLUT calls "special": arrows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Special {
    Up,
    Down,
    Left,
    Right,
}

/// What the loop does after a callback.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    Continue,
    Quit,
}

/// The viewer's callbacks. Positions are physical pixels from the window's top-left corner.
pub trait Callbacks {
    /// The window exists: create what draws into it. An error ends the loop.
    fn create(&mut self, window: &Arc<Window>) -> Result<(), AppError>;
    /// Draw a frame. An error ends the loop, and `main_loop` returns it.
    fn display(&mut self, window: &Window) -> Result<Flow, AppError>;
    /// The window was resized.
    fn reshape(&mut self, width: u32, height: u32);
    /// A bound or printable key was pressed.
    fn keyboard(&mut self, key: Key) -> Flow;
    /// An arrow key was pressed.
    fn special(&mut self, key: Special);
    /// A mouse button went down (`pressed`) or up at `(x, y)`.
    fn mouse(&mut self, button: Button, pressed: bool, x: f64, y: f64) -> Flow;
    /// The mouse moved to `(x, y)`.
    fn motion(&mut self, x: f64, y: f64);
    /// Wheel steps, positive away from the user.
    fn wheel(&mut self, steps: f32);
    /// Every raw event goes here first (for the UI layer); `true` means it was consumed.
    fn filter(&mut self, window: &Window, event: &WindowEvent) -> bool;
    /// The window's close button: quit, or stay (to ask first).
    fn close_requested(&mut self) -> Flow {
        Flow::Quit
    }
    /// A file was dropped onto the window.
    fn dropped(&mut self, _window: &Window, _path: std::path::PathBuf) {}
    /// When the window must be drawn again without any event (a status message expiring).
    fn wake_at(&self) -> Option<std::time::Instant> {
        None
    }
    /// Woken at `wake_at`'s time: whether a frame is due now (false: wait on).
    fn due(&mut self) -> bool {
        true
    }
    /// The loop is ending: free GPU objects while the window still exists.
    fn destroy(&mut self);
}

struct Glut<'a, C: Callbacks> {
    title: String,
    callbacks: &'a mut C,
    window: Option<Arc<Window>>,
    cursor: PhysicalPosition<f64>,
    /// Shift is held.
    shift: bool,
    /// The left button went down with Shift: it is reported as the middle one until it is up.
    left_is_middle: bool,
    error: Option<AppError>,
}

/// Opens a window titled `title` and runs the event loop with `callbacks` until one of them
/// returns [`Flow::Quit`] or the window is closed.
pub fn main_loop<C: Callbacks>(title: &str, callbacks: &mut C) -> Result<(), AppError> {
    use winit::platform::x11::EventLoopBuilderExtX11;
    let event_loop = EventLoop::builder().with_x11().build().map_err(|e| {
        let display = match std::env::var("DISPLAY") {
            Ok(d) => format!("DISPLAY={d}"),
            Err(_) => "DISPLAY is not set".to_string(),
        };
        AppError::Display {
            display,
            message: e.to_string(),
        }
    })?;
    let mut glut = Glut {
        title: title.to_string(),
        callbacks,
        window: None,
        cursor: PhysicalPosition::new(0.0, 0.0),
        shift: false,
        left_is_middle: false,
        error: None,
    };
    event_loop
        .run_app(&mut glut)
        .map_err(|e| AppError::EventLoop(e.to_string()))?;
    match glut.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

impl<C: Callbacks> Glut<'_, C> {
    fn quit(&mut self, event_loop: &ActiveEventLoop) {
        self.callbacks.destroy();
        event_loop.exit();
    }

    /// A key went down: arrows to `special`, bound and printable keys to `keyboard`.
    fn key_pressed(&mut self, key: &WinitKey) -> Flow {
        let key = match key {
            WinitKey::Named(NamedKey::F2) => Some(Key::F2),
            WinitKey::Named(NamedKey::F3) => Some(Key::F3),
            WinitKey::Named(NamedKey::Tab) => Some(Key::Tab),
            WinitKey::Named(NamedKey::Escape) => Some(Key::Escape),
            WinitKey::Named(arrow) => {
                let special = match arrow {
                    NamedKey::ArrowUp => Some(Special::Up),
                    NamedKey::ArrowDown => Some(Special::Down),
                    NamedKey::ArrowLeft => Some(Special::Left),
                    NamedKey::ArrowRight => Some(Special::Right),
                    _ => None,
                };
                if let Some(s) = special {
                    self.callbacks.special(s);
                }
                None
            }
            WinitKey::Character(s) => s.chars().next().map(Key::Char),
            _ => None,
        };
        match key {
            Some(key) => self.callbacks.keyboard(key),
            None => Flow::Continue,
        }
    }

    /// A mouse button went down (`pressed`) or up at the cursor.
    fn button(&mut self, pressed: bool, button: winit::event::MouseButton) -> Flow {
        let button = match button {
            // Shift + left stands for the middle button (panning) where there is none, as
            // on a touchpad; its release goes with its press.
            winit::event::MouseButton::Left => {
                if pressed {
                    self.left_is_middle = self.shift;
                }
                Some(if self.left_is_middle {
                    Button::Middle
                } else {
                    Button::Left
                })
            }
            winit::event::MouseButton::Right => Some(Button::Right),
            winit::event::MouseButton::Middle => Some(Button::Middle),
            _ => None,
        };
        match button {
            Some(b) => (self.callbacks).mouse(b, pressed, self.cursor.x, self.cursor.y),
            None => Flow::Continue,
        }
    }
}

impl<C: Callbacks> ApplicationHandler for Glut<'_, C> {
    fn new_events(&mut self, _event_loop: &ActiveEventLoop, cause: StartCause) {
        if let (StartCause::ResumeTimeReached { .. }, Some(window)) = (cause, &self.window) {
            if self.callbacks.due() {
                window.request_redraw();
            }
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        event_loop.set_control_flow(match self.callbacks.wake_at() {
            Some(at) => ControlFlow::WaitUntil(at),
            None => ControlFlow::Wait,
        });
    }

    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_some() {
            return;
        }
        let attributes = Window::default_attributes()
            .with_title(self.title.clone())
            .with_inner_size(LogicalSize::new(1024.0, 720.0));
        let window = match event_loop.create_window(attributes) {
            Ok(w) => Arc::new(w),
            Err(e) => {
                self.error = Some(AppError::Window(e.to_string()));
                event_loop.exit();
                return;
            }
        };
        if let Err(e) = self.callbacks.create(&window) {
            self.error = Some(e);
            self.quit(event_loop);
            return;
        }
        let size = window.inner_size();
        self.callbacks.reshape(size.width, size.height);
        window.request_redraw();
        self.window = Some(window);
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        let Some(window) = self.window.clone() else {
            return;
        };
        if self.callbacks.filter(&window, &event) {
            window.request_redraw();
            return;
        }
        let mut flow = Flow::Continue;
        match event {
            WindowEvent::CloseRequested => flow = self.callbacks.close_requested(),
            WindowEvent::DroppedFile(path) => self.callbacks.dropped(&window, path),
            WindowEvent::Resized(size) => self.callbacks.reshape(size.width, size.height),
            WindowEvent::RedrawRequested => {
                // Drawn on demand only: no redraw is requested from here, so an idle viewer
                // leaves the (shared, often software) GPU alone.
                match self.callbacks.display(&window) {
                    Ok(Flow::Continue) => {}
                    Ok(Flow::Quit) => self.quit(event_loop),
                    Err(e) => {
                        self.error = Some(e);
                        self.quit(event_loop);
                    }
                }
                return;
            }
            WindowEvent::KeyboardInput { event, .. } if event.state == ElementState::Pressed => {
                flow = self.key_pressed(&event.logical_key);
            }
            WindowEvent::CursorMoved { position, .. } => {
                self.cursor = position;
                self.callbacks.motion(position.x, position.y);
            }
            WindowEvent::ModifiersChanged(modifiers) => {
                self.shift = modifiers.state().shift_key();
            }
            WindowEvent::MouseInput { state, button, .. } => {
                flow = self.button(state == ElementState::Pressed, button);
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let steps = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    MouseScrollDelta::PixelDelta(p) => (p.y / 40.0) as f32,
                };
                self.callbacks.wheel(steps);
            }
            _ => return,
        }
        if flow == Flow::Quit {
            self.quit(event_loop);
        } else {
            window.request_redraw();
        }
    }
}
