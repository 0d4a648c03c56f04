//! One frame for both back ends (docs/design.md, "One frame, two back ends"): [`FrameInputs`]
//! computes once, from the scene, the plan and the [`FrameState`], everything a pass needs
//! (camera, mesh, uniform blocks, time); [`run_frame`] walks the plan's passes in order and
//! hands each to a [`Backend`], which knows how to execute one pass and nothing else. A back
//! end chooses no size, pass, technique or constant: they are all here or in the plan.

use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::camera::Camera;
use crate::camera_uniforms::CameraUniforms;
use crate::frame::{FrameUniforms, ObjectPoses, scene_sky, sky_ambient};
use crate::geometry::WaterVertex;
use crate::scene::{Ocean, Scene};
use crate::sky::SkyUniforms;
use crate::tonemap::TonemapUniforms;
use crate::waves::{FrameCycle, Synthesizer, WaveMaps};

use crate::plan::{FramePlan, Pass, PlannedPass};

/// The water mesh of a frame, as the `water` pass draws it: vertices relative to `origin`
/// (world x, z), triangles counter-clockwise seen from above.
#[derive(Clone, Debug, PartialEq)]
pub struct DrawMesh {
    /// The vertices (shared: a kept mesh is handed to every frame that asks for it, and a
    /// back end may keep its upload while it holds the same list).
    pub vertices: Arc<Vec<WaterVertex>>,
    /// The triangles.
    pub indices: Arc<Vec<[u32; 3]>>,
    /// The reference point (world x, z), m.
    pub origin: [f64; 2],
}

impl From<crate::geometry::WaterMesh> for DrawMesh {
    fn from(m: crate::geometry::WaterMesh) -> Self {
        Self { vertices: Arc::new(m.vertices), indices: Arc::new(m.indices), origin: m.origin }
    }
}

impl DrawMesh {
    /// The water mesh of `plan`'s frame seen by `camera` ([`FramePlan::water_mesh`]), kept
    /// per patch parameters and view where the plan draws the near and far patch (their
    /// refinement, stitching and upload were redone every frame of a still camera, about
    /// 0.2 ms of `hu`'s CPU encode on lavapipe); the kept mesh is the one made anew, bit for
    /// bit. The surfaces drawn from the vertex index ([`crate::stage::Surface::index_drawn`])
    /// build an empty mesh and keep nothing.
    ///
    /// # Errors
    /// As [`FramePlan::water_mesh`] (an error is not kept).
    pub fn kept(plan: &FramePlan, scene: &Scene, camera: &Camera) -> crate::Result<Self> {
        static KEPT: crate::kept::Kept<(crate::geometry::PatchParams, [u64; 9]), DrawMesh> =
            crate::kept::Kept::new();
        if plan.techniques.surface().index_drawn() {
            return plan.water_mesh(scene, camera).map(Into::into);
        }
        let (e, f) = (camera.eye, camera.forward);
        let far = if plan.runs(Pass::FarPatch) { 1.0 } else { 0.0 };
        let view = [e.x, e.y, e.z, f.x, f.y, f.z, camera.fov_y, camera.aspect(), far];
        let key = (scene.patch_params_for(camera), view.map(f64::to_bits));
        KEPT.get_or_make(key, || plan.water_mesh(scene, camera).map(Into::into))
    }
}

/// What every pass of one frame reads, computed once for both back ends.
pub struct FrameInputs<'a> {
    /// The validated scene.
    pub scene: &'a Scene,
    /// The plan being run.
    pub plan: &'a FramePlan,
    /// The camera.
    pub camera: Camera,
    /// The water mesh (the plan's near and far patch).
    pub mesh: DrawMesh,
    /// Time spent building [`Self::mesh`].
    pub mesh_time: Duration,
    /// The uniforms of the `objects`, `shadow` and `water` stages.
    pub uniforms: FrameUniforms,
    /// The environment the water reflects and the `sky` stage draws (the sky technique's
    /// uniforms).
    pub environment: SkyUniforms,
    /// Sky `atmosphere`'s sky-view table of this frame (zeros under the other sky techniques,
    /// which do not read it).
    pub sky_lut: std::sync::Arc<crate::atmosphere::SkyLut>,
    /// The `sky` stage's camera block.
    pub camera_uniforms: CameraUniforms,
    /// The `tonemap` stage's block, when the plan tonemaps.
    pub tonemap: Option<TonemapUniforms>,
    /// The `bloom` pass's levels and bright pass, when the plan runs it.
    pub bloom: Option<BloomInputs>,
    /// The sea's time this frame, s ([`FrameState::time_s`]).
    pub time_s: f64,
    /// Where the boats float at [`Self::time_s`] (`crate::frame::ObjectPoses`), settled once
    /// here for every object pass and the shadow map's box.
    pub poses: ObjectPoses,
}

impl<'a> FrameInputs<'a> {
    /// The inputs of frame `state.frame` of a validated scene under `plan`.
    ///
    /// # Errors
    /// An invalid camera, mesh, sky or exposure, or a boat that cannot be settled.
    pub fn new(scene: &'a Scene, plan: &'a FramePlan, state: &FrameState) -> crate::Result<Self> {
        let camera = Camera::from_scene(&scene.camera)?;
        let start = Instant::now();
        let mesh = DrawMesh::kept(plan, scene, &camera)?;
        Self::with_mesh(scene, plan, state, camera, mesh, start.elapsed())
    }

    /// [`Self::new`] with a given camera (an embedding program's, whose roll a scene camera
    /// cannot hold: `Camera::from_view_projection`); the plan must be made for the same
    /// image size.
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn with_camera(
        scene: &'a Scene,
        plan: &'a FramePlan,
        state: &FrameState,
        camera: Camera,
    ) -> crate::Result<Self> {
        let start = Instant::now();
        let mesh = DrawMesh::kept(plan, scene, &camera)?;
        Self::with_mesh(scene, plan, state, camera, mesh, start.elapsed())
    }

    /// [`Self::new`] with a given water mesh (tests draw a plain grid).
    ///
    /// # Errors
    /// As [`Self::new`].
    pub fn with_mesh(
        scene: &'a Scene,
        plan: &'a FramePlan,
        state: &FrameState,
        camera: Camera,
        mesh: DrawMesh,
        mesh_time: Duration,
    ) -> crate::Result<Self> {
        let sky = scene_sky(scene)?;
        let time_s = state.time_s(scene);
        let poses = state.boat_poses(scene, plan, time_s)?;
        let mut uniforms = FrameUniforms::new(scene, &camera, plan, mesh.origin, &poses);
        uniforms.ambient.sky = sky_ambient(&sky);
        // Waves `gerstner` at the frame's time (the block is made at the scene's).
        if time_s != scene.ocean.time_s && uniforms.gerstner.count > 0.0 {
            let mut at = scene.clone();
            at.ocean.time_s = time_s;
            uniforms.gerstner =
                FrameUniforms::new(&at, &camera, plan, mesh.origin, &poses).gerstner;
        }
        // Waves `coastal` likewise (a finite time always makes a sea).
        if time_s != scene.ocean.time_s
            && plan.techniques.waves().runs_up_a_shore()
            && let Ok(sea) = crate::frame::coastal_sea(scene, time_s)
        {
            uniforms.coastal = sea.block(mesh.origin);
        }
        let mut environment = sky.uniforms();
        if plan.techniques.sky().clouds() {
            // The layer (crate::clouds): its place over the eye, its colour under the objects'
            // light, and the sun dimmed by the cloud in front of it.
            let c = &scene.clouds;
            let origin = crate::clouds::cloud_origin(c, camera.eye.to_array(), time_s);
            let mean = crate::clouds::cloud_mean_opacity(origin[3]);
            let s = uniforms.sun;
            let light: [f32; 3] = std::array::from_fn(|i| {
                let direct = f64::from(s.radiance[i])
                    * (f64::from(s.direction[1]).max(0.0) * f64::from(s.lit))
                    / std::f64::consts::PI;
                ((direct + f64::from(uniforms.ambient.sky[i])) * c.albedo) as f32
            });
            environment.cloud_origin = origin;
            environment.cloud_color = [light[0], light[1], light[2], mean];
            let through = 1.0 - crate::clouds::cloud_alpha(origin, mean, s.direction);
            uniforms.sun.radiance = s.radiance.map(|r| r * through);
        }
        let sky_lut = if plan.techniques.sky().sky_view_table() {
            atmosphere_environment(scene, &camera, &mut uniforms, &mut environment)
        } else {
            crate::atmosphere::SkyLut::zero()
        };
        let camera_uniforms = CameraUniforms::new(
            camera.view_proj().to_cols_array_2d(),
            [0.0; 3],
            camera.width,
            camera.height,
        )?;
        let bloom = plan.runs(Pass::Bloom).then(|| BloomInputs::new(scene));
        let tonemap = tonemap_uniforms(scene, plan)?;
        Ok(Self {
            scene,
            plan,
            camera,
            mesh,
            mesh_time,
            uniforms,
            environment,
            sky_lut,
            camera_uniforms,
            tonemap,
            bloom,
            time_s,
            poses,
        })
    }
}

/// The `tonemap` pass's uniforms for `scene` under `plan` (`None` where the pass does not run):
/// the camera's exposure, the `[post]` curve and vignette for the image's size, and the bloom's
/// share of each level where pass `bloom` runs.
///
/// # Errors
/// An exposure or `[post]` value the uniforms cannot hold.
pub fn tonemap_uniforms(scene: &Scene, plan: &FramePlan) -> crate::Result<Option<TonemapUniforms>> {
    let bloom = plan.runs(Pass::Bloom).then(|| BloomInputs::new(scene));
    plan.runs(Pass::Tonemap)
        .then(|| {
            TonemapUniforms::for_image(
                scene.camera.exposure,
                &scene.post,
                scene.camera.width,
                scene.camera.height,
            )
            .map(|mut t| {
                // The bloom's share of each level: strength / L (crate::bloom, step 4);
                // 0 where the pass does not run, so the frame is the plain tonemap's.
                t.bloom_scale = bloom.as_ref().map_or(0.0, |b| b.scale(scene));
                t
            })
        })
        .transpose()
}

/// Sky `atmosphere` (ocean_core::atmosphere): the sky-view table seen from the eye, the sun's
/// light through the atmosphere on the water and in the disc, and the objects' ambient light
/// from the table. The scene's `[sun]` colour × intensity is what a sun at the zenith puts on the
/// sea ([`crate::atmosphere::top_irradiance`]); without a sun the sky is black.
fn atmosphere_environment(
    scene: &Scene,
    camera: &Camera,
    uniforms: &mut FrameUniforms,
    environment: &mut SkyUniforms,
) -> std::sync::Arc<crate::atmosphere::SkyLut> {
    use crate::atmosphere::{SkyLut, sun_at_eye, top_irradiance};
    let (dir, sea) = match &scene.sun {
        Some(sun) => {
            let d = glam::DVec3::from(sun.direction).normalize_or(glam::DVec3::Y);
            (d.to_array(), std::array::from_fn(|c| sun.color[c] * sun.intensity))
        }
        None => ([0.0, 1.0, 0.0], [0.0; 3]),
    };
    let altitude = camera.eye.y.max(0.0);
    /// The sun's irradiance at the top and at the eye, and the sky's ambient term.
    type Light = ([f64; 3], [f64; 3], [f32; 3]);
    // Two integrations of 256 steps and the table's 2,048 lookups: a quarter of a millisecond
    // that every frame asked again for the same eye height and sun, so kept with the table.
    static KEPT: crate::kept::Kept<[u64; 7], Light> = crate::kept::Kept::new();
    let key = [altitude, dir[0], dir[1], dir[2], sea[0], sea[1], sea[2]].map(f64::to_bits);
    let (top, at_eye, ambient) = KEPT.get(key, || {
        let top = top_irradiance(sea);
        let ambient = SkyLut::kept(altitude, dir, top).ambient(dir);
        (top, sun_at_eye(altitude, dir, top), ambient)
    });
    let lut = SkyLut::kept(altitude, dir, top);
    uniforms.sun.radiance = at_eye.map(|e| e as f32);
    environment.sun_radiance = [at_eye[0] as f32, at_eye[1] as f32, at_eye[2] as f32, 0.0];
    uniforms.ambient.sky = ambient;
    lut
}

/// What pass `bloom` needs (`crate::bloom`): one uniform block per level of the down chain
/// (level 0's reads the HDR frame through the bright pass) and the size of every level.
#[derive(Clone, Debug, PartialEq)]
pub struct BloomInputs {
    /// The down chain's dispatches, level 0 first.
    pub down: Vec<crate::bloom::BloomUniforms>,
    /// Size of each level, level 0 first.
    pub levels: Vec<[u32; 2]>,
    /// The chains' format: every texel written is stored through it.
    pub format: crate::frame_format::FrameFormat,
}

impl BloomInputs {
    /// The dispatches of a validated scene's frame.
    pub fn new(scene: &Scene) -> Self {
        let (w, h) = (scene.camera.width, scene.camera.height);
        let count = crate::bloom::level_count(w, h, scene.post.bloom_levels);
        let levels: Vec<[u32; 2]> = (0..count).map(|k| crate::bloom::level_size(w, h, k)).collect();
        let exposure = scene.camera.exposure as f32;
        let threshold = scene.post.bloom_threshold as f32;
        let down = (0..count as usize)
            .map(|k| {
                let src = if k == 0 { [w, h] } else { levels[k - 1] };
                crate::bloom::BloomUniforms::new(levels[k], src, exposure, threshold)
            })
            .collect();
        Self { down, levels, format: scene.frame_format() }
    }

    /// What the tonemap multiplies the up chain's level 0 by: strength / L
    /// (`crate::bloom`, step 4).
    pub fn scale(&self, scene: &Scene) -> f32 {
        (scene.post.bloom_strength / self.levels.len() as f64) as f32
    }

    /// The up chain's dispatch writing level `k` from level `k + 1`.
    pub fn up(&self, k: usize) -> crate::bloom::BloomUniforms {
        let mut u = crate::bloom::BloomUniforms::new(self.levels[k], self.levels[k + 1], 0.0, 0.0);
        if self.format == crate::frame_format::FrameFormat::Rgba16Float {
            u.store_max = crate::frame_format::HALF_MAX;
        }
        u
    }
}

/// The maps of one loop period of one ocean (pass `cycle`).
struct Cycle {
    key: Ocean,
    displacement: FrameCycle<f32>,
    bump: FrameCycle<f32>,
}

/// What lives across the frames of an animation, owned by the caller: the frame index, the
/// fixed step between frames, and the cycle's precomputed maps. Frame n shows the sea at
/// `time_s + n · step_s`, whatever the wall clock did, so it is a pure function of (scene, n).
#[derive(Default)]
pub struct FrameState {
    /// The index of the next frame.
    pub frame: u64,
    /// Seconds between frames.
    pub step_s: f64,
    cycle: Option<Cycle>,
    /// Steps of the spray's particle pool run so far (pass `spray`).
    pub spray_steps: u64,
    /// The CPU back end's particle pool.
    pub spray: Option<crate::spray::SprayState>,
    /// Steps of foam `accumulated`'s field run so far (pass `foam`).
    pub foam_steps: u64,
    /// The field's window (first lattice index per axis) at its last step.
    pub foam_window: Option<[i64; 2]>,
    /// The CPU back end's foam field.
    pub foam: Option<FoamField>,
    /// The boats carried from one frame to the next ([`Self::with_carried_boats`]); `None`:
    /// settled afresh in each frame.
    boats: Option<std::sync::Mutex<Option<crate::frame::BoatRun>>>,
}

/// Foam `accumulated`'s field as the CPU back end carries it across frames.
#[derive(Clone, Debug, PartialEq)]
pub struct FoamField {
    /// Its grid.
    pub grid: crate::foam::FieldGrid,
    /// Steps it has run.
    pub steps: u64,
    /// Texels (foam in x), row-major, `grid.size`² of them.
    pub texels: Vec<[f32; 4]>,
}

/// One frame's work of pass `foam`: the field's grid and the uniforms of each step.
#[derive(Clone, Debug, PartialEq)]
pub struct FoamWork {
    /// Where the field lives.
    pub grid: crate::foam::FieldGrid,
    /// The steps, in order.
    pub steps: Vec<crate::foam::FoamStepUniforms>,
    /// The window after them.
    pub window: [i64; 2],
}

impl FoamWork {
    /// The steps of frame `state.frame`: the scene's warm-up and one on a state's first, one
    /// on every later frame; the window follows the eye (world x, z `eye`), the mesh's
    /// reference point is `mesh_origin`.
    pub fn new(
        scene: &Scene,
        plan: &FramePlan,
        state: &FrameState,
        eye: [f64; 2],
        mesh_origin: [f64; 2],
    ) -> Self {
        let grid = crate::foam::FieldGrid::of(scene, plan.techniques.waves());
        let window = grid.window_start(eye);
        let count = state.foam_steps_this_frame(scene);
        let first_prev = state.foam_window.filter(|_| state.foam_steps > 0).unwrap_or(window);
        let steps = (0..count)
            .map(|k| {
                let prev = if k == 0 { first_prev } else { window };
                crate::foam::FoamStepUniforms::new(scene, &grid, window, prev, mesh_origin)
            })
            .collect();
        Self { grid, steps, window }
    }

    /// Whether a field of `grid` that has run `steps` steps is the one this work continues.
    pub fn continues(&self, grid: &crate::foam::FieldGrid, steps: u64, state: &FrameState) -> bool {
        *grid == self.grid && steps == state.foam_steps
    }
}

impl FrameState {
    /// Frames `step_s` apart, starting at frame 0.
    pub fn new(step_s: f64) -> Self {
        Self {
            frame: 0,
            step_s,
            cycle: None,
            spray_steps: 0,
            spray: None,
            foam_steps: 0,
            foam_window: None,
            foam: None,
            boats: None,
        }
    }

    /// This state with its boats carried from frame to frame, as a live animation wants them
    /// (the viewer, an embedding program, `ocean bench`'s real-time frames): each frame steps
    /// the boats on from the previous frame's time, one or two sub-steps at 60 frames a second,
    /// instead of settling them afresh over a window of 128 sub-steps
    /// (`crate::frame::ObjectPoses::carried`). A frame's poses then depend on the times of the
    /// frames before it, so a still frame or an animation whose frames must each stand alone
    /// (`ocean render --frames`, sharded) keeps the default.
    pub fn with_carried_boats(mut self) -> Self {
        self.boats = Some(Default::default());
        self
    }

    /// The poses of the boats of a frame of `scene` at `time_s` (carried or settled).
    ///
    /// # Errors
    /// As [`crate::frame::ObjectPoses::at`].
    pub fn boat_poses(
        &self,
        scene: &Scene,
        plan: &FramePlan,
        time_s: f64,
    ) -> crate::Result<ObjectPoses> {
        let Some(boats) = &self.boats else {
            return ObjectPoses::at(scene, plan, time_s);
        };
        // A poisoned lock only means a panic mid-step elsewhere: start the boats afresh.
        let mut run = boats.lock().unwrap_or_else(|e| {
            let mut g = e.into_inner();
            *g = None;
            g
        });
        ObjectPoses::carried(scene, plan, time_s, &mut run)
    }

    /// How many foam steps this frame runs: the scene's warm-up and one on the state's
    /// first, one on every later frame.
    pub fn foam_steps_this_frame(&self, scene: &Scene) -> u64 {
        if self.foam_steps == 0 { u64::from(scene.foam.warmup_steps) + 1 } else { 1 }
    }

    /// How many spray steps this frame runs: the scene's warm-up and one on the state's
    /// first, one on every later frame.
    pub fn spray_steps_this_frame(&self, scene: &Scene) -> u64 {
        if self.spray_steps == 0 { u64::from(scene.spray.warmup_steps) + 1 } else { 1 }
    }

    /// The sea's time of the current frame: the scene's `time_s` plus `frame · step_s`
    /// (frame 0 is the scene's time exactly).
    pub fn time_s(&self, scene: &Scene) -> f64 {
        if self.frame == 0 {
            scene.ocean.time_s
        } else {
            scene.ocean.time_s + self.frame as f64 * self.step_s
        }
    }

    /// Moves on to the next frame.
    pub fn advance(&mut self) {
        self.frame += 1;
    }

    /// Pass `cycle`: precomputes the loop's maps of `ocean` unless they are already here
    /// (a later frame of the same sea plays them). Returns whether it computed them.
    ///
    /// # Errors
    /// A sea that does not loop, or a cycle too large to hold.
    pub fn precompute_cycle(&mut self, ocean: &Ocean) -> crate::Result<bool> {
        let key = Ocean { time_s: 0.0, ..ocean.clone() };
        if self.cycle.as_ref().is_some_and(|c| c.key == key) {
            return Ok(false);
        }
        let surface = ocean.surface()?;
        let chop = ocean.choppiness;
        let mut synth_d = Synthesizer::<f32>::new(surface.displacement.resolution())?;
        let mut synth_b = Synthesizer::<f32>::new(surface.bump.resolution())?;
        self.cycle = Some(Cycle {
            key,
            displacement: FrameCycle::new(&surface.displacement, &mut synth_d, chop)?,
            bump: FrameCycle::new(&surface.bump, &mut synth_b, chop)?,
        });
        Ok(true)
    }

    /// The cycle's (displacement, bump) maps nearest `t`, once [`Self::precompute_cycle`]
    /// has run for this ocean.
    pub fn cycle_at(&self, ocean: &Ocean, t: f64) -> Option<(&WaveMaps<f32>, &WaveMaps<f32>)> {
        let key = Ocean { time_s: 0.0, ..ocean.clone() };
        let c = self.cycle.as_ref().filter(|c| c.key == key)?;
        Some((c.displacement.frame_at(t), c.bump.frame_at(t)))
    }
}

/// A back end: knows how to execute each kind of pass, nothing else; [`run_frame`] decides
/// which run, in which order, at what size. It keeps the resources the passes write
/// (allocated at the plan's sizes) until the caller takes them. `cycle` is not here: it is
/// the same CPU precompute for both back ends, run by [`run_frame`] into the [`FrameState`];
/// `far_patch` is geometry, built into [`FrameInputs::mesh`].
pub trait Backend {
    /// The back end's error.
    type Error: From<crate::Error>;

    /// `waves`: the displacement and bump maps at the frame's time (the cycle's, when the
    /// plan plays it).
    ///
    /// # Errors
    /// Whatever the synthesis reports.
    fn waves(&mut self, frame: &FrameInputs<'_>, state: &FrameState) -> Result<(), Self::Error>;

    /// `wave_mips`: the slope maps' mip chains with their second moments, and for far field
    /// `variance` the filtered Fresnel table.
    ///
    /// # Errors
    /// A device error.
    fn wave_mips(&mut self, frame: &FrameInputs<'_>) -> Result<(), Self::Error>;

    /// `fresnel_table`: the two Fresnel textures (η and 1/η).
    ///
    /// # Errors
    /// A device error.
    fn fresnel_tables(&mut self, frame: &FrameInputs<'_>) -> Result<(), Self::Error>;

    /// `shadow_map`, `reflection_map`, `refraction_map` or `objects`: `pass.objects` drawn
    /// into the pass's target.
    ///
    /// # Errors
    /// A device error.
    fn objects(&mut self, pass: &PlannedPass, frame: &FrameInputs<'_>) -> Result<(), Self::Error>;

    /// `sky`: the environment behind everything.
    ///
    /// # Errors
    /// A device error.
    fn sky(&mut self, frame: &FrameInputs<'_>) -> Result<(), Self::Error>;

    /// `water`: the sea surface over the frame.
    ///
    /// # Errors
    /// A technique without an implementation; a device error.
    fn water(&mut self, frame: &FrameInputs<'_>) -> Result<(), Self::Error>;

    /// `spray`: `steps` fixed steps of the particle pool, from step `state.spray_steps`
    /// (the CPU keeps its pool in `state.spray`, a GPU in its own buffer), then the sprites
    /// added to the frame.
    ///
    /// # Errors
    /// A device error.
    fn spray(
        &mut self,
        frame: &FrameInputs<'_>,
        state: &mut FrameState,
        steps: u64,
    ) -> Result<(), Self::Error>;

    /// `foam`: the steps of foam `accumulated`'s field in `work`, from step
    /// `state.foam_steps` (the CPU keeps its field in `state.foam`, a GPU in its own texture).
    ///
    /// # Errors
    /// A device error.
    fn foam(
        &mut self,
        frame: &FrameInputs<'_>,
        state: &mut FrameState,
        work: &FoamWork,
    ) -> Result<(), Self::Error>;

    /// `bloom`: the bright pass's down and up chains ([`FrameInputs::bloom`]).
    ///
    /// # Errors
    /// A device error.
    fn bloom(&mut self, frame: &FrameInputs<'_>) -> Result<(), Self::Error>;

    /// `tonemap`: HDR → 8-bit.
    ///
    /// # Errors
    /// A device error.
    fn tonemap(&mut self, frame: &FrameInputs<'_>) -> Result<(), Self::Error>;
}

/// Runs every pass of `frame.plan` in order on `backend`; `on_pass` is called as each pass
/// starts (progress). Returns the wall time of each pass (for a GPU back end: the time to
/// record it).
///
/// # Errors
/// The first error of a pass.
pub fn run_frame<B: Backend>(
    backend: &mut B,
    frame: &FrameInputs<'_>,
    state: &mut FrameState,
    on_pass: &mut dyn FnMut(Pass),
) -> Result<Vec<(Pass, Duration)>, B::Error> {
    let mut timings = Vec::with_capacity(frame.plan.passes.len());
    for pass in &frame.plan.passes {
        on_pass(pass.name);
        let t0 = Instant::now();
        match pass.name {
            Pass::Cycle => {
                state.precompute_cycle(&frame.scene.ocean)?;
            }
            Pass::FarPatch => {}
            Pass::Waves => backend.waves(frame, state)?,
            Pass::WaveMips => backend.wave_mips(frame)?,
            Pass::FresnelTable => backend.fresnel_tables(frame)?,
            Pass::ShadowMap | Pass::ReflectionMap | Pass::RefractionMap | Pass::Objects => {
                backend.objects(pass, frame)?
            }
            Pass::Sky => backend.sky(frame)?,
            Pass::Water => backend.water(frame)?,
            Pass::Spray => {
                let steps = state.spray_steps_this_frame(frame.scene);
                backend.spray(frame, state, steps)?;
                state.spray_steps += steps;
            }
            Pass::Foam => {
                let eye = [frame.camera.eye.x, frame.camera.eye.z];
                let work = FoamWork::new(frame.scene, frame.plan, state, eye, frame.mesh.origin);
                backend.foam(frame, state, &work)?;
                state.foam_steps += work.steps.len() as u64;
                state.foam_window = Some(work.window);
            }
            Pass::Bloom => backend.bloom(frame)?,
            Pass::Tonemap => backend.tonemap(frame)?,
        }
        let mut elapsed = t0.elapsed();
        // The water pass's time includes building its mesh (near patch, and far patch if
        // planned), as before the frame graph.
        if pass.name == Pass::Water {
            elapsed += frame.mesh_time;
        }
        timings.push((pass.name, elapsed));
    }
    Ok(timings)
}
