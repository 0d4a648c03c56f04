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
//! # Live animations
//!
//! A live animation (the viewer, an embedding program: `crate::graph::FrameState::
//! with_carried_boats`) does have a history, and re-running the settle window every frame
//! would cost it [`SETTLE_STEPS`] sub-steps a frame: its first frame settles the boats, and
//! each later one carries them on from the previous frame's time ([`ObjectPoses::carried`]).
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
    Ok(settle_boat(o, sea, t, steps)?.pose())
}

/// [`settle`]'s boat itself, at time `t`, to be stepped on (a live animation's first frame).
fn settle_boat(o: &Object, sea: &SurfaceSource<'_>, t: f64, steps: usize) -> crate::Result<Boat> {
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
    Ok(boat)
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

    /// The poses of a live animation's frame at time `t`: `run`'s boats continued from the
    /// time they are at to `t` when they ride this scene and plan and `t` is later by at most
    /// the settle window, else (a first frame, a jump back or far ahead, another scene) the
    /// boats settled as [`Self::at`] settles them; `run` keeps them for the next frame.
    ///
    /// Continuing takes ⌈Δt / h⌉ sub-steps of equal length (h the boat's longest,
    /// [`BoatParams::max_substep_s`]), each on the surface at its start, as the settle run
    /// steps: one or two at 60 frames a second, where a settle run takes [`SETTLE_STEPS`].
    /// The poses so continued are those of one boat riding the frames' times, which a still
    /// frame's settle run approaches (module doc) but does not equal.
    ///
    /// # Errors
    /// As [`Self::at`].
    pub fn carried(
        scene: &Scene,
        plan: &FramePlan,
        t: f64,
        run: &mut Option<BoatRun>,
    ) -> crate::Result<Self> {
        if !scene.objects.iter().any(|o| start(o).is_some()) {
            *run = None;
            return Ok(Self { poses: vec![None; scene.objects.len()] });
        }
        let key = BoatRun::key(scene, plan);
        let mut current = run.take().filter(|r| r.key == key);
        if let Some(r) = current.as_ref().filter(|r| r.time_s == t) {
            let poses = r.poses();
            *run = current;
            return Ok(poses);
        }
        // The sea's time-free part (an FFT's modes: 1.1 ms of `coastal_boat`'s frame) is
        // made once per run.
        let sea = match current.as_mut().and_then(|r| r.sea.take()) {
            Some((sea, damped_m)) => SurfaceSource { scene, sea, damped_m },
            None => SurfaceSource::new(scene, plan)?,
        };
        if let Some(mut r) = current {
            let dt = t - r.time_s;
            let window = r.boats.iter().flatten().map(|b| settle_window_s(b.params()));
            if dt > 0.0 && window.fold(f64::INFINITY, f64::min) >= dt {
                r.continue_to(&sea, t)?;
                r.sea = BoatRun::keep(sea);
                let poses = r.poses();
                *run = Some(r);
                return Ok(poses);
            }
        }
        let boats = scene
            .objects
            .par_iter()
            .map(|o| start(o).map(|_| settle_boat(o, &sea, t, SETTLE_STEPS)).transpose())
            .collect::<crate::Result<Vec<_>>>()?;
        let fresh = BoatRun { key, time_s: t, boats, sea: BoatRun::keep(sea) };
        let poses = fresh.poses();
        *run = Some(fresh);
        Ok(poses)
    }

    /// The pose object `index` (that is `o`) is drawn at: its entry, else, for a boat, its
    /// [`resting_pose`]; `None` for the other kinds.
    pub fn of(&self, index: usize, o: &Object) -> Option<BoatPose> {
        self.get(index).copied().or_else(|| resting_pose(o))
    }
}

/// The boats of a live animation, carried from one frame to the next
/// ([`ObjectPoses::carried`]; `crate::graph::FrameState` holds one).
pub struct BoatRun {
    key: RunKey,
    /// The time they are at, s.
    time_s: f64,
    /// Indexed as the scene's objects.
    boats: Vec<Option<Boat>>,
    /// The height query's sea and damping wavelength, kept where they do not depend on the
    /// scene's time (not under waves `coastal`, whose sea is made at a time).
    sea: Option<(super::Sea, Option<f64>)>,
}

/// What the boats of a [`BoatRun`] ride: the scene with its sea time and camera set aside
/// (neither moves a boat) and its floor's relief compared by identity (comparing its texels
/// every frame would cost more than the step it saves), and the plan's techniques.
#[derive(PartialEq)]
struct RunKey {
    scene: Scene,
    relief: crate::terrain::SameRelief,
    techniques: crate::technique::Techniques,
}

impl BoatRun {
    fn key(scene: &Scene, plan: &FramePlan) -> RunKey {
        let mut s = scene.clone();
        s.ocean.time_s = 0.0;
        s.camera = Default::default();
        let relief = s.terrain.as_mut().and_then(|t| t.relief.take());
        RunKey { scene: s, relief: crate::terrain::SameRelief(relief), techniques: plan.techniques }
    }

    fn keep(sea: SurfaceSource<'_>) -> Option<(super::Sea, Option<f64>)> {
        (!matches!(sea.sea, super::Sea::Coastal(_))).then_some((sea.sea, sea.damped_m))
    }

    fn poses(&self) -> ObjectPoses {
        ObjectPoses { poses: self.boats.iter().map(|b| b.as_ref().map(Boat::pose)).collect() }
    }

    /// Every boat stepped from `self.time_s` to `t` (> it) in equal sub-steps no longer than
    /// the boat's longest, each on the surface at its start.
    fn continue_to(&mut self, sea: &SurfaceSource<'_>, t: f64) -> crate::Result<()> {
        let t0 = self.time_s;
        let dt = t - t0;
        for boat in self.boats.iter_mut().flatten() {
            let n = (dt / boat.params().max_substep_s()).ceil().max(1.0) as usize;
            let h = dt / n as f64;
            for k in 0..n {
                boat.step(&sea.at(t0 + k as f64 * h)?, h);
            }
        }
        self.time_s = t;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::OutputKind;
    use crate::technique::System;

    fn coastal() -> (Scene, FramePlan) {
        let s = Scene::builtin_for(System::Coastal).with_system(System::Coastal).unwrap();
        let plan = FramePlan::new(&s, OutputKind::Ldr);
        assert!(s.objects.iter().any(|o| start(o).is_some()), "the coastal scene has a boat");
        (s, plan)
    }

    fn boat_pose(p: &ObjectPoses) -> BoatPose {
        *p.poses.iter().flatten().next().expect("a boat")
    }

    /// The carrying rule written out: `boat` stepped from `a` to `b` in ⌈(b − a)/h⌉ equal
    /// sub-steps, each on `sea` at its start.
    fn step_by_hand(boat: &mut Boat, sea: &SurfaceSource<'_>, a: f64, b: f64) {
        let n = ((b - a) / boat.params().max_substep_s()).ceil().max(1.0) as usize;
        let h = (b - a) / n as f64;
        for k in 0..n {
            boat.step(&sea.at(a + k as f64 * h).unwrap(), h);
        }
    }

    /// A live run's first frame is the still frame's settle run; the next frame is that
    /// boat stepped on by Δt in sub-steps of at most h on the surface at each's start (the
    /// same boat stepped here by hand), not a settle run of its own; a frame at the same time
    /// is the same poses.
    #[test]
    fn a_live_frame_continues_the_previous_frames_boat() {
        let (s, plan) = coastal();
        let t0 = s.ocean.time_s;
        let mut run = None;
        let first = ObjectPoses::carried(&s, &plan, t0, &mut run).unwrap();
        assert_eq!(first, ObjectPoses::at(&s, &plan, t0).unwrap());

        let t1 = t0 + 1.0 / 60.0;
        let second = ObjectPoses::carried(&s, &plan, t1, &mut run).unwrap();
        let sea = SurfaceSource::new(&s, &plan).unwrap();
        let o = s.objects.iter().find(|o| start(o).is_some()).unwrap();
        let mut by_hand = settle_boat(o, &sea, t0, SETTLE_STEPS).unwrap();
        step_by_hand(&mut by_hand, &sea, t0, t1);
        assert_eq!(boat_pose(&second), by_hand.pose());
        // The control: a settle run at t1 is another computation, and gives another pose.
        let settled = boat_pose(&ObjectPoses::at(&s, &plan, t1).unwrap());
        assert_ne!(boat_pose(&second), settled);
        assert_eq!(ObjectPoses::carried(&s, &plan, t1, &mut run).unwrap(), second);
    }

    /// Under FFT waves the run keeps the sea's modes from frame to frame: the poses are
    /// those of the same boat stepped on a sea made afresh each frame.
    #[test]
    fn a_kept_fft_sea_steps_the_boat_as_a_fresh_one() {
        let (coast, _) = coastal();
        let mut s = Scene::builtin_for(System::Hu).with_system(System::Hu).unwrap();
        s.ocean.resolution = 32;
        s.objects = coast.objects.iter().filter(|o| start(o).is_some()).cloned().collect();
        let plan = FramePlan::new(&s, OutputKind::Ldr);
        let sea = SurfaceSource::new(&s, &plan).unwrap();
        assert!(matches!(sea.sea, super::super::Sea::Fft { .. }));
        let t0 = s.ocean.time_s;
        let mut run = None;
        ObjectPoses::carried(&s, &plan, t0, &mut run).unwrap();
        assert!(run.as_ref().is_some_and(|r| r.sea.is_some()), "the FFT sea is kept");
        let mut by_hand = settle_boat(&s.objects[0], &sea, t0, SETTLE_STEPS).unwrap();
        for f in 1..=3 {
            let (a, b) = (t0 + f64::from(f - 1) / 30.0, t0 + f64::from(f) / 30.0);
            step_by_hand(&mut by_hand, &SurfaceSource::new(&s, &plan).unwrap(), a, b);
            let live = ObjectPoses::carried(&s, &plan, b, &mut run).unwrap();
            assert_eq!(boat_pose(&live), by_hand.pose(), "frame {f}");
        }
    }

    /// A jump back in time, a jump past the settle window, or another scene settles afresh:
    /// the poses are the still frame's.
    #[test]
    fn a_jump_or_another_scene_settles_afresh() {
        let (s, plan) = coastal();
        let t0 = s.ocean.time_s;
        let mut run = None;
        ObjectPoses::carried(&s, &plan, t0, &mut run).unwrap();
        ObjectPoses::carried(&s, &plan, t0 + 0.1, &mut run).unwrap();
        let back = t0 + 0.05;
        assert_eq!(
            ObjectPoses::carried(&s, &plan, back, &mut run).unwrap(),
            ObjectPoses::at(&s, &plan, back).unwrap()
        );
        let far = back + 60.0;
        assert_eq!(
            ObjectPoses::carried(&s, &plan, far, &mut run).unwrap(),
            ObjectPoses::at(&s, &plan, far).unwrap()
        );
        let mut moved = s.clone();
        moved.ocean.wind_speed *= 1.5;
        let next = far + 1.0 / 60.0;
        assert_eq!(
            ObjectPoses::carried(&moved, &plan, next, &mut run).unwrap(),
            ObjectPoses::at(&moved, &plan, next).unwrap()
        );
        // Another camera or sea time alone is the same run: it continues.
        let mut looked = moved.clone();
        looked.camera.position[0] += 5.0;
        looked.ocean.time_s += 3.0;
        let later = next + 1.0 / 60.0;
        assert_ne!(
            ObjectPoses::carried(&looked, &plan, later, &mut run).unwrap(),
            ObjectPoses::at(&looked, &plan, later).unwrap()
        );
    }

    /// Ten seconds of 60 frames a second: the carried boat stays finite, afloat and near
    /// where a still frame's settle run puts it (the two differ by what no force restores,
    /// the drift, and by the rest of the settle's start that has not decayed).
    #[test]
    fn ten_seconds_of_live_frames_stay_near_the_settled_boat() {
        let (s, plan) = coastal();
        let t0 = s.ocean.time_s;
        let mut run = None;
        let (mut worst, mut tilt) = (0.0f64, 0.0f64);
        for n in 0..=600 {
            let t = t0 + f64::from(n) / 60.0;
            let live = boat_pose(&ObjectPoses::carried(&s, &plan, t, &mut run).unwrap());
            assert!(live.position.is_finite() && live.up.is_finite(), "frame {n}");
            if n % 100 == 0 {
                let still = boat_pose(&ObjectPoses::at(&s, &plan, t).unwrap());
                worst = worst.max((live.position - still.position).length());
                tilt = tilt.max(live.up.dot(still.up).clamp(-1.0, 1.0).acos().to_degrees());
            }
        }
        println!("carried against settled over 10 s: at most {worst:.4} m and {tilt:.3}° apart");
        // Measured 3.5 cm and 0.51°; the bound is the settle's documented drift (7 mm to
        // 4 cm, module doc) with room, and a few times the tilt, so a carried boat that
        // wanders or capsizes fails.
        assert!(worst < 0.1 && tilt < 2.0, "{worst} m, {tilt}°");
    }
}
