//! The frame plan: which passes a scene needs, in order, and why each is in or out. Both back
//! ends run a [`FramePlan`] and never decide on their own (docs/design.md, "Data flow").
//!
//! Every rule leaves out a pass whose contribution to the picture is exactly zero, so the
//! pruned frame is bit-identical to the full one:
//! - `waves`: no wind → a flat sea; the displacement and bump maps are all zero (and J = 1),
//!   which the water pass reads as such without sampling.
//! - `shadow_map`: it only darkens the sun's specular highlight (eq. 3's A_shadow); without a
//!   sun above the horizon there is no highlight, and without an object above the water
//!   nothing casts a shadow.
//! - `reflection_map`: holds the objects above the water, mirrored, with coverage in alpha;
//!   the sky is reflected analytically in the water pass. No object above the water → alpha
//!   is 0 everywhere → the map changes nothing.
//! - `refraction_map`: holds the objects under the water with eq. 4's fog, coverage in alpha;
//!   the water volume colour fills the rest. No object under the water → nothing to show.
//! - `objects`: no objects, no pass.
//! - `sky`: with the camera under the water the background is the water volume's colour (the
//!   frame is cleared to it); the sky is still seen through the surface (Snell's window), which
//!   the water pass evaluates analytically.
//! - `tonemap`: an EXR output keeps linear HDR.
//! - `bloom` (post technique `bloom`): composited by the tonemap, so it runs only where the
//!   tonemap does; `bloom_strength = 0` adds 0 · (a finite pyramid) = 0 to every pixel.
//! - `cycle`: the loop's maps precomputed once and played cyclically (seed 000 §2.1) pay off
//!   only over several frames of a looping sea; a single frame is synthesised at its t.
//! - `far_patch`: the far rings and the stitch lie outside the near patch's square on the sea
//!   plane (weight 0, flat); when the view's footprint on the plane lies inside that square
//!   they are clipped whole and are not built.
//! - per-pass object lists: an object whose box (mirrored for the reflection map, scaled by
//!   1/η for the refraction map) lies outside the view frustum yields no fragment in that
//!   pass and is culled from it; a pass left with no object is skipped. The shadow map keeps
//!   every object above the water: a caster outside the view can shadow the visible water.
//!
//! [`FramePlan::full`] turns every one of these rules off (the `sky` and `tonemap` choices
//! stay: they are what the picture shows, not work saved); the tests render both plans and
//! compare the bits.

pub mod memory;
mod resource;
mod rules;
mod spray;
pub use spray::spray_uniforms;

use crate::tables::TextureMapping;
use std::fmt;

use glam::{DVec3, DVec4};
use serde::Serialize;

use crate::camera::{Camera, NEAR_PLANE_M};
use crate::geometry::WaterMesh;
use crate::scene::{Object, Scene, Shape};

pub use crate::technique::{
    Choice, FarField, Foam, Post, SYSTEMS, Shading, Sky, Spray, Stage, StageTechnique, Surface,
    System, SystemInfo, TechniqueError, TechniqueInfo, Techniques, Waves, all_techniques,
    known_systems, technique,
};
pub use resource::{Format, Resource, ResourceId, SHADOW_MAP_SIZE};

/// A pass of the frame, named as in docs/design.md (the name of its stage, or of the map an
/// object pass fills, or of the work it stands for: `cycle`, `far_patch`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Pass {
    /// The maps of one loop period, precomputed and played cyclically (seed 000 §2.1).
    Cycle,
    /// Displacement and bump maps of the sea at time t (stage `waves`).
    Waves,
    /// The slope maps' mip chains (stage `wave_mips`, far fields `mip` and `variance`).
    WaveMips,
    /// Foam `accumulated`: fixed steps of the foam field (stage `foam`).
    Foam,
    /// The 2D Fresnel texture (stage `fresnel_table`).
    FresnelTable,
    /// Depth of the objects seen from the sun (stage `shadow`).
    ShadowMap,
    /// Objects above the water, mirrored (stage `objects`, entry `vs_reflect`).
    ReflectionMap,
    /// Objects under the water, scaled and fogged (stage `objects`, entry `vs_refract`).
    RefractionMap,
    /// The sky behind everything (stage `sky`).
    Sky,
    /// The objects in the main view (stage `objects`).
    Objects,
    /// The far patch of the water mesh and its stitch to the near patch (seed 000 §3).
    FarPatch,
    /// The water surface, eq. 3 (stage `water`).
    Water,
    /// Spray particles: one fixed step of the pool, then their sprites (stage `spray`).
    Spray,
    /// The bright pass and its blur pyramid (post technique `bloom`, stage `bloom`).
    Bloom,
    /// HDR → 8-bit sRGB (stage `tonemap`).
    Tonemap,
}

impl Pass {
    /// Every pass, in execution order.
    pub const ALL: [Pass; 15] = [
        Pass::Cycle,
        Pass::Waves,
        Pass::WaveMips,
        Pass::Foam,
        Pass::FresnelTable,
        Pass::ShadowMap,
        Pass::ReflectionMap,
        Pass::RefractionMap,
        Pass::Sky,
        Pass::Objects,
        Pass::FarPatch,
        Pass::Water,
        Pass::Spray,
        Pass::Bloom,
        Pass::Tonemap,
    ];

    /// The technique stage the pass belongs to, if it is one of a stage's techniques (the
    /// object passes belong to none: every system draws the scene's objects alike).
    pub fn stage(self) -> Option<Stage> {
        match self {
            Pass::Cycle | Pass::Waves => Some(Stage::Waves),
            Pass::FresnelTable | Pass::Water => Some(Stage::Shading),
            Pass::Sky => Some(Stage::Sky),
            Pass::WaveMips => Some(Stage::FarField),
            Pass::FarPatch => Some(Stage::Surface),
            Pass::Tonemap | Pass::Bloom => Some(Stage::Post),
            Pass::Spray => Some(Stage::Spray),
            Pass::Foam => Some(Stage::Foam),
            Pass::ShadowMap | Pass::ReflectionMap | Pass::RefractionMap | Pass::Objects => None,
        }
    }

    /// The registry stage whose WGSL executes the pass (`None`: CPU work in ocean-core, the
    /// cycle's precompute and the far patch's geometry).
    pub fn shader(self) -> Option<&'static str> {
        match self {
            Pass::Cycle | Pass::FarPatch => None,
            Pass::Waves => Some("waves"),
            Pass::WaveMips => Some("wave_mips"),
            Pass::FresnelTable => Some("fresnel_table"),
            Pass::ShadowMap => Some("shadow"),
            Pass::ReflectionMap | Pass::RefractionMap | Pass::Objects => Some("objects"),
            Pass::Sky => Some("sky"),
            Pass::Water => Some("water"),
            Pass::Tonemap => Some("tonemap"),
            Pass::Bloom => Some("bloom"),
            Pass::Spray => Some("spray"),
            Pass::Foam => Some("foam"),
        }
    }

    /// The resources the pass reads.
    pub fn reads(self) -> &'static [ResourceId] {
        use ResourceId as R;
        match self {
            Pass::Water => &[
                R::Displacement,
                R::DisplacementSlopes,
                R::Bump,
                R::DisplacementSlopeMips,
                R::BumpMips,
                R::FresnelFilter,
                R::FresnelAbove,
                R::FresnelBelow,
                R::ShadowMap,
                R::ReflectionMap,
                R::RefractionMap,
                R::FoamField,
                R::Environment,
            ],
            Pass::Foam => &[R::Displacement, R::FoamField],
            Pass::Tonemap => &[R::Hdr, R::BloomUp],
            Pass::Bloom => &[R::Hdr],
            Pass::Spray => &[R::Displacement, R::Hdr],
            Pass::Sky => &[R::Environment],
            Pass::WaveMips => &[R::DisplacementSlopes, R::Bump],
            _ => &[],
        }
    }

    /// The resources the pass writes.
    pub fn writes(self) -> &'static [ResourceId] {
        use ResourceId as R;
        match self {
            Pass::Cycle | Pass::FarPatch => &[],
            Pass::Waves => &[R::Displacement, R::DisplacementSlopes, R::Bump],
            Pass::WaveMips => &[R::DisplacementSlopeMips, R::BumpMips, R::FresnelFilter],
            Pass::FresnelTable => &[R::FresnelAbove, R::FresnelBelow],
            Pass::ShadowMap => &[R::ShadowMap],
            Pass::ReflectionMap => &[R::ReflectionMap],
            Pass::RefractionMap => &[R::RefractionMap],
            Pass::Sky | Pass::Objects | Pass::Water | Pass::Spray => &[R::Hdr],
            Pass::Bloom => &[R::BloomDown, R::BloomUp],
            Pass::Foam => &[R::FoamField],
            Pass::Tonemap => &[R::Ldr],
        }
    }

    /// The pass's name in plans, labels and reports.
    pub fn name(self) -> &'static str {
        match self {
            Pass::Cycle => "cycle",
            Pass::Waves => "waves",
            Pass::WaveMips => "wave_mips",
            Pass::FresnelTable => "fresnel_table",
            Pass::ShadowMap => "shadow_map",
            Pass::ReflectionMap => "reflection_map",
            Pass::RefractionMap => "refraction_map",
            Pass::Sky => "sky",
            Pass::Objects => "objects",
            Pass::FarPatch => "far_patch",
            Pass::Water => "water",
            Pass::Spray => "spray",
            Pass::Foam => "foam",
            Pass::Bloom => "bloom",
            Pass::Tonemap => "tonemap",
        }
    }
}

impl fmt::Display for Pass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// How the `waves` pass computes technique `fft`'s maps (both back ends follow it).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum WavesKernel {
    /// `shaders/waves.wgsl`: the GPU FFT on the GPU, its CPU mirror on the oracle (both maps'
    /// sides are powers of two, as its radix-2 FFT needs).
    Shader,
    /// ocean-core's FFT synthesis, uploaded on the GPU: a side that is not a power of two.
    Synthesis,
}

impl WavesKernel {
    /// The kernel for a displacement and a bump map of these sides.
    pub fn for_resolutions(n_d: u32, n_b: u32) -> Self {
        let fft = |n: u32| crate::waves::uniforms::check_fft_size(n as usize).is_ok();
        if fft(n_d) && fft(n_b) { WavesKernel::Shader } else { WavesKernel::Synthesis }
    }

    /// The kernel for a sea: [`Self::for_resolutions`], except that a looping sea is always
    /// synthesised by ocean-core — the cycle's precompute (`cycle`) is, so a frame played from
    /// the cycle and one synthesised at its instant are the same bits, and the planner's
    /// `cycle` rule stays exact.
    pub fn for_ocean(ocean: &crate::scene::Ocean) -> Self {
        if ocean.loop_period_s > 0.0 {
            WavesKernel::Synthesis
        } else {
            Self::for_resolutions(ocean.resolution, ocean.bump_resolution)
        }
    }
}

/// What the frame is written to: the tonemap pass runs only for 8-bit output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputKind {
    /// 8-bit sRGB (PNG).
    Ldr,
    /// Linear HDR (EXR).
    Hdr,
}

/// A pass with the reason it is in or out of the plan, its stage and technique, what it
/// reads and writes and which objects it draws.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct PlannedPass {
    /// Which pass.
    pub name: Pass,
    /// Why it runs or is skipped.
    pub reason: String,
    /// Its technique stage ([`Pass::stage`]).
    pub stage: Option<Stage>,
    /// The technique of that stage the plan chose.
    pub technique: Option<&'static str>,
    /// The registry stage whose WGSL runs it ([`Pass::shader`]).
    pub shader: Option<&'static str>,
    /// Resources it reads.
    pub reads: &'static [ResourceId],
    /// Resources it writes.
    pub writes: &'static [ResourceId],
    /// The objects it draws (indices into the scene's `objects`; object passes only).
    pub objects: Vec<usize>,
    /// Whether it draws the sea floor (`[terrain]`; object passes only).
    pub terrain: bool,
}

/// Which objects (indices into the scene's `objects`) each object pass draws.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct PassObjects {
    /// Casters of the sun's shadow map.
    pub shadow_map: Vec<usize>,
    /// Objects mirrored into the reflection map.
    pub reflection_map: Vec<usize>,
    /// Objects scaled and fogged into the refraction map.
    pub refraction_map: Vec<usize>,
    /// Objects in the main view.
    pub objects: Vec<usize>,
}

impl PassObjects {
    /// The list of an object pass (empty for the other passes).
    pub fn of(&self, pass: Pass) -> &[usize] {
        match pass {
            Pass::ShadowMap => &self.shadow_map,
            Pass::ReflectionMap => &self.reflection_map,
            Pass::RefractionMap => &self.refraction_map,
            Pass::Objects => &self.objects,
            _ => &[],
        }
    }
}

/// The frame graph: the system and the technique per stage, the resources with their
/// formats and sizes, the ordered passes, the ones left out, and what each object pass
/// draws. Both back ends run it through [`crate::graph::run_frame`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FramePlan {
    /// The system the techniques start from.
    pub system: System,
    /// The technique of every stage.
    pub techniques: Techniques,
    /// The passes to run, in order.
    pub passes: Vec<PlannedPass>,
    /// The passes left out, with why.
    pub skipped: Vec<PlannedPass>,
    /// Every texture the frame binds, with its format and size.
    pub resources: Vec<Resource>,
    /// How the `waves` pass computes its maps.
    pub waves_kernel: WavesKernel,
    /// The format of the frame's colour buffers (HDR frame, reflection and refraction maps,
    /// bloom chains): the scene's `[post] frame_format` or the system's.
    pub frame_format: crate::frame_format::FrameFormat,
    /// Side N of the N × N Fresnel textures (`[quality] fresnel_table_size`).
    pub fresnel_table_size: u32,
    /// Which view vectors the Fresnel textures' texels stand for: the grazing mapping, whose
    /// rim falls on texel centres (error ≤ 1.4e-3 over the whole hemisphere at 256², against
    /// 0.41 at the rim for the contract's default `hemisphere`; `tests/fresnel.rs`).
    pub fresnel_mapping: TextureMapping,
    /// Width and height of the reflection map, pixels (`[quality] reflection_map_scale` of the
    /// viewport, at least 1).
    pub reflection_map_size: [u32; 2],
    /// How far the waves may reach above and below the sea plane, and horizontally (the
    /// choppy displacement), m: the projected grid's slab and its edge's margin, the spray's
    /// band (0 where neither surface `projected_grid` nor spray `particles` is used).
    /// Computed once here (the spectrum's significant wave height is a quadrature), not per
    /// frame's uniforms.
    pub wave_bound_m: [f64; 2],
    /// The spray's emitters (spray `particles`; empty otherwise), found once per plan.
    #[serde(skip)]
    pub spray_emitters: std::sync::Arc<Vec<crate::spray::Emitter>>,
}

/// The vertical extent of an object, m: a boat's is unbounded (it floats, so it is always at
/// the water, above and below it).
fn y_range(o: &Object) -> (f64, f64) {
    match bounds(o) {
        Some((lo, hi)) => (lo.y, hi.y),
        None => (f64::NEG_INFINITY, f64::INFINITY),
    }
}

/// The axis-aligned box of an object (world, m); `None` for a boat, whose place is a frame's
/// (`crate::frame::ObjectPoses`), not the plan's: the plan, made once for every time, draws it
/// in every pass it can show in and never culls it.
fn bounds(o: &Object) -> Option<(DVec3, DVec3)> {
    let half = match o.shape() {
        Some(Shape::Sphere { radius }) => DVec3::splat(radius),
        Some(Shape::Box { size }) => DVec3::from_array(size) * 0.5,
        Some(Shape::Boat { .. }) => return None,
        None => DVec3::ZERO,
    };
    let c = DVec3::from_array(o.center);
    Some((c - half, c + half))
}

/// Margin of the culling tests, pixels: a box must be this far outside the frustum's side
/// planes to be culled. The renderers transform f32 positions with f32 matrices (relative
/// error ~1e-7) and snap to 1/256 pixel; 4 pixels covers both with room to spare.
const CULL_MARGIN_PX: f64 = 4.0;

/// Whether the box [lo, hi] (world) is outside the camera's frustum: all eight corners beyond
/// one side plane (widened by [`CULL_MARGIN_PX`]) or behind half the near plane. A box
/// straddling a plane is kept, so this never culls what the rasterizer would draw.
fn outside_view(camera: &Camera, lo: DVec3, hi: DVec3) -> bool {
    let vp = camera.view_proj();
    let mx = 1.0 + 2.0 * CULL_MARGIN_PX / f64::from(camera.width);
    let my = 1.0 + 2.0 * CULL_MARGIN_PX / f64::from(camera.height);
    let corners: Vec<DVec4> = (0..8)
        .map(|i| {
            let p = DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            vp * (p - camera.eye).extend(1.0)
        })
        .collect();
    let all = |f: &dyn Fn(&DVec4) -> bool| corners.iter().all(f);
    all(&|c| c.x > mx * c.w)
        || all(&|c| c.x < -mx * c.w)
        || all(&|c| c.y > my * c.w)
        || all(&|c| c.y < -my * c.w)
        || all(&|c| c.w < 0.5 * NEAR_PLANE_M)
}

/// "#1 box" — how a reason names an object.
fn object_name(i: usize, o: &Object) -> String {
    let kind = match o.kind {
        crate::scene::ObjectKind::Sphere => "sphere",
        crate::scene::ObjectKind::Box => "box",
        crate::scene::ObjectKind::Boat => "boat",
    };
    format!("#{i} {kind}")
}

/// Whether the view's footprint on the sea plane lies inside the near patch's square, so that
/// the far patch and the stitch (outside the square, flat) are clipped whole. Returns the
/// footprint's bounding box (min x, min z, max x, max z) and the square (centre, half side)
/// when it does.
fn footprint_inside_near_patch(scene: &Scene, camera: &Camera) -> Option<([f64; 4], [f64; 3])> {
    let eye = camera.eye;
    if eye.y == 0.0 {
        return None;
    }
    // Corner rays of the frustum widened by the culling margin: all must meet the plane, and
    // then the footprint is the convex hull of where they meet it.
    let mx = 1.0 + 2.0 * CULL_MARGIN_PX / f64::from(camera.width);
    let my = 1.0 + 2.0 * CULL_MARGIN_PX / f64::from(camera.height);
    let mut bbox = [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY];
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
        let d = camera.ray_direction(sx * mx, sy * my);
        // Towards the plane (a grazing ray hits it far out, beyond any near patch).
        if d.y * eye.y >= 0.0 || d.y.is_nan() {
            return None;
        }
        let t = -eye.y / d.y;
        let p = eye + d * t;
        if !p.is_finite() {
            return None;
        }
        bbox = [bbox[0].min(p.x), bbox[1].min(p.z), bbox[2].max(p.x), bbox[3].max(p.z)];
    }
    let params = scene.patch_params_for(camera);
    let (c, half) = crate::geometry::near_patch_square(&params, [eye.x, eye.z]).ok()?;
    // One grid cell inside the boundary: the footprint then clears the far patch by a cell.
    let inner = half - params.grid_spacing_m;
    let inside = bbox[0] > c[0] - inner
        && bbox[2] < c[0] + inner
        && bbox[1] > c[1] - inner
        && bbox[3] < c[1] + inner;
    inside.then_some((bbox, [c[0], c[1], half]))
}

impl FramePlan {
    /// The plan of one frame of a validated scene: every rule applied.
    pub fn new(scene: &Scene, output: OutputKind) -> Self {
        Self::build(scene, output, rules::Options { frames: 1, prune: true })
    }

    /// The plan of each of `frames` frames of an animation of the scene: as [`Self::new`],
    /// and a looping sea precomputes its cycle when more than one frame is asked for.
    pub fn for_frames(scene: &Scene, output: OutputKind, frames: u64) -> Self {
        Self::build(scene, output, rules::Options { frames, prune: true })
    }

    /// The plan with every pruning rule turned off: every pass the scene can use runs (the
    /// cycle whenever the sea loops and has waves), the far patch is built and each object
    /// pass draws every object that can show in it (above the water for the reflection and
    /// shadow maps, below it for the refraction map). Its picture is the reference that the
    /// pruned plan's must equal bit for bit (the cycle's only at its frame instants).
    pub fn full(scene: &Scene, output: OutputKind) -> Self {
        Self::build(scene, output, rules::Options { frames: u64::MAX, prune: false })
    }

    /// The resource table: each texture at the size its writer makes it, or 1×1 where the
    /// writer is skipped.
    fn size_resources(&self, scene: &Scene) -> Vec<Resource> {
        let viewport = [scene.camera.width, scene.camera.height];
        let o = &scene.ocean;
        let written = |id: ResourceId| id.writer().is_none_or(|p| self.runs(p));
        // The frame's colour buffers (`crate::frame_format`); the other maps stay f32.
        let frame = Format::of_frame(self.frame_format);
        let mut out = Vec::new();
        for id in ResourceId::ALL {
            let (format, size) = match id {
                ResourceId::Displacement | ResourceId::DisplacementSlopes => {
                    (Format::Rgba32Float, [o.resolution; 2])
                }
                ResourceId::Bump => (Format::Rgba32Float, [o.bump_resolution; 2]),
                ResourceId::DisplacementSlopeMips => (Format::Rgba32Float, [o.resolution; 2]),
                ResourceId::BumpMips => (Format::Rgba32Float, [o.bump_resolution; 2]),
                ResourceId::FresnelFilter => (
                    Format::Rgba32Float,
                    [crate::far_field::FILTER_RADII, crate::far_field::FILTER_SIGMAS],
                ),
                ResourceId::FresnelAbove | ResourceId::FresnelBelow => {
                    (Format::Rgba32Float, [self.fresnel_table_size; 2])
                }
                ResourceId::ShadowMap => (Format::R32Float, [SHADOW_MAP_SIZE; 2]),
                ResourceId::ReflectionMap => (frame, self.reflection_map_size),
                ResourceId::RefractionMap => (frame, viewport),
                ResourceId::Hdr => (frame, viewport),
                ResourceId::BloomDown | ResourceId::BloomUp => {
                    (frame, crate::bloom::base_size(viewport[0], viewport[1]))
                }
                ResourceId::FoamField => (Format::Rgba32Float, {
                    let g = crate::foam::FieldGrid::of(scene, self.techniques.waves());
                    [g.size; 2]
                }),
                ResourceId::Ldr => (Format::Rgba8Unorm, viewport),
                // The sky's uniforms and its sky-view table (`SkyLut`, bound by the `sky` and
                // `water` stages under every sky technique, filled under `atmosphere`).
                ResourceId::Environment => (
                    Format::Uniform,
                    [
                        (std::mem::size_of::<crate::sky::SkyUniforms>()
                            + std::mem::size_of::<crate::atmosphere::SkyLut>())
                            as u32,
                        1,
                    ],
                ),
            };
            // Only the `variance` technique reads the filtered Fresnel table.
            let is_written = written(id)
                && (id != ResourceId::FresnelFilter
                    || self.techniques.far_field().slope_variance());
            if id == ResourceId::Ldr && !is_written {
                continue;
            }
            // The frame starts from the sky; under the water the sky is skipped and the water
            // volume's colour is the background.
            let clear = if id == ResourceId::Hdr && !self.runs(Pass::Sky) {
                let c = scene.water.color.map(|v| v as f32);
                [c[0], c[1], c[2], 1.0]
            } else {
                [0.0; 4]
            };
            let (format, size) =
                if is_written { (format, size) } else { (Format::Rgba32Float, [1, 1]) };
            let levels = match id {
                ResourceId::DisplacementSlopeMips | ResourceId::BumpMips if is_written => {
                    crate::far_field::mip_level_count(size[0], size[1])
                }
                ResourceId::BloomDown | ResourceId::BloomUp if is_written => {
                    crate::bloom::level_count(viewport[0], viewport[1], scene.post.bloom_levels)
                }
                _ => 1,
            };
            out.push(Resource { id, format, size, written: is_written, clear, levels });
        }
        out
    }

    /// The plan's entry for a resource (every resource but `ldr` of an HDR frame is listed).
    pub fn resource(&self, id: ResourceId) -> Option<&Resource> {
        self.resources.iter().find(|r| r.id == id)
    }

    /// The objects each object pass draws (run or skipped), gathered from the passes.
    pub fn objects(&self) -> PassObjects {
        let of = |pass: Pass| {
            self.passes
                .iter()
                .chain(&self.skipped)
                .find(|p| p.name == pass)
                .map_or_else(Vec::new, |p| p.objects.clone())
        };
        PassObjects {
            shadow_map: of(Pass::ShadowMap),
            reflection_map: of(Pass::ReflectionMap),
            refraction_map: of(Pass::RefractionMap),
            objects: of(Pass::Objects),
        }
    }

    /// The planned pass `pass`, if it runs.
    pub fn pass(&self, pass: Pass) -> Option<&PlannedPass> {
        self.passes.iter().find(|p| p.name == pass)
    }

    /// The filtered Fresnel table the frame binds, when the plan writes it (far field
    /// `variance`): ocean-core's, built once per process and η, the same texels on both
    /// back ends.
    pub fn fresnel_filter(
        &self,
        scene: &Scene,
    ) -> Option<std::sync::Arc<crate::far_field::FresnelFilterTable>> {
        self.resource(ResourceId::FresnelFilter)
            .is_some_and(|r| r.written)
            .then(|| crate::far_field::FresnelFilterTable::cached(scene.water.ior))
    }

    /// Whether the plan runs a pass.
    pub fn runs(&self, pass: Pass) -> bool {
        self.passes.iter().any(|p| p.name == pass)
    }

    /// Whether a frame leaves state the next one continues ([`crate::graph::FrameState`]'s foam field of
    /// foam `accumulated`, or the spray's particle pool), so that frame n of an animation
    /// depends on the frames before it.
    pub fn carries_state(&self) -> bool {
        self.runs(Pass::Foam) || self.runs(Pass::Spray)
    }

    /// The plan of a frame an animation steps but does not draw (a frame of another shard, or
    /// one already on disk): only the passes whose work outlives the frame — `cycle`, `waves`
    /// (the displacement the foam and the spray step on), `foam`, `spray` — in their order.
    /// Running it in place of a frame leaves [`crate::graph::FrameState`] as the whole frame would.
    pub fn advance_only(&self) -> FramePlan {
        let mut plan = self.clone();
        plan.passes
            .retain(|p| matches!(p.name, Pass::Cycle | Pass::Waves | Pass::Foam | Pass::Spray));
        plan
    }

    /// The passes an animation runs on a frame it steps but does not draw: those of
    /// [`Self::advance_only`] where the plan [`Self::carries_state`], none otherwise.
    pub fn state_passes(&self) -> Vec<Pass> {
        if self.carries_state() {
            self.advance_only().passes.iter().map(|p| p.name).collect()
        } else {
            Vec::new()
        }
    }

    /// The water mesh of this plan's frame (seed 000 §3): near and far patch, or the near
    /// patch alone where the plan leaves the far patch out.
    pub fn water_mesh(&self, scene: &Scene, camera: &Camera) -> crate::Result<WaterMesh> {
        let params = scene.patch_params_for(camera);
        // The surfaces drawn from the vertex index (frame::ClipmapBlock, ProjectedGridBlock):
        // the mesh only fixes the reference point, for the clipmap the eye snapped to twice
        // level 0's quad, for the grid the eye's (x, z) on the displacement grid.
        let g = params.grid_spacing_m;
        let index_drawn = |origin: [f64; 2]| WaterMesh {
            origin,
            origin_cell: origin.map(|x| (x / g).round() as i64),
            vertices: Vec::new(),
            indices: Vec::new(),
            near_vertices: 0,
            near_triangles: 0,
            stitch_triangles: 0,
            far_first_ring: 0,
            far_inner_radius_m: 0.0,
            far_outer_radius_m: 0.0,
        };
        if let Some(clipmap) = crate::geometry::Clipmap::of_frame(scene, camera, self) {
            return Ok(index_drawn(clipmap?.origin));
        }
        if self.techniques.surface().index_drawn() {
            // The clipmap returned above: what is left of the index-drawn surfaces is the
            // camera grids.
            let cell = |x: f64| (x / g).round() * g;
            return Ok(index_drawn([cell(camera.eye.x), cell(camera.eye.z)]));
        }
        if self.runs(Pass::FarPatch) {
            WaterMesh::for_view(
                &params,
                camera.eye.to_array(),
                camera.forward.to_array(),
                camera.fov_y,
                camera.aspect(),
            )
        } else {
            WaterMesh::near_only(&params, camera.eye.to_array())
        }
    }

    /// The passes the full plan runs that this one leaves out.
    pub fn pruned_from(&self, full: &FramePlan) -> Vec<Pass> {
        full.passes.iter().map(|p| p.name).filter(|&p| !self.runs(p)).collect()
    }
}

impl fmt::Display for FramePlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "  system {} ({})", self.system, self.system.info().paper)?;
        for (stage, t) in self.techniques.iter() {
            let by = if self.techniques.is_overridden(stage) { "  [techniques]" } else { "" };
            writeln!(f, "  stage {:<10} {:<16} {}{by}", stage.name(), t.name, t.source)?;
        }
        writeln!(
            f,
            "  frame {:<10} {:<16} HDR frame, reflection/refraction maps, bloom chains",
            "format",
            self.frame_format.name()
        )?;
        for p in &self.passes {
            writeln!(f, "  run   {:<15} {}", p.name.name(), p.reason)?;
        }
        for p in &self.skipped {
            writeln!(f, "  skip  {:<15} {}", p.name.name(), p.reason)?;
        }
        Ok(())
    }
}

/// How the plan names the sea floor a pass draws.
fn floor_reason(scene: &Scene) -> String {
    match scene.terrain.as_ref() {
        Some(t) => match t.relief() {
            Some(r) if t.kind == crate::scene::TerrainKind::Island => format!(
                "the sea floor ([terrain], an island {:.0} m across, {:.0} m high, its relief \
                 {}×{}, {} triangles)",
                2.0 * t.island_radius_m,
                t.island_height_m,
                r.width,
                r.height,
                t.mesh_triangles()
            ),
            Some(r) => format!(
                "the sea floor ([terrain], a {}×{} heightmap, {} triangles)",
                r.width,
                r.height,
                t.mesh_triangles()
            ),
            None => format!("the sea floor ([terrain], a plane, {} triangles)", t.mesh_triangles()),
        },
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{ObjectKind, Sun};

    fn sphere(y: f64) -> Object {
        Object {
            kind: ObjectKind::Sphere,
            center: [0.0, y, -10.0],
            radius: Some(1.0),
            size: None,
            heading_deg: None,
            mass_kg: None,
            color: [0.5; 3],
        }
    }

    #[test]
    fn builtin_scene_runs_every_pass_but_the_cycle_the_spray_and_the_tonemap_for_exr() {
        let s = Scene::builtin();
        let p = FramePlan::new(&s, OutputKind::Ldr);
        let skipped: Vec<_> = p.skipped.iter().map(|p| p.name).collect();
        assert_eq!(skipped, [Pass::Cycle, Pass::Foam, Pass::Spray, Pass::Bloom], "{p}");
        let names: Vec<_> = p.passes.iter().map(|p| p.name).collect();
        let want: Vec<_> = Pass::ALL[1..]
            .iter()
            .copied()
            .filter(|p| !matches!(p, Pass::Foam | Pass::Spray | Pass::Bloom))
            .collect();
        assert_eq!(names, want);
        assert_eq!(p.objects().objects, [0, 1]);
        let p = FramePlan::new(&s, OutputKind::Hdr);
        assert_eq!(p.skipped.len(), 5);
        assert!(!p.runs(Pass::Tonemap));
        // The full plan of a scene that needs everything is the pruned one.
        assert_eq!(FramePlan::full(&s, OutputKind::Ldr).passes.len(), 11);
    }

    #[test]
    fn cycle_only_for_several_frames_of_a_looping_sea() {
        let mut s = Scene::default();
        s.ocean.loop_period_s = 20.0;
        assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::Cycle));
        assert!(!FramePlan::for_frames(&s, OutputKind::Ldr, 1).runs(Pass::Cycle));
        assert!(FramePlan::for_frames(&s, OutputKind::Ldr, 2).runs(Pass::Cycle));
        assert!(FramePlan::full(&s, OutputKind::Ldr).runs(Pass::Cycle));
        s.ocean.loop_period_s = 0.0;
        assert!(!FramePlan::for_frames(&s, OutputKind::Ldr, 100).runs(Pass::Cycle));
        assert!(!FramePlan::full(&s, OutputKind::Ldr).runs(Pass::Cycle));
    }

    #[test]
    fn far_patch_is_left_out_only_when_the_footprint_is_inside_the_near_patch() {
        let mut s = Scene::default();
        // 25 m up, looking straight down: the footprint is ~±30 m, the near patch ±256 m.
        s.camera.position = [3.0, 25.0, -7.0];
        s.camera.look_at = [3.0, 0.0, -7.1];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(!p.runs(Pass::FarPatch), "{p}");
        assert!(FramePlan::full(&s, OutputKind::Ldr).runs(Pass::FarPatch));
        // Same from below the water, looking up.
        s.camera.position = [3.0, -25.0, -7.0];
        s.camera.look_at = [3.0, 0.0, -7.1];
        assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::FarPatch));
        // Higher up the near patch grows with the eye (Scene::patch_params_for) and still
        // holds the footprint below; tilted up, the horizon shows.
        s.camera.position = [3.0, 400.0, -7.0];
        s.camera.look_at = [3.0, 0.0, -7.1];
        assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::FarPatch));
        s.camera.position = [3.0, 400.0, -7.0];
        s.camera.look_at = [3.0, 390.0, -100.0];
        assert!(FramePlan::new(&s, OutputKind::Ldr).runs(Pass::FarPatch));
        s.camera.position = [0.0, 25.0, 0.0];
        s.camera.look_at = [0.0, 20.0, -10.0];
        assert!(FramePlan::new(&s, OutputKind::Ldr).runs(Pass::FarPatch));
    }

    #[test]
    fn objects_are_culled_per_pass_and_named() {
        let mut s = Scene::default();
        // Camera at (0, 6, 30) looking along −z, slightly down.
        let behind = Object { center: [0.0, 3.0, 80.0], ..sphere(0.0) };
        let ahead = sphere(3.0);
        // 400 m ahead the view spans y ≈ −224 … 192 m (it looks slightly down): an object at
        // y = 208 is above it, its mirror image at y = −208 inside it.
        let high = Object { center: [0.0, 208.0, -370.0], ..sphere(0.0) };
        s.objects = vec![behind, ahead, high];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert_eq!(p.objects().objects, [1], "{p}");
        assert_eq!(p.objects().reflection_map, [1, 2], "{p}");
        assert_eq!(p.objects().shadow_map, [0, 1, 2]);
        let reason = &p.passes.iter().find(|q| q.name == Pass::Objects).unwrap().reason;
        assert!(reason.contains("#0 sphere") && reason.contains("#2 sphere"), "{reason}");
        let full = FramePlan::full(&s, OutputKind::Ldr);
        assert_eq!(full.objects().objects, [0, 1, 2]);
        // Everything behind the camera: no objects pass, no reflection map.
        s.objects = vec![Object { center: [0.0, 3.0, 80.0], ..sphere(0.0) }];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(!p.runs(Pass::Objects) && !p.runs(Pass::ReflectionMap), "{p}");
        // A box straddling the view's edge is kept (negative control of the culling test).
        // 40 m ahead the view's left edge is at x ≈ −37 m.
        s.objects = vec![Object { center: [-37.0, 3.0, -10.0], ..sphere(0.0) }];
        assert!(FramePlan::new(&s, OutputKind::Ldr).runs(Pass::Objects));
    }

    #[test]
    fn each_rule_fires() {
        let mut s = Scene::default();
        let p = FramePlan::new(&s, OutputKind::Ldr);
        for pass in [Pass::ShadowMap, Pass::ReflectionMap, Pass::RefractionMap, Pass::Objects] {
            assert!(!p.runs(pass), "{pass}");
        }
        s.objects = vec![sphere(5.0)];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(p.runs(Pass::ReflectionMap) && !p.runs(Pass::RefractionMap));
        assert!(!p.runs(Pass::ShadowMap), "no sun");
        s.sun = Some(Sun::default());
        assert!(FramePlan::new(&s, OutputKind::Ldr).runs(Pass::ShadowMap));
        s.sun = Some(Sun { direction: [0.0, -0.1, 1.0], ..Sun::default() });
        assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::ShadowMap), "sun below");
        s.objects = vec![sphere(-5.0)];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(!p.runs(Pass::ReflectionMap) && p.runs(Pass::RefractionMap));
        s.objects = vec![sphere(0.5)];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(p.runs(Pass::ReflectionMap) && p.runs(Pass::RefractionMap), "straddles");
        s.ocean.wind_speed = 0.0;
        assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::Waves));
    }
}
