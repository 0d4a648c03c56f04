//! The viewer's fly camera: mouse-look, WASD/QE flight, scroll for speed, and the two jumps
//! (back to the scene's camera, level with the horizon). Pure state, no window: the viewer
//! feeds it input and asks for a scene camera each frame, and the tests drive it directly.
//!
//! Conventions: y is up; yaw 0 looks along −z (the default scene's view) and grows turning
//! right (towards +x); pitch grows looking up and stays within ±[`MAX_PITCH_DEG`], so the
//! view never degenerates to straight up or down (where "right" has no meaning).

use glam::DVec3;
use ocean_core::scene;

/// Largest |pitch|, degrees.
pub const MAX_PITCH_DEG: f64 = 89.0;
/// Flight speed bounds, m/s: slow enough to inspect a crest, fast enough to cross a storm
/// sea's 512 m patch in a blink.
pub const SPEED_RANGE: (f64, f64) = (0.1, 5000.0);
/// Factor per scroll step.
pub const SCROLL_FACTOR: f64 = 1.25;
/// Speed factor while the boost key (Shift) is held.
pub const BOOST: f64 = 5.0;
/// Longest time step integrated at once, s: a stalled frame must not teleport the camera.
pub const MAX_STEP_S: f64 = 0.25;
/// Default mouse sensitivity, radians per pixel of motion.
pub const DEFAULT_SENSITIVITY: f64 = 0.003;

/// A direction of flight (held keys).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Motion {
    /// W: along the view direction.
    Forward,
    /// S: against it.
    Back,
    /// A: to the left, level.
    Left,
    /// D: to the right, level.
    Right,
    /// E: straight up.
    Up,
    /// Q: straight down.
    Down,
}

impl Motion {
    const ALL: [Motion; 6] =
        [Motion::Forward, Motion::Back, Motion::Left, Motion::Right, Motion::Up, Motion::Down];

    fn index(self) -> usize {
        self as usize
    }
}

/// The fly camera.
#[derive(Clone, Debug)]
pub struct CameraController {
    /// Eye position, m.
    pub position: DVec3,
    /// Heading, radians (0 = −z, positive turning right).
    pub yaw: f64,
    /// Elevation of the view, radians (positive = up).
    pub pitch: f64,
    /// Flight speed, m/s.
    pub speed: f64,
    /// Radians per pixel of mouse motion.
    pub sensitivity: f64,
    /// Whether the boost key is held.
    pub boost: bool,
    held: [bool; 6],
    home: scene::Camera,
    /// True until the first move: the scene camera is then handed back unchanged, bit for
    /// bit, so the viewer's first frames equal `ocean render`'s.
    at_home: bool,
}

impl CameraController {
    /// A controller at the scene's camera.
    pub fn new(home: &scene::Camera) -> Self {
        let mut c = Self {
            position: DVec3::ZERO,
            yaw: 0.0,
            pitch: 0.0,
            speed: 10.0,
            sensitivity: DEFAULT_SENSITIVITY,
            boost: false,
            held: [false; 6],
            home: home.clone(),
            at_home: true,
        };
        c.jump_home();
        c
    }

    /// Back to the scene's camera (key R); the speed follows the camera's height, so that a
    /// view from 2 m and one from 2 km both move at a usable pace.
    pub fn jump_home(&mut self) {
        let eye = DVec3::from_array(self.home.position);
        let d = DVec3::from_array(self.home.look_at) - eye;
        self.position = eye;
        self.yaw = d.x.atan2(-d.z);
        self.pitch = clamp_pitch(d.y.atan2(d.x.hypot(d.z)));
        self.speed = (2.0 * eye.y.abs()).clamp(10.0, SPEED_RANGE.1);
        self.at_home = true;
    }

    /// Level the view with the horizon (key H), keeping position and heading.
    pub fn look_at_horizon(&mut self) {
        self.pitch = 0.0;
        self.at_home = false;
    }

    /// Sets whether a flight key is held.
    pub fn set_held(&mut self, motion: Motion, down: bool) {
        self.held[motion.index()] = down;
    }

    /// Releases every key (the window lost focus: keys released elsewhere never arrive).
    pub fn release_all(&mut self) {
        self.held = [false; 6];
        self.boost = false;
    }

    /// Whether any flight key is held.
    pub fn is_moving(&self) -> bool {
        self.held.iter().any(|&h| h)
    }

    /// Turns the view by a mouse motion of (dx, dy) pixels (x right, y down). Non-finite
    /// input is ignored.
    pub fn look(&mut self, dx: f64, dy: f64) {
        if !(dx.is_finite() && dy.is_finite()) || (dx == 0.0 && dy == 0.0) {
            return;
        }
        self.yaw = (self.yaw + dx * self.sensitivity).rem_euclid(std::f64::consts::TAU);
        self.pitch = clamp_pitch(self.pitch - dy * self.sensitivity);
        self.at_home = false;
    }

    /// Changes the speed by [`SCROLL_FACTOR`] per step (positive = faster), within
    /// [`SPEED_RANGE`].
    pub fn scroll(&mut self, steps: f64) {
        if steps.is_finite() {
            self.speed =
                (self.speed * SCROLL_FACTOR.powf(steps)).clamp(SPEED_RANGE.0, SPEED_RANGE.1);
        }
    }

    /// The unit view direction.
    pub fn forward(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        let (sp, cp) = self.pitch.sin_cos();
        DVec3::new(sy * cp, sp, -cy * cp)
    }

    /// The unit level direction to the right of the view.
    pub fn right(&self) -> DVec3 {
        let (sy, cy) = self.yaw.sin_cos();
        DVec3::new(cy, 0.0, sy)
    }

    /// Moves by the held keys over `dt` seconds (clamped to [0, [`MAX_STEP_S`]]). Opposite
    /// keys cancel; diagonal flight is no faster than straight flight.
    pub fn update(&mut self, dt: f64) {
        let dt = if dt.is_finite() { dt.clamp(0.0, MAX_STEP_S) } else { 0.0 };
        let mut v = DVec3::ZERO;
        for m in Motion::ALL {
            if !self.held[m.index()] {
                continue;
            }
            v += match m {
                Motion::Forward => self.forward(),
                Motion::Back => -self.forward(),
                Motion::Right => self.right(),
                Motion::Left => -self.right(),
                Motion::Up => DVec3::Y,
                Motion::Down => -DVec3::Y,
            };
        }
        let len = v.length();
        if len < 1e-12 || dt == 0.0 {
            return;
        }
        let speed = if self.boost { self.speed * BOOST } else { self.speed };
        self.position += v / len * speed * dt;
        self.at_home = false;
    }

    /// Writes the view into a scene's camera (position and look-at; size, field of view and
    /// exposure untouched). Until the first move, the scene's own camera.
    pub fn apply(&self, camera: &mut scene::Camera) {
        if self.at_home {
            camera.position = self.home.position;
            camera.look_at = self.home.look_at;
            return;
        }
        // 100 m ahead: far enough that the look-at differs from the eye in f64 even a
        // million metres out.
        camera.position = self.position.to_array();
        camera.look_at = (self.position + 100.0 * self.forward()).to_array();
    }
}

fn clamp_pitch(p: f64) -> f64 {
    let max = MAX_PITCH_DEG.to_radians();
    p.clamp(-max, max)
}
