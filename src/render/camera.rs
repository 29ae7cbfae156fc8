//! `Camera`: the two navigation modes of the original viewer — model control (a trackball that
//! turns the model about the centre of its bounding box) and eye control (a first-person eye
//! that looks around and walks) — plus framing on a bounding box and the projection.
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
            self.eye = self.bounds.centre() + Vec3::Z * self.distance;
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
            Navigation::Model => look_to_mat4(centre + Vec3::Z * self.distance, -Vec3::Z, Vec3::Y),
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
        let aspect = if aspect.is_finite() && aspect > 0.0 {
            aspect
        } else {
            1.0
        };
        // A portrait viewport keeps the field of view across its narrow side, so the framed
        // model fits in both directions.
        let fov_y = if aspect < 1.0 {
            2.0 * ((FOV_Y * 0.5).tan() / aspect).atan()
        } else {
            FOV_Y
        };
        perspective(fov_y, aspect, near, far.max(near * 2.0))
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
    fn eye_walks_towards_the_model() {
        let mut c = Camera::framing(unit_box());
        c.set_navigation(Navigation::Eye);
        let d0 = c.eye.distance(Vec3::ZERO);
        c.walk(0.5, 0.0);
        assert!(c.eye.distance(Vec3::ZERO) < d0);
    }
}
