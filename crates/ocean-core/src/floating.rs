//! Floating objects: the boat of seed 004 ("As homework I also made a ship floating and moving
//! on the water"), moved by the height query of any wave model.
//!
//! # The model
//!
//! Five point masses: the four corners of the hull's keel rectangle (length `length_m` along
//! the bow, beam `beam_m` across) and an engine point in the middle of the stern, `engine_depth_m`
//! below the keel ("1 in the middle of the back side at some lower height as an engine"). The
//! body frame and the angles are those of [`BoatPose`].
//!
//! Forces, per point:
//! - gravity, m·g, on all five (the engine's mass is part of the boat's);
//! - buoyancy on a corner, upwards: each corner stands for a quarter of the waterplane,
//!   A_c = L·B/4, and for the column of hull above it, up to the hull's depth H (keel to deck).
//!   With d = η(x, z) − y its depth below the surface, the displaced volume is A_c·clamp(d, 0, H)
//!   and the force ρ·g·A_c·clamp(d, 0, H): Archimedes for a box hull, exact on still water
//!   (where the corners' mean depth is the keel's mean depth), zero above the water, and
//!   capped once the column is fully under, so a corner started deep or overrun by an enormous
//!   wave gets a bounded push (a full box, not a spring that grows without end);
//! - damping on a corner under water, proportional to the submerged share s = clamp(d/H, 0, 1)
//!   of its column: −m·s·(c_v·v_y, c_h·v_x, c_h·v_z). Vertical (heave) damping is strong — a
//!   hull moving up and down makes waves and pushes water — and horizontal drag weak, so the
//!   boat rides the swell without bouncing yet still glides forward. The share s makes the
//!   force start from zero at the waterline rather than switch on, so a corner skimming the
//!   surface is not kicked from step to step. The query gives heights only, so the damping is
//!   against the still-water frame (no orbital velocity, no drift);
//! - the engine's thrust, on the engine point, along the boat's forward axis turned by the
//!   steering angle about its up axis, and only while the engine point is under water (a
//!   propeller in the air pushes nothing). Thrust low in the stern, below the centre of mass,
//!   lifts the bow when it drives the boat ahead and dips it when it brakes (throttle astern):
//!   "This makes the front of the boot going up if you accelerate and going down if you
//!   decelerate".
//!
//! Nine pairwise distances of the five points are held at their rest lengths ("to hold the
//! ship together … replace each vertex according to the coordinates of the other vertices in
//! more iterations"): the keel rectangle's sides and a diagonal, and the engine to every
//! corner. With the engine off the keel plane that is rigid with no pair to spare, so the five
//! points move as one body (`constraints` says why these nine).
//!
//! # Integration
//!
//! One sub-step of length h, the same every time:
//! 1. damping, applied implicitly to the velocity the body has: v ← v/(1 + c·s·h) per axis —
//!    exact in the limit, never reverses the velocity, and unconditionally stable however
//!    large c·h (the explicit v −= c·s·h·v overshoots once c·s·h > 1 and diverges past 2);
//! 2. the other forces at the current positions: v += h·F/m (semi-implicit Euler: the
//!    velocity first, then the position from the new velocity — symplectic, so the undamped
//!    buoyancy oscillation neither grows nor decays numerically, and stable while ω·h < 2);
//! 3. velocities projected onto the constraints: every pair's relative velocity along its axis
//!    removed, by equal and opposite impulses shared by inverse mass, in one linear solve
//!    (`constraints`). Such impulses keep momentum and angular momentum and never add
//!    kinetic energy;
//! 4. x += h·v;
//! 5. positions projected onto the constraints (position-based dynamics, Müller et al. 2007,
//!    with the pairs solved together: [`POSITION_ITERATIONS`] Newton steps), to remove the
//!    drift of the rotation's first-order step.
//!
//! Projecting velocity and position separately (SHAKE/RATTLE rather than PBD's v = Δx/h) keeps
//! the round-off of the position projection out of the velocity: with v = Δx/h a 10⁻¹⁶ m
//! correction over a tiny h would become an enormous speed. Damping before the other forces
//! (rather than after) matters at rest: the impulse a corner passes on through the
//! constraints (holding the engine up) must not be damped, or the boat settles off its
//! equilibrium (deeper by m_e·g·c·s·h/(ρ g L B), 0.6 mm at 60 Hz).
//!
//! A frame of length Δt is split into n = ⌈Δt/h_max⌉ equal sub-steps, h_max =
//! [`MAX_PHASE_PER_SUBSTEP`]/ω with ω = √(ρ g A_c / m_c) the fastest buoyancy oscillation of a
//! corner; n is capped at [`MAX_SUBSTEPS`], and a frame longer than MAX_SUBSTEPS·h_max is
//! simulated for that long only (the boat slows down rather than blowing up, as a game caps its
//! frame time). All sub-steps of a frame use the frame's surface: the query is of one time.
//!
//! Everything is plain f64 arithmetic in a fixed order, with no threads: a step is a pure
//! function of the state, the surface and Δt, and n frames are bit-identical on every run.

mod constraints;
mod pose;

use glam::DVec3;

use constraints::PAIRS;
pub use constraints::POSITION_ITERATIONS;
pub use pose::BoatPose;

use crate::{Error, GRAVITY, Result};

/// Density of sea water at the surface, kg/m³ (UNESCO 1981 at 35 ‰ and about 15 °C).
pub const SEA_WATER_DENSITY_KG_M3: f64 = 1025.0;

/// ω·h of the longest sub-step: a tenth of semi-implicit Euler's stability limit (ω·h < 2),
/// where its frequency error, ≈ (ω h)²/24, is 0.17 %.
pub const MAX_PHASE_PER_SUBSTEP: f64 = 0.2;

/// The most sub-steps of one [`Boat::step`]; a longer frame is simulated for
/// MAX_SUBSTEPS·h_max only (module doc). 1024 sub-steps is a few seconds of simulated time
/// for a small boat, and bounds the cost of a frame.
pub const MAX_SUBSTEPS: usize = 1024;

/// Which point is which: the four corners, then the engine.
const BOW_PORT: usize = 0;
const BOW_STARBOARD: usize = 1;
const STERN_STARBOARD: usize = 2;
const STERN_PORT: usize = 3;
const ENGINE: usize = 4;
const POINTS: usize = 5;

/// The height of the water surface above a world point (x, z), m: what a floating body asks
/// of a wave model. Implemented for [`crate::waves::WaveSurface`] (any waves technique, via
/// [`crate::frame::surface_query`]) and for any `Fn(f64, f64) -> f64`.
pub trait WaterHeight {
    /// The surface height η above (x, z), m. A non-finite value means "no water here": the
    /// point gets no buoyancy, damping or thrust (it falls).
    fn water_height(&self, x: f64, z: f64) -> f64;

    /// [`Self::water_height`] of each of the five points' (x, z), in order: what one sub-step
    /// asks. A surface whose query is costly may answer the points in parallel; each answer
    /// must still be exactly its `water_height`, so the boat does not depend on how.
    fn water_heights(&self, points: &[(f64, f64); 5]) -> [f64; 5] {
        points.map(|(x, z)| self.water_height(x, z))
    }
}

impl<F: Fn(f64, f64) -> f64 + ?Sized> WaterHeight for F {
    fn water_height(&self, x: f64, z: f64) -> f64 {
        self(x, z)
    }
}

impl WaterHeight for crate::waves::WaveSurface {
    fn water_height(&self, x: f64, z: f64) -> f64 {
        self.height_at(x, z)
    }

    /// Waves `fft`: the points in parallel. A point's query sums every mode several times (the
    /// displacement's inversion, ~1 ms at 128², `frame::ObjectPoses`), and each is the same
    /// sequential sum on whichever thread, so the heights are bit-identical to one by one.
    fn water_heights(&self, points: &[(f64, f64); 5]) -> [f64; 5] {
        use rayon::prelude::*;
        match self {
            Self::Fft(_) | Self::Damped { .. } => {
                let mut out = [0.0; 5];
                out.par_iter_mut()
                    .zip(points.par_iter())
                    .for_each(|(h, &(x, z))| *h = self.height_at(x, z));
                out
            }
            Self::Gerstner(_) | Self::Coastal(_) => points.map(|(x, z)| self.height_at(x, z)),
        }
    }
}

impl WaterHeight for crate::waves::gerstner::GerstnerSea {
    fn water_height(&self, x: f64, z: f64) -> f64 {
        self.height_at(x, z)
    }
}

/// The boat's build: dimensions, masses and the water's response. SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoatParams {
    /// Keel length, bow to stern, m (the corners' spacing along the forward axis).
    pub length_m: f64,
    /// Keel width, port to starboard, m.
    pub beam_m: f64,
    /// Hull depth H, keel to deck, m: a corner's buoyancy stops growing once it is this deep.
    pub hull_depth_m: f64,
    /// Total mass, kg, engine included.
    pub mass_kg: f64,
    /// The engine point's share of the mass, kg (0 < engine < total); the rest is split
    /// evenly over the corners.
    pub engine_mass_kg: f64,
    /// How far below the keel plane the engine point (propeller) sits, m (> 0, so that the
    /// five points do not lie in one plane and the constraints make them rigid).
    pub engine_depth_m: f64,
    /// Water density ρ, kg/m³.
    pub water_density_kg_m3: f64,
    /// Vertical damping rate of a fully submerged corner, 1/s.
    pub heave_damping_per_s: f64,
    /// Horizontal damping (drag) rate of a fully submerged corner, 1/s.
    pub drag_per_s: f64,
    /// The engine's greatest thrust, N (throttle ±1).
    pub max_thrust_n: f64,
    /// The greatest steering angle, rad, in [0, π/2].
    pub max_steer_rad: f64,
}

impl Default for BoatParams {
    /// A 6 m × 2.5 m launch of 3 t: draft M/(ρ L B) = 0.195 m on still water, heave period
    /// 2π√(d/g) ≈ 0.89 s, heave damping ratio ζ ≈ c_v·(d/H)/(2ω) ≈ 0.3, top speed ≈ 7 m/s.
    fn default() -> Self {
        Self {
            length_m: 6.0,
            beam_m: 2.5,
            hull_depth_m: 1.0,
            mass_kg: 3000.0,
            engine_mass_kg: 150.0,
            engine_depth_m: 0.6,
            water_density_kg_m3: SEA_WATER_DENSITY_KG_M3,
            heave_damping_per_s: 20.0,
            drag_per_s: 1.0,
            max_thrust_n: 4000.0,
            max_steer_rad: 0.5,
        }
    }
}

/// The default launch's loading, M/(ρ L B H): the share of its hull under water on still
/// water (d/H = 3000/(1025·6·2.5·1) ≈ 0.195); [`BoatParams::launch`]'s mass when none is
/// given.
pub const LAUNCH_LOADING: f64 = 3000.0 / (SEA_WATER_DENSITY_KG_M3 * 6.0 * 2.5 * 1.0);

impl BoatParams {
    /// The default launch made to another hull: length `length_m`, hull depth `hull_depth_m`,
    /// beam `beam_m` and mass `mass_kg` (`None`: [`LAUNCH_LOADING`] of the hull's full
    /// displacement). Every other field is the default's scaled so that the boat behaves like
    /// it in its own time: the engine keeps its share of the mass (5 %) and its depth below
    /// the keel (0.6 H); the damping rates keep their ratio to the buoyancy frequency ω
    /// (so the damping ratios, and the number of heave periods a disturbance takes to die
    /// away, are the default's); thrust keeps its ratio to the weight. This is what a scene's
    /// `kind = "boat"` object floats as (`crate::frame::ObjectPoses`).
    ///
    /// The result is not validated: [`Self::validate`] and [`Self::floats`] say whether it is a
    /// boat (a mass above ρ L B H sinks).
    pub fn launch(length_m: f64, hull_depth_m: f64, beam_m: f64, mass_kg: Option<f64>) -> Self {
        let default = Self::default();
        let water = default.water_density_kg_m3;
        let mass_kg = mass_kg.unwrap_or(LAUNCH_LOADING * water * length_m * beam_m * hull_depth_m);
        let mut p = Self {
            length_m,
            beam_m,
            hull_depth_m,
            mass_kg,
            engine_mass_kg: mass_kg * (default.engine_mass_kg / default.mass_kg),
            engine_depth_m: hull_depth_m * (default.engine_depth_m / default.hull_depth_m),
            max_thrust_n: mass_kg * (default.max_thrust_n / default.mass_kg),
            ..default
        };
        let scale = p.buoyancy_omega() / default.buoyancy_omega();
        p.heave_damping_per_s = default.heave_damping_per_s * scale;
        p.drag_per_s = default.drag_per_s * scale;
        p
    }

    /// Checks that every field is finite and in its range.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<()> {
        let positive = [
            ("boat length_m", self.length_m),
            ("boat beam_m", self.beam_m),
            ("boat hull_depth_m", self.hull_depth_m),
            ("boat mass_kg", self.mass_kg),
            ("boat engine_mass_kg", self.engine_mass_kg),
            ("boat engine_depth_m", self.engine_depth_m),
            ("boat water_density_kg_m3", self.water_density_kg_m3),
        ];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(invalid(name, value, "must be finite and positive"));
            }
        }
        let non_negative = [
            ("boat heave_damping_per_s", self.heave_damping_per_s),
            ("boat drag_per_s", self.drag_per_s),
            ("boat max_thrust_n", self.max_thrust_n),
        ];
        for (name, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(invalid(name, value, "must be finite and non-negative"));
            }
        }
        if self.engine_mass_kg >= self.mass_kg {
            return Err(invalid(
                "boat engine_mass_kg",
                self.engine_mass_kg,
                "must be below mass_kg: the corners carry the rest of the mass",
            ));
        }
        if !(0.0..=std::f64::consts::FRAC_PI_2).contains(&self.max_steer_rad) {
            return Err(invalid(
                "boat max_steer_rad",
                self.max_steer_rad,
                "must lie in [0, π/2]: past a right angle the thrust pushes backwards",
            ));
        }
        Ok(())
    }

    /// The draft on still water, m: weight = ρ·g·(L·B)·d, so d = M/(ρ L B) (Archimedes for
    /// the box hull), valid while d ≤ H (else the boat sinks: [`Self::floats`]).
    pub fn still_water_draft_m(&self) -> f64 {
        self.mass_kg / (self.water_density_kg_m3 * self.length_m * self.beam_m)
    }

    /// Whether the full hull displaces more than the boat weighs (ρ L B H > M).
    pub fn floats(&self) -> bool {
        self.still_water_draft_m() < self.hull_depth_m
    }

    /// The mass of one corner, kg.
    fn corner_mass_kg(&self) -> f64 {
        (self.mass_kg - self.engine_mass_kg) / 4.0
    }

    /// ρ·g·A_c: a corner's buoyancy per metre of depth, N/m.
    fn corner_stiffness_n_per_m(&self) -> f64 {
        self.water_density_kg_m3 * GRAVITY * self.length_m * self.beam_m / 4.0
    }

    /// The longest sub-step, s: [`MAX_PHASE_PER_SUBSTEP`]/ω, with ω = √(ρ g A_c / m_c) a
    /// corner's buoyancy frequency.
    pub fn max_substep_s(&self) -> f64 {
        MAX_PHASE_PER_SUBSTEP / self.buoyancy_omega()
    }

    /// ω = √(ρ g A_c / m_c), rad/s: the buoyancy frequency of one corner, the fastest motion
    /// the sub-step must resolve (2π/ω is about the heave period).
    pub fn buoyancy_omega(&self) -> f64 {
        (self.corner_stiffness_n_per_m() / self.corner_mass_kg()).sqrt()
    }

    /// The points in the body frame (corners on the keel plane y = 0, engine below the stern).
    fn body_points(&self) -> [DVec3; POINTS] {
        let (hl, hb) = (self.length_m / 2.0, self.beam_m / 2.0);
        let mut p = [DVec3::ZERO; POINTS];
        p[BOW_PORT] = DVec3::new(hl, 0.0, -hb);
        p[BOW_STARBOARD] = DVec3::new(hl, 0.0, hb);
        p[STERN_STARBOARD] = DVec3::new(-hl, 0.0, hb);
        p[STERN_PORT] = DVec3::new(-hl, 0.0, -hb);
        p[ENGINE] = DVec3::new(-hl, -self.engine_depth_m, 0.0);
        p
    }
}

fn invalid(name: &'static str, value: f64, reason: &str) -> Error {
    Error::InvalidParameter { name, value, reason: reason.into() }
}

/// What the helm asks of the engine. Out-of-range values are clamped when used, non-finite ones
/// read as 0 (engine idle, helm centred), so no input can make a force infinite.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BoatControls {
    /// Thrust as a share of [`BoatParams::max_thrust_n`], in [−1, 1] (negative: astern).
    pub throttle: f64,
    /// Steering angle, rad, clamped to ±[`BoatParams::max_steer_rad`]; positive turns the bow to
    /// port (yaw increases), by pushing the stern to starboard.
    pub steer_rad: f64,
}

impl BoatControls {
    /// The thrust, N, and the steering angle, rad, after the clamps.
    fn effective(&self, params: &BoatParams) -> (f64, f64) {
        let finite_or_zero = |v: f64| if v.is_finite() { v } else { 0.0 };
        let throttle = finite_or_zero(self.throttle).clamp(-1.0, 1.0);
        let steer =
            finite_or_zero(self.steer_rad).clamp(-params.max_steer_rad, params.max_steer_rad);
        (throttle * params.max_thrust_n, steer)
    }
}

/// A floating boat: its build, its five points' positions and velocities, the helm and the
/// clock. Cloning it is how a simulation is continued from a saved frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Boat {
    params: BoatParams,
    inv_mass: [f64; POINTS],
    rest_length: [f64; PAIRS.len()],
    position: [DVec3; POINTS],
    velocity: [DVec3; POINTS],
    /// The helm; read at every sub-step.
    pub controls: BoatControls,
    time_s: f64,
}

impl Boat {
    /// A boat at rest, placed at `pose` (the keel centre and the body axes), at time `time_s`.
    ///
    /// # Errors
    /// The parameters are out of range ([`BoatParams::validate`]), or the pose or the time is
    /// not finite.
    pub fn new(params: BoatParams, pose: &BoatPose, time_s: f64) -> Result<Self> {
        params.validate()?;
        for (name, v) in [
            ("boat position x", pose.position.x),
            ("boat position y", pose.position.y),
            ("boat position z", pose.position.z),
            ("boat time_s", time_s),
        ] {
            if !v.is_finite() {
                return Err(invalid(name, v, "must be finite"));
            }
        }
        // Re-orthonormalise so that any finite axes give a rigid body of the right lengths.
        let pose = BoatPose::from_axes(pose.position, pose.forward, pose.starboard);
        let body = params.body_points();
        let position = body.map(|b| pose.to_world(b));
        let rest_length = PAIRS.map(|(i, j)| (body[i] - body[j]).length());
        let corner = 1.0 / params.corner_mass_kg();
        let inv_mass = [corner, corner, corner, corner, 1.0 / params.engine_mass_kg];
        Ok(Self {
            params,
            inv_mass,
            rest_length,
            position,
            velocity: [DVec3::ZERO; POINTS],
            controls: BoatControls::default(),
            time_s,
        })
    }

    /// The boat's build.
    pub fn params(&self) -> &BoatParams {
        &self.params
    }

    /// The clock, s: the start time plus every step's Δt.
    pub fn time_s(&self) -> f64 {
        self.time_s
    }

    /// The five points' positions: bow-port, bow-starboard, stern-starboard, stern-port
    /// corners, then the engine.
    pub fn points(&self) -> [DVec3; 5] {
        self.position
    }

    /// The five points' velocities, m/s, in the order of [`Self::points`].
    pub fn velocities(&self) -> [DVec3; 5] {
        self.velocity
    }

    /// The rest lengths of the nine constraints and their current lengths, m, in a fixed
    /// order: how rigid the body has stayed.
    pub fn constraint_lengths(&self) -> [(f64, f64); 9] {
        let mut out = [(0.0, 0.0); PAIRS.len()];
        for (k, &(i, j)) in PAIRS.iter().enumerate() {
            out[k] = (self.rest_length[k], (self.position[i] - self.position[j]).length());
        }
        out
    }

    /// The centre of mass, m: Σ m p / M.
    pub fn centre_of_mass(&self) -> DVec3 {
        let mut sum = DVec3::ZERO;
        for i in 0..POINTS {
            sum += self.position[i] / self.inv_mass[i];
        }
        sum / self.params.mass_kg
    }

    /// The pose for drawing: the corners' centroid and the axes they span (forward: stern
    /// midpoint to bow midpoint; starboard: port midpoint to starboard midpoint;
    /// orthonormalised by [`BoatPose::from_axes`]).
    pub fn pose(&self) -> BoatPose {
        let p = &self.position;
        let centroid = (p[BOW_PORT] + p[BOW_STARBOARD] + p[STERN_STARBOARD] + p[STERN_PORT]) / 4.0;
        let forward = (p[BOW_PORT] + p[BOW_STARBOARD]) - (p[STERN_PORT] + p[STERN_STARBOARD]);
        let starboard = (p[BOW_STARBOARD] + p[STERN_STARBOARD]) - (p[BOW_PORT] + p[STERN_PORT]);
        BoatPose::from_axes(centroid, forward, starboard)
    }

    /// Kinetic plus potential energy, J, on still water at height `water_level_m`: Σ ½ m v² +
    /// Σ m g y + the buoyancy's potential, ρ g A_c ∫₀^d clamp(s, 0, H) ds per corner. Damping
    /// and the constraints only ever remove it, so with the engine idle it is the simulation's
    /// Lyapunov function.
    pub fn mechanical_energy(&self, water_level_m: f64) -> f64 {
        let k = self.params.corner_stiffness_n_per_m();
        let h = self.params.hull_depth_m;
        let mut energy = 0.0;
        for i in 0..POINTS {
            let m = 1.0 / self.inv_mass[i];
            energy +=
                0.5 * m * self.velocity[i].length_squared() + m * GRAVITY * self.position[i].y;
            if i != ENGINE {
                let d = water_level_m - self.position[i].y;
                energy += if d <= 0.0 {
                    0.0
                } else if d <= h {
                    0.5 * k * d * d
                } else {
                    // Past full submersion the force is constant, so the potential is linear.
                    k * h * (0.5 * h + (d - h))
                };
            }
        }
        energy
    }

    /// Advances the boat by `dt_s` on the surface `water` (the surface at this frame's time),
    /// in equal sub-steps (module doc). Returns the time actually simulated, s: `dt_s`, or
    /// less when the frame is longer than [`MAX_SUBSTEPS`] sub-steps allow. A zero, negative or
    /// non-finite `dt_s` leaves the boat unchanged and returns 0; otherwise the clock advances
    /// by `dt_s` whatever was simulated.
    pub fn step<W: WaterHeight + ?Sized>(&mut self, water: &W, dt_s: f64) -> f64 {
        if !(dt_s.is_finite() && dt_s > 0.0) {
            return 0.0;
        }
        let h_max = self.params.max_substep_s();
        // ⌈dt/h_max⌉ in f64 first: a huge dt would overflow the integer conversion.
        let wanted = (dt_s / h_max).ceil();
        let (substeps, h) = if wanted <= MAX_SUBSTEPS as f64 {
            let n = (wanted as usize).max(1);
            (n, dt_s / n as f64)
        } else {
            (MAX_SUBSTEPS, h_max)
        };
        for _ in 0..substeps {
            self.substep(water, h);
        }
        // The clock stops at the largest f64 rather than becoming infinite (only absurd steps
        // get there), so the time a surface is asked for stays finite.
        self.time_s = (self.time_s + dt_s).min(f64::MAX);
        substeps as f64 * h
    }

    /// Runs `frames` steps of `frame_dt_s`, asking `surface_at(t)` for the surface at each
    /// frame's start time t = [`Self::time_s`], and returns the pose after each frame.
    pub fn simulate<W: WaterHeight>(
        &mut self,
        frames: usize,
        frame_dt_s: f64,
        mut surface_at: impl FnMut(f64) -> W,
    ) -> Vec<BoatPose> {
        (0..frames)
            .map(|_| {
                let water = surface_at(self.time_s);
                self.step(&water, frame_dt_s);
                self.pose()
            })
            .collect()
    }

    /// [`Self::simulate`] with a surface that can fail to build (as
    /// [`crate::frame::surface_query`] can).
    ///
    /// # Errors
    /// The first error of `surface_at`; the boat keeps the frames done before it.
    pub fn try_simulate<W: WaterHeight, E>(
        &mut self,
        frames: usize,
        frame_dt_s: f64,
        mut surface_at: impl FnMut(f64) -> std::result::Result<W, E>,
    ) -> std::result::Result<Vec<BoatPose>, E> {
        let mut poses = Vec::with_capacity(frames);
        for _ in 0..frames {
            let water = surface_at(self.time_s)?;
            self.step(&water, frame_dt_s);
            poses.push(self.pose());
        }
        Ok(poses)
    }

    /// One sub-step of length h (module doc, steps 1–5).
    fn substep<W: WaterHeight + ?Sized>(&mut self, water: &W, h: f64) {
        let p = self.params;
        let k = p.corner_stiffness_n_per_m();
        let (thrust_n, steer_rad) = self.controls.effective(&p);
        let pose = self.pose();
        // The thrust's direction: forward turned by the steering angle about up, towards
        // starboard for positive angles, which pushes the stern to starboard and turns the bow
        // to port.
        let thrust_dir = pose.forward * steer_rad.cos() + pose.starboard * steer_rad.sin();
        // The positions do not change before the loop's end: all heights first (one call,
        // which the surface may answer in parallel).
        let points = self.position.map(|x| (x.x, x.z));
        let heights = water.water_heights(&points);
        for (i, &eta) in heights.iter().enumerate() {
            let x = self.position[i];
            // Non-finite height: no water at this point (the trait's contract).
            let depth = if eta.is_finite() { eta - x.y } else { f64::NEG_INFINITY };
            let mut force = DVec3::new(0.0, -GRAVITY / self.inv_mass[i], 0.0);
            let mut share = 0.0;
            if i == ENGINE {
                if depth > 0.0 {
                    force += thrust_dir * thrust_n;
                }
            } else {
                // clamp(d, 0, H): no buoyancy above the water, a full column's at most.
                let submerged_m = depth.clamp(0.0, p.hull_depth_m);
                force.y += k * submerged_m;
                share = submerged_m / p.hull_depth_m;
            }
            // Damp the velocity the body had, then add the other forces' impulse (module doc:
            // why in this order).
            let mut v = self.velocity[i];
            v.y /= 1.0 + p.heave_damping_per_s * share * h;
            let drag = 1.0 + p.drag_per_s * share * h;
            v.x /= drag;
            v.z /= drag;
            self.velocity[i] = v + force * (h * self.inv_mass[i]);
        }
        constraints::project_velocities(&self.position, &mut self.velocity, &self.inv_mass);
        for i in 0..POINTS {
            self.position[i] += self.velocity[i] * h;
        }
        constraints::project_positions(&mut self.position, &self.inv_mass, &self.rest_length);
    }
}
