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

use glam::{DMat4, DVec3};
use rayon::prelude::*;

use super::SurfaceSource;
use crate::floating::{Boat, BoatParams, BoatPose, MAX_PHASE_PER_SUBSTEP, WaterHeight};
use crate::plan::FramePlan;
use crate::scene::{Object, Scene, Shape};

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

/// The bow's share of the hull's length: the last 30 % narrows from the full beam to a
/// point on the centre line.
pub const BOW_SHARE: f64 = 0.3;

/// Triangles of one hull: the deck and the keel (pentagons, 3 each) and five sides (2 each).
pub const HULL_TRIANGLES: u32 = 16;

/// The settle window W of a boat, s: [`SETTLE_STEPS`] of its longest sub-step.
pub fn settle_window_s(params: &BoatParams) -> f64 {
    SETTLE_STEPS as f64 * params.max_substep_s()
}

/// The heave periods 2π/ω in the settle window: SETTLE_STEPS · 0.2 / 2π, the same for every
/// boat.
pub fn settle_periods() -> f64 {
    SETTLE_STEPS as f64 * MAX_PHASE_PER_SUBSTEP / std::f64::consts::TAU
}

/// Where a boat starts: its start point's (x, z) and its heading as [`BoatPose`]'s yaw.
fn start(o: &Object) -> Option<(BoatParams, f64, f64, f64)> {
    match o.shape()? {
        Shape::Boat { heading_deg, .. } => {
            // heading_deg turns from +x towards +z, clockwise seen from above; yaw turns the
            // bow to port, anticlockwise: the same angle with the other sign.
            Some((o.boat_params()?, o.center[0], o.center[2], -heading_deg.to_radians()))
        }
        _ => None,
    }
}

/// A boat at rest on still water at y = 0: level, its keel at its draft, at its start point
/// and heading. What the planner, which knows no time, takes for its place (the spray's
/// emitters), and what a boat is drawn at when no pose is given.
pub fn resting_pose(o: &Object) -> Option<BoatPose> {
    let (p, x, z, yaw) = start(o)?;
    Some(BoatPose::from_angles(DVec3::new(x, -p.still_water_draft_m(), z), yaw, 0.0, 0.0))
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
/// Made once per frame (`crate::plan::FrameInputs`) and read by every object pass.
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

/// The hull's outline seen from above, body frame (x forward, z starboard) on the keel
/// plane: stern port, stern starboard, starboard shoulder, bow, port shoulder.
fn outline(length_m: f64, beam_m: f64) -> [DVec3; 5] {
    let (hl, hb) = (0.5 * length_m, 0.5 * beam_m);
    let shoulder = hl - BOW_SHARE * length_m;
    [
        DVec3::new(-hl, 0.0, -hb),
        DVec3::new(-hl, 0.0, hb),
        DVec3::new(shoulder, 0.0, hb),
        DVec3::new(hl, 0.0, 0.0),
        DVec3::new(shoulder, 0.0, -hb),
    ]
}

/// The hull's faces in the body frame ([`BoatPose`]'s: origin the keel's centre, x forward,
/// y up, z starboard): each a convex polygon counter-clockwise seen from outside, with its
/// outward normal. A prism: the outline (a box with a pointed bow, [`BOW_SHARE`]) extruded
/// from the keel plane y = 0 up to the deck at the hull depth. Its volume is
/// B·H·(L − BOW_SHARE·L/2).
pub fn hull_faces(size: [f64; 3]) -> Vec<(DVec3, Vec<DVec3>)> {
    let [length, depth, beam] = size;
    let keel = outline(length, beam);
    let up = DVec3::new(0.0, depth, 0.0);
    let deck: Vec<DVec3> = keel.iter().map(|&p| p + up).collect();
    let mut faces = vec![(DVec3::Y, deck), (DVec3::NEG_Y, keel.to_vec())];
    for i in 0..keel.len() {
        let (a, b) = (keel[i], keel[(i + 1) % keel.len()]);
        let edge = b - a;
        // The outline's centroid is inside and the polygon convex: the outward normal is the
        // edge's horizontal perpendicular that points away from it.
        let mut n = DVec3::new(edge.z, 0.0, -edge.x).normalize();
        if n.dot(a) < 0.0 {
            n = -n;
        }
        faces.push((n, vec![a, b, b + up, a + up]));
    }
    // Wind each face counter-clockwise seen from outside (Newell's normal along the outward).
    for (n, poly) in &mut faces {
        let newell = (0..poly.len())
            .map(|i| poly[i].cross(poly[(i + 1) % poly.len()]))
            .fold(DVec3::ZERO, |s, c| s + c);
        if newell.dot(*n) < 0.0 {
            poly.reverse();
        }
    }
    faces
}

/// The hull's triangles in the world at `pose`: each face fanned from its first corner, the
/// corners through [`BoatPose::model_matrix`], the normals through its rotation.
pub fn hull_triangles(size: [f64; 3], pose: &BoatPose) -> Vec<([DVec3; 3], DVec3)> {
    let m: DMat4 = pose.model_matrix();
    let mut tris = Vec::new();
    for (n, poly) in hull_faces(size) {
        let n = m.transform_vector3(n);
        let w: Vec<DVec3> = poly.iter().map(|&p| m.transform_point3(p)).collect();
        for i in 1..w.len() - 1 {
            tris.push(([w[0], w[i], w[i + 1]], n));
        }
    }
    tris
}

/// The world box of a hull at `pose` (its ten corners'), m.
pub fn hull_bounds(size: [f64; 3], pose: &BoatPose) -> (DVec3, DVec3) {
    let m = pose.model_matrix();
    let up = DVec3::new(0.0, size[1], 0.0);
    outline(size[0], size[2])
        .iter()
        .flat_map(|&p| [p, p + up])
        .map(|p| m.transform_point3(p))
        .fold((DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)), |(lo, hi), p| {
            (lo.min(p), hi.max(p))
        })
}
