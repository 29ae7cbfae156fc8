//! `Camera`: the two navigation modes of the original viewer — model control (a trackball that
//! turns the model about the centre of its bounding box) and eye control (a first-person eye
//! that looks around and walks) — plus panning (the view slides across the screen, so that a
//! detail can be brought to the middle and zoomed into), framing on a bounding box and the
//! projection.
//!
//! The model's orientation is kept in both modes, so switching mode never jumps: eye control
//! starts where model control's eye is, looking at the centre.

use glam::camera::rh::{proj::vulkan::perspective, view::look_to_mat4};
use glam::{Mat4, Quat, Vec2, Vec3};

/// Vertical field of view.
const FOV_Y: f32 = std::f32::consts::FRAC_PI_4;
/// Radians per pixel of mouse drag.
const TURN_PER_PIXEL: f32 = 0.008;
/// The default view: a three-quarter view, turned 30° about Y and tipped 20° towards the eye,
/// so a box shows three faces.
const DEFAULT_YAW: f32 = -0.52;
const DEFAULT_PITCH: f32 = 0.35;

/// Which navigation the mouse and keys drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Navigation {
    /// Grab and turn the model about its centre; the wheel moves the eye closer.
    Model,
    /// First-person: drag looks around, wheel / arrows / W S walk.
    Eye,
}

/// An axis-aligned box in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    pub min: Vec3,
    pub max: Vec3,
}

impl Bounds {
    pub fn centre(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }

    /// Radius of the bounding sphere, never zero.
    pub fn radius(&self) -> f32 {
        ((self.max - self.min).length() * 0.5).max(1e-6)
    }

    /// The union of both boxes.
    pub fn union(self, other: Self) -> Self {
        Self {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }
}

/// A camera framed on a bounding box.
#[derive(Debug, Clone, PartialEq)]
pub struct Camera {
    pub navigation: Navigation,
    bounds: Bounds,
    /// Rotation of the model about the box centre (model control).
    orientation: Quat,
    /// Eye distance from the centre in model control.
    distance: f32,
    /// Model control: how far the view slid across the screen (world units, x right, y up,
    /// at the centre's depth); the eye looks at `centre + pan` and zooms towards it.
    pan: Vec2,
    /// Eye control: position and look angles, relative to the model-control frame.
    eye: Vec3,
    yaw: f32,
    pitch: f32,
}

impl Camera {
    /// A camera in model control that shows the whole box.
    pub fn framing(bounds: Bounds) -> Self {
        let distance = bounds.radius() / (FOV_Y * 0.5).sin() * 1.05;
        Self {
            navigation: Navigation::Model,
            bounds,
            orientation: Quat::from_rotation_x(DEFAULT_PITCH) * Quat::from_rotation_y(DEFAULT_YAW),
            distance,
            pan: Vec2::ZERO,
            eye: bounds.centre() + Vec3::Z * distance,
            yaw: 0.0,
            pitch: 0.0,
        }
    }

    /// Back to the framed default view, keeping the navigation mode.
    pub fn reset(&mut self) {
        let navigation = self.navigation;
        *self = Self::framing(self.bounds);
        self.navigation = navigation;
    }

    /// Switches between model and eye control; eye control starts at model control's eye.
    pub fn set_navigation(&mut self, navigation: Navigation) {
        if navigation == Navigation::Eye && self.navigation == Navigation::Model {
            self.eye = self.target() + Vec3::Z * self.distance;
            self.yaw = 0.0;
            self.pitch = 0.0;
        }
        self.navigation = navigation;
    }

    /// A mouse drag of `delta` pixels: turns the model, or looks around.
    pub fn drag(&mut self, delta: Vec2) {
        match self.navigation {
            Navigation::Model => {
                let turn = Quat::from_rotation_y(delta.x * TURN_PER_PIXEL)
                    * Quat::from_rotation_x(delta.y * TURN_PER_PIXEL);
                self.orientation = (turn * self.orientation).normalize();
            }
            Navigation::Eye => {
                self.yaw -= delta.x * TURN_PER_PIXEL;
                self.pitch = (self.pitch - delta.y * TURN_PER_PIXEL).clamp(-1.5, 1.5);
            }
        }
    }

    /// A pan by `delta` pixels in a viewport `height` pixels tall of this aspect ratio
    /// (width / height): the model follows the pointer, the point under it at the centre's
    /// depth staying under it (model control); in eye control the eye steps sideways and up
    /// as far.
    pub fn pan(&mut self, delta: Vec2, height: f32, aspect: f32) {
        if !(height.is_finite() && height >= 1.0) {
            return;
        }
        let depth = match self.navigation {
            Navigation::Model => self.distance,
            Navigation::Eye => (self.eye - self.bounds.centre())
                .length()
                .max(self.bounds.radius()),
        };
        // World units per pixel at that depth: the view's height there over its pixels.
        let per_pixel = 2.0 * depth * (fov_y(aspect) * 0.5).tan() / height;
        let slide = Vec2::new(-delta.x, delta.y) * per_pixel;
        match self.navigation {
            Navigation::Model => self.pan += slide,
            Navigation::Eye => {
                let dir = self.look_direction();
                let side = dir.cross(Vec3::Y).normalize_or_zero();
                let up = side.cross(dir);
                self.eye += side * slide.x + up * slide.y;
            }
        }
    }

    /// Where model control's eye looks: the box centre, slid by the pan.
    fn target(&self) -> Vec3 {
        self.bounds.centre() + self.pan.extend(0.0)
    }

    /// Wheel `steps` (positive: towards the model): zooms, or walks forward.
    pub fn wheel(&mut self, steps: f32) {
        match self.navigation {
            Navigation::Model => {
                let min = self.bounds.radius() * 0.05;
                self.distance = (self.distance * 0.9f32.powf(steps)).max(min);
            }
            Navigation::Eye => self.walk(steps * 0.1, 0.0),
        }
    }

    /// Walks in eye control: `forward` and `right` in units of the box radius. Model control
    /// treats forward as zoom and ignores sideways.
    pub fn walk(&mut self, forward: f32, right: f32) {
        let r = self.bounds.radius();
        match self.navigation {
            Navigation::Model => self.wheel(forward * 10.0),
            Navigation::Eye => {
                let dir = self.look_direction();
                let side = dir.cross(Vec3::Y).normalize_or_zero();
                self.eye += (dir * forward + side * right) * r;
            }
        }
    }

    fn look_direction(&self) -> Vec3 {
        Vec3::new(
            -self.yaw.sin() * self.pitch.cos(),
            self.pitch.sin(),
            -self.yaw.cos() * self.pitch.cos(),
        )
    }

    /// World → view transform.
    pub fn view(&self) -> Mat4 {
        let centre = self.bounds.centre();
        let turn_model = Mat4::from_translation(centre)
            * Mat4::from_quat(self.orientation)
            * Mat4::from_translation(-centre);
        let eye_view = match self.navigation {
            Navigation::Model => {
                look_to_mat4(self.target() + Vec3::Z * self.distance, -Vec3::Z, Vec3::Y)
            }
            Navigation::Eye => look_to_mat4(self.eye, self.look_direction(), Vec3::Y),
        };
        eye_view * turn_model
    }

    /// View → clip transform for a viewport of this aspect ratio (width / height).
    pub fn projection(&self, aspect: f32) -> Mat4 {
        let r = self.bounds.radius();
        let (near, far) = match self.navigation {
            Navigation::Model => (
                (self.distance - r * 1.5).max(r * 0.01),
                self.distance + r * 1.5,
            ),
            Navigation::Eye => (
                r * 0.01,
                (self.eye - self.bounds.centre()).length() + r * 2.0,
            ),
        };
        perspective(fov_y(aspect), usable(aspect), near, far.max(near * 2.0))
    }
}

/// An aspect ratio fit to project with: 1 when it is not a positive number.
fn usable(aspect: f32) -> f32 {
    if aspect.is_finite() && aspect > 0.0 {
        aspect
    } else {
        1.0
    }
}

/// The vertical field of view of a viewport of this aspect ratio: a portrait one keeps the
/// field of view across its narrow side, so the framed model fits in both directions.
fn fov_y(aspect: f32) -> f32 {
    let aspect = usable(aspect);
    if aspect < 1.0 {
        2.0 * ((FOV_Y * 0.5).tan() / aspect).atan()
    } else {
        FOV_Y
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_box() -> Bounds {
        Bounds {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        }
    }

    fn project(c: &Camera, p: Vec3) -> Vec3 {
        project_with_aspect(c, p, 1.0)
    }

    fn project_with_aspect(c: &Camera, p: Vec3, aspect: f32) -> Vec3 {
        (c.projection(aspect) * c.view()).project_point3(p)
    }

    #[test]
    fn portrait_and_landscape_viewports_keep_the_model_in_view() {
        let c = Camera::framing(unit_box());
        for aspect in [0.3, 0.66, 1.0, 2.5] {
            for corner in [Vec3::ONE, -Vec3::ONE, Vec3::new(1.0, -1.0, 1.0)] {
                let ndc = project_with_aspect(&c, corner, aspect);
                assert!(
                    ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0,
                    "aspect {aspect}: {ndc:?}"
                );
            }
        }
    }

    #[test]
    fn framing_keeps_every_corner_on_screen() {
        let c = Camera::framing(unit_box());
        for x in [-1.0, 1.0] {
            for y in [-1.0, 1.0] {
                for z in [-1.0, 1.0] {
                    let ndc = project(&c, Vec3::new(x, y, z));
                    assert!(ndc.x.abs() < 1.0 && ndc.y.abs() < 1.0, "{ndc:?}");
                    assert!((0.0..1.0).contains(&ndc.z), "{ndc:?}");
                }
            }
        }
    }

    #[test]
    fn centre_projects_to_screen_centre_in_both_modes() {
        let mut c = Camera::framing(unit_box());
        assert!(project(&c, Vec3::ZERO).truncate().length() < 1e-4);
        c.set_navigation(Navigation::Eye);
        assert!(project(&c, Vec3::ZERO).truncate().length() < 1e-4);
    }

    #[test]
    fn wheel_zooms_in_and_reset_restores() {
        let mut c = Camera::framing(unit_box());
        let before = c.clone();
        c.wheel(3.0);
        let near = project(&c, Vec3::X);
        assert!(near.x.abs() > project(&before, Vec3::X).x.abs());
        c.drag(Vec2::new(40.0, 10.0));
        c.reset();
        assert_eq!(c, before);
    }

    #[test]
    fn panning_keeps_the_grabbed_point_under_the_pointer_and_zooms_towards_it() {
        // An 800 × 600 viewport and a 300 × 900 one (portrait: a wider field of view).
        for (width, height) in [(800.0f32, 600.0f32), (300.0, 900.0)] {
            let aspect = width / height;
            let mut c = Camera::framing(unit_box());
            c.drag(Vec2::new(30.0, -20.0));
            let to_pixels = |c: &Camera, p: Vec3| {
                let ndc = project_with_aspect(c, p, aspect);
                Vec2::new((ndc.x + 1.0) * 0.5 * width, (ndc.y + 1.0) * 0.5 * height)
            };
            let before = to_pixels(&c, Vec3::ZERO);
            // Right by 120 px and down by 45 px (window y grows downwards).
            c.pan(Vec2::new(120.0, 45.0), height, aspect);
            let after = to_pixels(&c, Vec3::ZERO);
            // Vulkan's clip y points down the screen, as window pixels do.
            let moved = after - before;
            assert!(
                (moved - Vec2::new(120.0, 45.0)).length() < 0.5,
                "{width}×{height}: the centre moved by {moved:?}"
            );
            // Zooming in keeps the panned-to point where it is on screen and enlarges about it.
            // The point at the middle of the view, at the centre's depth (the model is turned).
            let target = c.view().inverse().transform_point3(-Vec3::Z * c.distance);
            assert!((to_pixels(&c, target) - Vec2::new(width, height) * 0.5).length() < 0.5);
            let at = to_pixels(&c, target);
            let beside = to_pixels(&c, target + Vec3::X * 0.1);
            c.wheel(5.0);
            assert!((to_pixels(&c, target) - at).length() < 0.5);
            assert!((to_pixels(&c, target + Vec3::X * 0.1) - at).length() > (beside - at).length());
            // Reset brings the framed view back.
            c.reset();
            assert_eq!(c.pan, Vec2::ZERO);
            assert!(project(&c, Vec3::ZERO).truncate().length() < 1e-4);
        }
    }

    #[test]
    fn panning_in_eye_control_steps_sideways_without_turning() {
        let mut c = Camera::framing(unit_box());
        c.set_navigation(Navigation::Eye);
        let (eye, look) = (c.eye, c.look_direction());
        c.pan(Vec2::new(-50.0, 0.0), 600.0, 1.0);
        let step = c.eye - eye;
        assert!(step.x > 0.0, "dragging left moves the eye right: {step:?}");
        assert!(
            step.dot(look).abs() < 1e-6 && step.y.abs() < 1e-6,
            "{step:?}"
        );
        assert_eq!(c.look_direction(), look);
        // A degenerate viewport pans nothing.
        let before = c.clone();
        c.pan(Vec2::new(10.0, 10.0), 0.0, 1.0);
        assert_eq!(c, before);
    }

    #[test]
    fn eye_walks_towards_the_model() {
        let mut c = Camera::framing(unit_box());
        c.set_navigation(Navigation::Eye);
        let d0 = c.eye.distance(Vec3::ZERO);
        c.walk(0.5, 0.0);
        assert!(c.eye.distance(Vec3::ZERO) < d0);
    }
}
