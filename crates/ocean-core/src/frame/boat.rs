//! The boats of a scene (`[[objects]] kind = "boat"`): where each floats at a frame's time
//! and the hull both back ends draw there.
//!
//! # The pose at time t
//!
//! A frame has no history (`ocean render` draws one time; the viewer may jump), so a boat's
//! pose is a pure function of the scene and t: the boat is started at rest, level, heading
//! along `heading_deg`, with its keel at its still-water draft below the surface above its
//! start point at time t − W, and [`crate::floating::Boat`] is stepped to t on the scene's
//! height query ([`super::SurfaceSource`], the surface the picture draws), one sub-step of
//! the longest length the model allows ([`BoatParams::max_substep_s`], 0.2/ω) per surface,
//! [`SETTLE_STEPS`] of them. The start is a guess (the water is moving, the trim is not the
//! engine's); what the guess gets wrong decays like any disturbance of the boat, and W is many
//! of its heave periods. With the damping of [`BoatParams::launch`] (the default launch's
//! ratio to ω at every size) a release loses ~95 % of its energy per heave period
//! (`crates/ocean-core/tests/floating.rs`), so after W ≈ 4 periods what is left of the
//! start's error is ~10⁻⁵ of its energy, ~10⁻³ of its amplitude: the pose is that of a boat
//! that has been riding these waves.
//!
//! Why W is counted in the boat's periods and not in seconds: how fast a start is forgotten
//! is the boat's own time (√(d/g), d its draft), so a fixed number of periods settles every
//! size equally, and it fixes the cost: [`SETTLE_STEPS`] surfaces and 5 height queries on
//! each, whatever the boat.
//!
//! Every step is plain f64 arithmetic in a fixed order on one thread (boats are settled in
//! parallel, each on its own), so the pose is bit-identical on every run and thread count.

use glam::DVec3;
use rayon::prelude::*;

use super::SurfaceSource;
use crate::floating::{Boat, BoatParams, BoatPose, MAX_PHASE_PER_SUBSTEP, WaterHeight};
use crate::objects::start;
pub use crate::objects::{
    BOW_SHARE, HULL_TRIANGLES, hull_bounds, hull_faces, hull_triangles, resting_pose,
};
use crate::plan::FramePlan;
use crate::scene::{Object, Scene};

/// Sub-steps of a boat's settle run: W = SETTLE_STEPS · 0.2/ω ≈ 4.1 heave periods 2π/ω
/// (3.5 s for the default 6 m launch). Measured against a run 6 times longer (768 steps), the
/// 6 m launch on `welch_calm_day` and `coastal_boat`: the boat's up axis differs by 5e-4 and
/// 1.6e-4 (32 steps: 1.5e-2 and 1.5e-2, 64: 2.9e-3 and 1.5e-3), and more steps do not bring
/// it much closer (256: 1.3e-4 on `coastal_boat`): what is left is mostly the drift, the
/// boat's horizontal place and heading, which no force restores and which so depend on the
/// whole run (7 mm to 4 cm, up to 1e-3 rad). At 128² under shading
/// `chiu` (`coastal_boat`) the run costs 0.54 s a frame on one core, 0.38 s on two (5 height
/// queries a sub-step at ~1 ms each; docs/coastal.md, "A boat in a scene").
pub const SETTLE_STEPS: usize = 128;

/// The settle window W of a boat, s: [`SETTLE_STEPS`] of its longest sub-step.
pub fn settle_window_s(params: &BoatParams) -> f64 {
    SETTLE_STEPS as f64 * params.max_substep_s()
}

/// The heave periods 2π/ω in the settle window: SETTLE_STEPS · 0.2 / 2π, the same for every
/// boat.
pub fn settle_periods() -> f64 {
    SETTLE_STEPS as f64 * MAX_PHASE_PER_SUBSTEP / std::f64::consts::TAU
}

/// The pose of boat `o` at time `t` on the sea of `sea` (module doc).
///
/// # Errors
/// The boat is not valid (a scene that passed validation never has one) or a surface cannot
/// be made (a non-finite time).
pub fn settled_pose(o: &Object, sea: &SurfaceSource<'_>, t: f64) -> crate::Result<BoatPose> {
    settle(o, sea, t, SETTLE_STEPS)
}

/// [`settled_pose`] with a window of `steps` sub-steps instead of [`SETTLE_STEPS`]: how a
/// test sees that the window is long enough (a longer one must give the same pose).
///
/// # Errors
/// As [`settled_pose`].
pub fn settle(
    o: &Object,
    sea: &SurfaceSource<'_>,
    t: f64,
    steps: usize,
) -> crate::Result<BoatPose> {
    let Some((params, x, z, yaw)) = start(o) else {
        return Err(crate::Error::InvalidParameter {
            name: "object kind",
            value: f64::NAN,
            reason: "only a boat has a settled pose".into(),
        });
    };
    let h = params.max_substep_s();
    let n = steps.max(1);
    // Each step's time from t, so the last step ends on t itself (a running sum would carry
    // n round-offs).
    let time = |k: usize| t - (n - k) as f64 * h;
    let water = sea.at(time(0))?;
    let eta = water.water_height(x, z);
    // A sea with no height here (never for the scene's waves) starts the boat on y = 0.
    let eta = if eta.is_finite() { eta } else { 0.0 };
    let keel = DVec3::new(x, eta - params.still_water_draft_m(), z);
    let mut boat = Boat::new(params, &BoatPose::from_angles(keel, yaw, 0.0, 0.0), time(0))?;
    boat.step(&water, h);
    for k in 1..n {
        boat.step(&sea.at(time(k))?, h);
    }
    Ok(boat.pose())
}

/// Where each object of a scene is in one frame: the settled pose of every boat
/// ([`settled_pose`]), nothing for the other kinds (they stand where the scene puts them).
/// Made once per frame (`crate::graph::FrameInputs`) and read by every object pass.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjectPoses {
    poses: Vec<Option<BoatPose>>,
}

impl ObjectPoses {
    /// The poses of `scene`'s boats at time `t` on the sea `plan` draws. Boats are settled in
    /// parallel, each by itself, so the result does not depend on the thread count.
    ///
    /// # Errors
    /// The sea cannot be made, or a boat cannot be settled ([`settled_pose`]).
    pub fn at(scene: &Scene, plan: &FramePlan, t: f64) -> crate::Result<Self> {
        if !scene.objects.iter().any(|o| start(o).is_some()) {
            return Ok(Self { poses: vec![None; scene.objects.len()] });
        }
        let sea = SurfaceSource::new(scene, plan)?;
        let poses = scene
            .objects
            .par_iter()
            .map(|o| start(o).map(|_| settled_pose(o, &sea, t)).transpose())
            .collect::<crate::Result<Vec<_>>>()?;
        Ok(Self { poses })
    }

    /// Given poses, indexed as the scene's objects (a caller that runs its own boats, or a
    /// test).
    pub fn from_poses(poses: Vec<Option<BoatPose>>) -> Self {
        Self { poses }
    }

    /// Every boat at its [`resting_pose`].
    pub fn resting(scene: &Scene) -> Self {
        Self { poses: scene.objects.iter().map(resting_pose).collect() }
    }

    /// The pose of object `index`; `None` for an object that is not a boat (or beyond the
    /// list).
    pub fn get(&self, index: usize) -> Option<&BoatPose> {
        self.poses.get(index).and_then(Option::as_ref)
    }

    /// The pose object `index` (that is `o`) is drawn at: its entry, else, for a boat, its
    /// [`resting_pose`]; `None` for the other kinds.
    pub fn of(&self, index: usize, o: &Object) -> Option<BoatPose> {
        self.get(index).copied().or_else(|| resting_pose(o))
    }
}
