//! The uniforms of the frame's render passes (`objects`, `shadow`, `water`), defined once
//! here and declared with the same names in WGSL (`shaders/shared/frame.wgsl`); a test
//! compares sizes and offsets with the naga-parsed declaration.
//!
//! Every position a shader sees is camera-relative (see [`crate::camera`]); the only absolute
//! coordinates that reach f32 are the eye's height and the eye's position modulo each wave
//! patch (reduced in f64), which is what tiling the maps needs.

use crate::stage::{Shading, Surface, Waves};
use bytemuck::{Pod, Zeroable};
use glam::{DMat4, DVec3, DVec4};

use crate::camera::{Camera, to_cols_f32};
use crate::floating::BoatPose;
use crate::plan::{FramePlan, Pass};
use crate::scene::{Object, Scene, Shape, Sun};
use crate::sky::{PreethamSky, SkyParams};
pub use crate::terrain::{TerrainBlock, terrain_triangles};
use crate::waves::WaveMaps;

mod boat;
mod foam;
mod triangles;

pub use crate::geometry::ProjectedGridBlock;
pub use crate::objects::{ObjectVertex, SPHERE_BANDS, SPHERE_SEGMENTS};
pub use crate::scene::coastal_sea;
use crate::scene::finite_time;
use crate::switch::switch;

pub use triangles::{
    ObjectsKey, object_triangles, pass_floor_triangles, pass_object_triangles, pass_triangles,
};

pub use boat::{
    BOW_SHARE, BoatRun, HULL_TRIANGLES, ObjectPoses, SETTLE_STEPS, hull_bounds, hull_faces,
    hull_triangles, resting_pose, settle, settle_periods, settle_window_s, settled_pose,
};

/// Phong exponent s of the sun's specular term, a whole number (the water stage raises to it
/// by repeated multiplication, `pow_int`) (seed 000 §5.3: "s is specified before
/// rendering"); 400 gives a glitter path a few degrees wide.
pub const SUN_SPECULAR_EXPONENT: f32 = 400.0;
/// Scale of the reflection-map lookup shift by the bump value (§5.2, Fig. 5), in texture
/// units per unit of normal tilt.
pub const REFLECTION_DISTORTION: f32 = 0.04;
/// The same for the refraction map.
pub const REFRACTION_DISTORTION: f32 = 0.03;
pub use crate::scene::{DEEP_WATER_COLOR, MAX_SCALES, WATER_EXTINCTION_PER_M};

/// The view from the eye (every stage that draws in the main view or its maps).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ViewBlock {
    /// Camera-relative view-projection (reversed-Z infinite).
    pub view_proj: [[f32; 4]; 4],
    /// (width, height) of the main view, pixels.
    pub viewport_size: [f32; 2],
    /// (1/width, 1/height).
    pub inv_viewport_size: [f32; 2],
    /// The eye's height above the mean sea plane, m.
    pub eye_height: f32,
    /// Padding to 16 bytes.
    pub pad0: f32,
    /// Padding.
    pub pad1: f32,
    /// Padding.
    pub pad2: f32,
}

/// The sun: its light and its shadow map's camera.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct SunBlock {
    /// Camera-relative orthographic view-projection of the sun's shadow map (depth 0 near
    /// the sun, 1 far, `Less`).
    pub shadow_view_proj: [[f32; 4]; 4],
    /// Unit direction towards the sun.
    pub direction: [f32; 3],
    /// 1 when the sun lights the scene (above the horizon, intensity > 0), else 0.
    pub lit: f32,
    /// Sun colour × intensity, linear RGB.
    pub radiance: [f32; 3],
    /// Padding to 16 bytes.
    pub pad: f32,
}

/// Where the wave maps tile under the water mesh (stage `waves`, technique `fft`: the
/// displacement and bump patches).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct WaveTilingBlock {
    /// (c.x mod L_d, c.z mod L_d), m: the water mesh's reference point c in the displacement
    /// tile (reduced in f64). c sits on a displacement grid point, so a near-patch vertex
    /// lands exactly on a map sample.
    pub displacement_origin: [f32; 2],
    /// (c.x mod L_b, c.z mod L_b), m: the same in the bump tile.
    pub bump_origin: [f32; 2],
    /// (c.x − eye.x, c.z − eye.z), m: where the mesh's reference point is relative to the
    /// eye (formed in f64).
    pub mesh_offset: [f32; 2],
    /// Padding to 16 bytes.
    pub pad0: f32,
    /// Padding.
    pub pad1: f32,
    /// 1/L_d, 1/m.
    pub inv_displacement_size: f32,
    /// 1/L_b, 1/m.
    pub inv_bump_size: f32,
    /// Half a texel of the displacement map, 0.5/N_d.
    pub displacement_half_texel: f32,
    /// Half a texel of the bump map, 0.5/N_b.
    pub bump_half_texel: f32,
}

/// The water's optics, shared by every shading technique and the refraction map.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct WaterBlock {
    /// Deep-water colour, linear RGB (eq. 4's C_deep_water).
    pub color: [f32; 3],
    /// Diffuse extinction K, 1/m.
    pub extinction_per_m: f32,
    /// η of the water.
    pub eta: f32,
    /// 1/η: the refraction map's apparent-depth scale.
    pub inv_eta: f32,
    /// The water-volume colour's model: 0 the constant `color` (shading `hu`), 1 seed 001's
    /// eq. 8, (0.30, 0.73, 0.63)^(k_d·y) under the downwelling light at depth y.
    pub volume_model: f32,
    /// Eq. 8's k_d, 1/m.
    pub kd_per_m: f32,
}

/// Parameters of shading technique `chiu` (seed 001 eqs. 2–8; the scene's `[chiu]`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ChiuShadingBlock {
    /// Eq. 6's ζ, m.
    pub zeta_m: f32,
    /// Eq. 5's shininess per metre of view depth.
    pub shininess_per_m: f32,
    /// 1: the reflection and refraction maps clip the objects at the wave height under each
    /// fragment (§3.5.1, Fig. 4), 0: at the plane y = 0 (seed 000).
    pub clip_waves: f32,
    /// Padding to 16 bytes.
    pub pad1: f32,
}

/// Parameters of shading technique `ggx` (seed 002; the scene's `[ggx]`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct GgxShadingBlock {
    /// The GGX distribution's α = roughness².
    pub alpha: f32,
    /// 0: eq. 2's exact Fresnel, 1: Schlick's.
    pub schlick_fresnel: f32,
    /// 0: Smith's height-correlated G2, 1: the seed's Schlick-GGX.
    pub schlick_geometry: f32,
    /// Schlick's F0 = ((η − 1)/(η + 1))², formed in f64.
    pub f0: f32,
}

/// Eq. 1 of seed 001 (shading `chiu`): the surface Σ_i a_i·D(x/s_i) of the displacement map
/// D, per scale i (up to [`MAX_SCALES`]; unused ones have weight 0): 1/(L·s_i), a_i, the
/// mesh's reference point modulo L·s_i (f64, rounded once), and −log2 s_i (the footprint's
/// LOD on the stretched map). `count` = 0: the single map of seed 000.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct MultiScaleBlock {
    /// 1/(L·s_i).
    pub inv_size: [f32; 4],
    /// a_i = 1/√n.
    pub weight: [f32; 4],
    /// The reference point's x modulo L·s_i.
    pub origin_x: [f32; 4],
    /// The reference point's z modulo L·s_i.
    pub origin_z: [f32; 4],
    /// −log2 s_i.
    pub lod_offset: [f32; 4],
    /// The number of scales (0: eq. 1 off).
    pub count: f32,
    /// Padding to 16 bytes.
    pub pad0: f32,
    /// Padding.
    pub pad1: f32,
    /// Padding.
    pub pad2: f32,
}

impl MultiScaleBlock {
    /// The block for `scales` over a displacement patch of side `patch` with the mesh's
    /// reference point at `origin` (world x, z).
    pub fn new(scales: &[f64], patch: f64, origin: [f64; 2]) -> Self {
        let mut b = Self::zeroed();
        let n = scales.len().min(MAX_SCALES);
        let a = 1.0 / (n as f64).sqrt();
        for (i, &s) in scales.iter().take(n).enumerate() {
            let size = patch * s;
            b.inv_size[i] = (1.0 / size) as f32;
            b.weight[i] = a as f32;
            b.origin_x[i] = origin[0].rem_euclid(size) as f32;
            b.origin_z[i] = origin[1].rem_euclid(size) as f32;
            b.lod_offset[i] = (-s.log2()) as f32;
        }
        b.count = n as f32;
        b
    }
}

/// Parameters of shading technique `hu` (seed 000 eq. 3).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct HuShadingBlock {
    /// Phong exponent s of the sun's highlight, a whole number.
    pub phong_exponent: f32,
    /// Shift of the reflection-map lookup per unit of normal tilt (§5.2).
    pub reflection_distortion: f32,
    /// The same for the refraction map.
    pub refraction_distortion: f32,
    /// a of the Fresnel textures' grazing lookup s = a·u + ½
    /// ([`crate::tables::TextureMapping::grazing_scale`]).
    pub fresnel_scale: f32,
}

/// Parameters of the far-field technique (`crate::far_field`), all f32.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FarFieldBlock {
    /// [`crate::far_field::FarField::code`]: 0 none, 1 mip, 2 variance.
    pub mode: f32,
    /// Added to every LOD (0: the footprint's).
    pub lod_bias: f32,
    /// δ = 2·tan(fov_y/2)/height: radians a pixel subtends at the image centre.
    pub pixel_angle: f32,
    /// 1/[`crate::far_field::SIGMA_MAX`].
    pub inv_sigma_max: f32,
    /// log2(N/L) of the displacement map: LOD = log2(footprint in m) + this.
    pub lod_offset_d: f32,
    /// The same for the bump map.
    pub lod_offset_b: f32,
    /// u = r·a + b of the filtered Fresnel table (r on texel centres i·R/(N_r − 1)).
    pub filter_r_scale: f32,
    /// b of that.
    pub filter_r_offset: f32,
    /// v = t·c + d (t = sqrt(σ/Σ) on texel centres j/(N_σ − 1)).
    pub filter_t_scale: f32,
    /// d of that.
    pub filter_t_offset: f32,
    /// log2 of the most taps a pixel takes along its footprint's long axis (anisotropic
    /// filtering; 0: isotropic, the long side's LOD).
    pub max_aniso_log2: f32,
    /// The sun's lobe in the Fresnel table's coordinates ([`crate::far_field::SunLobe`]):
    /// cos α, where it peaks along the sun's azimuth.
    pub sun_centre: f32,
    /// Its radial half Gaussian's variance towards the zenith.
    pub sun_above: f32,
    /// Its radial half Gaussian's variance towards the rim.
    pub sun_below: f32,
    /// Its tangential Gaussian's variance, 1/s.
    pub sun_tangential: f32,
    /// Its value beyond the table's rim, exp(−s α²/2).
    pub sun_rim: f32,
    /// 2^(−3/4)·τ: the water mesh's typical triangle leg per metre of distance (the near
    /// patch splits a triangle whose hypotenuse subtends more than τ, so a leaf's leg lies in
    /// (τd/2, τd/√2]; this is their geometric mean).
    pub mesh_leg_scale: f32,
    /// The mesh's finest leg, the displacement grid's spacing, m.
    pub mesh_leg_min: f32,
    /// Padding.
    pub pad0: f32,
    /// Padding.
    pub pad1: f32,
}

impl FarFieldBlock {
    /// The block of `far_field` for a camera of vertical field of view `fov_y` (rad) and
    /// `height` pixels, over maps of `n_d` and `n_b` texels on `l_d` and `l_b` metres.
    pub fn new(
        far_field: crate::far_field::FarField,
        fov_y: f64,
        height: u32,
        (n_d, l_d): (u32, f64),
        (n_b, l_b): (u32, f64),
    ) -> Self {
        use crate::far_field::{FILTER_RADII, FILTER_SIGMAS, RADIUS_MAX, SIGMA_MAX};
        let centres = |n: u32, range: f64| {
            let n = f64::from(n);
            ((((n - 1.0) / n) / range) as f32, (0.5 / n) as f32)
        };
        let (filter_r_scale, filter_r_offset) = centres(FILTER_RADII, RADIUS_MAX);
        let (filter_t_scale, filter_t_offset) = centres(FILTER_SIGMAS, 1.0);
        Self {
            mode: far_field.code(),
            lod_bias: 0.0,
            pixel_angle: (2.0 * (0.5 * fov_y).tan() / f64::from(height.max(1))) as f32,
            inv_sigma_max: (1.0 / SIGMA_MAX) as f32,
            lod_offset_d: (f64::from(n_d) / l_d).log2() as f32,
            lod_offset_b: (f64::from(n_b) / l_b).log2() as f32,
            filter_r_scale,
            filter_r_offset,
            filter_t_scale,
            filter_t_offset,
            max_aniso_log2: crate::far_field::MAX_ANISOTROPY.ilog2() as f32,
            sun_centre: 1.0,
            sun_above: 0.0,
            sun_below: 0.0,
            sun_tangential: 0.0,
            sun_rim: 0.0,
            mesh_leg_scale: 0.0,
            mesh_leg_min: 1e-30,
            pad0: 0.0,
            pad1: 0.0,
        }
    }

    /// The block with the water mesh's scale: its split threshold τ (rad) and its finest leg
    /// (m). Without it the mesh counts as finer than any footprint (every displacement slope
    /// under the pixel is geometry).
    pub fn with_mesh(self, split_threshold: f64, finest_leg_m: f64) -> Self {
        Self {
            mesh_leg_scale: (2f64.powf(-0.75) * split_threshold) as f32,
            mesh_leg_min: finest_leg_m as f32,
            ..self
        }
    }

    /// The block with the sun's lobe for a sun whose unit direction has vertical component
    /// `sin_elevation`, under a Phong exponent `exponent`
    /// ([`crate::far_field::sun_lobe`], in f64, so both back ends read the same constants).
    pub fn with_sun(self, sin_elevation: f64, exponent: f64) -> Self {
        // Its 200-step bisection was a quarter of a steady `hu` frame's `prepare`, asked again every
        // frame for the same sun.
        static KEPT: crate::kept::Kept<[u64; 2], crate::far_field::SunLobe> =
            crate::kept::Kept::new();
        let key = [sin_elevation.to_bits(), exponent.to_bits()];
        let lobe = KEPT.get(key, || crate::far_field::sun_lobe(sin_elevation, exponent));
        Self {
            sun_centre: lobe.centre as f32,
            sun_above: lobe.above as f32,
            sun_below: lobe.below as f32,
            sun_tangential: lobe.tangential as f32,
            sun_rim: lobe.rim as f32,
            ..self
        }
    }
}

/// Which optional maps the frame made: 1.0 when the pass ran, 0.0 when its 1×1 zero map is
/// bound in its place (the shaders multiply what they read by it).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct PassFlags {
    /// `waves`.
    pub waves: f32,
    /// `reflection_map`.
    pub reflection_map: f32,
    /// `refraction_map`.
    pub refraction_map: f32,
    /// `shadow_map`.
    pub shadow_map: f32,
}

/// Light from the environment for the objects' diffuse shading.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct AmbientBlock {
    /// Irradiance-like ambient light from the sky on an upward surface, divided by π.
    pub sky: [f32; 3],
    /// Padding to 16 bytes.
    pub pad: f32,
}

/// Uniforms of the `objects`, `shadow` and `water` stages (WGSL `FrameUniforms`): one named
/// block per concern, so that a new technique adds a block or a field instead of
/// re-purposing a lane. Each block is declared with the same names in
/// `shaders/shared/frame.wgsl`; the registry's layout check compares every member's name,
/// offset and type with the naga-parsed WGSL.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FrameUniforms {
    /// The view from the eye.
    pub view: ViewBlock,
    /// The sun.
    pub sun: SunBlock,
    /// The wave maps' tiling.
    pub tiling: WaveTilingBlock,
    /// The water's optics.
    pub water: WaterBlock,
    /// Shading technique `hu`.
    pub hu: HuShadingBlock,
    /// Which optional maps were made.
    pub passes: PassFlags,
    /// The environment's ambient light.
    pub ambient: AmbientBlock,
    /// The far-field technique.
    pub far: FarFieldBlock,
    /// Surface `projected_grid`.
    pub grid: ProjectedGridBlock,
    /// Shading technique `chiu`.
    pub chiu: ChiuShadingBlock,
    /// The sea floor.
    pub terrain: TerrainBlock,
    /// Eq. 1's multi-scale sampling.
    pub scales: MultiScaleBlock,
    /// Waves technique `gerstner`'s waves (count 0 under `fft`).
    pub gerstner: crate::waves::gerstner::GerstnerBlock,
    /// Shading technique `ggx`.
    pub ggx: GgxShadingBlock,
    /// Surface `clipmap` (`levels` 0 under the other surfaces).
    pub clip: crate::geometry::ClipmapBlock,
    /// Shading `ggx`'s detail normal map (`count` 0 without it).
    pub detail: crate::detail::DetailBlock,
    /// Stage `foam`.
    pub foam: crate::foam::FoamBlock,
    /// Waves technique `coastal` (`shape[0]` 0 under the other waves techniques).
    pub coastal: crate::waves::coastal::CoastalBlock,
    /// Shading technique `coastal`.
    pub coastal_shading: crate::waves::coastal::CoastalShadingBlock,
}

// The clipmap a frame draws: here, where the scene and the plan are known, so the clipmap's
// geometry depends on neither.
impl crate::geometry::Clipmap {
    /// The clipmap of a frame of `plan` seen through `camera`, if its surface is `clipmap`.
    pub fn of_frame(
        scene: &crate::scene::Scene,
        camera: &crate::camera::Camera,
        plan: &crate::plan::FramePlan,
    ) -> Option<crate::Result<Self>> {
        plan.techniques.surface().clipmap_levels().then(|| {
            Self::new(
                [camera.eye.x, camera.eye.z],
                camera.eye.y,
                scene.quality.clipmap_cell_m,
                scene.quality.clipmap_cells,
            )
        })
    }
}

/// Uniforms of the `fresnel_table` stage (WGSL `FresnelTableUniforms`).
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct FresnelTableUniforms {
    /// η of the table: the water's index for the surface seen from above, its inverse from
    /// below.
    pub eta: f32,
    /// N of the N×N table.
    pub size: u32,
    /// [`crate::tables::TextureMapping::code`]: 0 the whole hemisphere (docs/design.md), 1 the
    /// paper's half range, 2 the grazing mapping.
    pub mapping: u32,
    /// 2/(N − 1), the step of the grazing mapping's u between texel centres, formed in f64
    /// and rounded once (0 for N < 2). A multiplication by it, not a division in the shader:
    /// lavapipe's f32 division is not always the correctly rounded one, and one ulp of u moved
    /// a texel's F by 3e-5 next to the critical angle of the table seen from below.
    pub step: f32,
    /// 4/(N − 1)², the factor of the grazing mapping's 1 − u² = 4 i (N − 1 − i)/(N − 1)²,
    /// likewise (0 for N < 2).
    pub step2: f32,
    /// Padding to 32 bytes.
    pub pad0: u32,
    /// Padding.
    pub pad1: u32,
    /// Padding.
    pub pad2: u32,
}

impl FresnelTableUniforms {
    /// The uniforms of an `size`² table for index ratio `eta` under `mapping`.
    pub fn new(eta: f32, size: u32, mapping: crate::tables::TextureMapping) -> Self {
        let last = f64::from(size) - 1.0;
        let (step, step2) = if size >= 2 {
            ((2.0 / last) as f32, (4.0 / (last * last)) as f32)
        } else {
            (0.0, 0.0)
        };
        Self { eta, size, mapping: mapping.code(), step, step2, pad0: 0, pad1: 0, pad2: 0 }
    }
}

/// Uniforms of the `wave_mips` stage (WGSL `WaveMipsUniforms`): one dispatch's level sizes.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct WaveMipsUniforms {
    /// Width of the level written, texels.
    pub width: u32,
    /// Its height.
    pub height: u32,
    /// Width of the level read (`downsample`).
    pub src_width: u32,
    /// Its height.
    pub src_height: u32,
}

impl WaveMipsUniforms {
    /// The uniforms of a dispatch writing a `dst`-sized level from a `src`-sized one.
    pub fn new(dst: [u32; 2], src: [u32; 2]) -> Self {
        Self { width: dst[0], height: dst[1], src_width: src[0], src_height: src[1] }
    }
}

/// The representative wavelengths (m) of the displacement's and the bump map's waves that
/// `[terrain] wave_damping` scales: waves `gerstner`, their median wavelength for both; waves
/// `fft`, the spectral peak's deep-water wavelength 2πg/ω_p² (at most the patch) and the bump
/// patch's side (its longest wave). `None` under waves `coastal` (its own shoaling).
pub fn damped_wavelengths(scene: &Scene, plan: &FramePlan) -> Option<[f64; 2]> {
    let o = &scene.ocean;
    match plan.techniques.waves() {
        Waves::Coastal => None,
        Waves::Gerstner => Some([scene.gerstner.median_wavelength_m; 2]),
        Waves::Fft => {
            let g = o.dispersion().map_or(9.81, |d| d.gravity);
            let peak = o
                .wave_spectrum()
                .ok()
                .and_then(|s| s.peak_omega())
                .map_or(o.patch_size_m, |w| std::f64::consts::TAU * g / (w * w));
            let bump = o.patch_size_m / f64::from(o.bump_patch_divisor.max(1));
            Some([peak.min(o.patch_size_m), bump])
        }
    }
}

/// How high the sand is wet, m above the sea plane: the coastal waves' run-up (ocean-core
/// waves::coastal, "The shore zones"); 0 (no wet band) under the other waves techniques.
pub fn wet_top_m(scene: &Scene) -> f64 {
    if !scene.techniques().waves().runs_up_a_shore() {
        return 0.0;
    }
    // The run-up does not depend on the time: any finite one.
    coastal_sea(scene, 0.0).map_or(0.0, |s| s.run_up_m)
}

/// The world box of an object, m (a boat's at `pose`, or at rest without one); `None` for an
/// object without its shape's key.
pub fn object_bounds(o: &Object, pose: Option<&BoatPose>) -> Option<(DVec3, DVec3)> {
    let c = DVec3::from_array(o.center);
    let half = match o.shape()? {
        Shape::Sphere { radius } => DVec3::splat(radius),
        Shape::Box { size } => DVec3::from_array(size) * 0.5,
        Shape::Boat { size, .. } => {
            let pose = pose.copied().or_else(|| resting_pose(o))?;
            return Some(hull_bounds(size, &pose));
        }
    };
    Some((c - half, c + half))
}

/// The sun's orthographic shadow camera: looks along −sun_dir at the bounding sphere of the
/// objects above the water (camera-relative; boats at `poses`), depth 0 at the sphere's
/// sun-side and 1 behind. `None` without such objects.
pub fn sun_view_proj(
    objects: &[Object],
    poses: &ObjectPoses,
    eye: DVec3,
    sun_dir: DVec3,
) -> Option<DMat4> {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for (i, o) in objects.iter().enumerate() {
        let (a, b) = object_bounds(o, poses.get(i))?;
        if b.y <= 0.0 {
            continue;
        }
        lo = lo.min(a);
        hi = hi.max(b);
    }
    if !lo.is_finite() {
        return None;
    }
    let centre = 0.5 * (lo + hi) - eye;
    // The shadow can fall on the water as far as the objects' height above it, along the sun.
    let radius = 0.5 * (hi - lo).length() + hi.y.max(0.0) / sun_dir.y.max(0.05);
    let d = sun_dir.normalize();
    let right = if d.cross(DVec3::Y).length_squared() > 1e-12 {
        d.cross(DVec3::Y).normalize()
    } else {
        DVec3::X
    };
    let up = right.cross(d);
    let fwd = -d;
    // View: rows right, up, −fwd, relative to the sphere's centre; ortho: x,y/radius, depth
    // (−z_view + radius)/(2 radius) ∈ [0, 1].
    let view = DMat4::from_cols(
        DVec4::new(right.x, up.x, -fwd.x, 0.0),
        DVec4::new(right.y, up.y, -fwd.y, 0.0),
        DVec4::new(right.z, up.z, -fwd.z, 0.0),
        DVec4::W,
    ) * DMat4::from_translation(-centre);
    let proj = DMat4::from_cols(
        DVec4::new(1.0 / radius, 0.0, 0.0, 0.0),
        DVec4::new(0.0, 1.0 / radius, 0.0, 0.0),
        DVec4::new(0.0, 0.0, -0.5 / radius, 0.0),
        DVec4::new(0.0, 0.0, 0.5, 1.0),
    );
    Some(proj * view)
}

impl FrameUniforms {
    /// The uniforms of a scene's frame for a camera, a plan, the water mesh's reference
    /// point `mesh_origin` (world x, z) and the frame's boats (`poses`: the shadow map's box).
    pub fn new(
        scene: &Scene,
        camera: &Camera,
        plan: &FramePlan,
        mesh_origin: [f64; 2],
        poses: &ObjectPoses,
    ) -> Self {
        let o = &scene.ocean;
        let eye = camera.eye;
        let l_d = o.patch_size_m;
        let l_b = o.patch_size_m / o.bump_patch_divisor as f64;
        let (sun_dir, sun_radiance, sun_on) = match &scene.sun {
            Some(s) => {
                let d = DVec3::from_array(s.direction).normalize();
                let on = d.y > 0.0 && s.intensity > 0.0;
                let rad = DVec3::from_array(s.color) * s.intensity;
                (d, rad, on)
            }
            None => (DVec3::Y, DVec3::ZERO, false),
        };
        let shadow = sun_view_proj(&scene.objects, poses, eye, sun_dir).unwrap_or(DMat4::IDENTITY);
        let flag = |p: Pass| switch(plan.runs(p));
        let eta = scene.water.ior as f32;
        let shading = plan.techniques.shading();
        FrameUniforms {
            view: ViewBlock {
                view_proj: to_cols_f32(camera.view_proj()),
                viewport_size: [camera.width as f32, camera.height as f32],
                inv_viewport_size: [1.0 / camera.width as f32, 1.0 / camera.height as f32],
                eye_height: eye.y as f32,
                pad0: 0.0,
                pad1: 0.0,
                pad2: 0.0,
            },
            sun: SunBlock {
                shadow_view_proj: to_cols_f32(shadow),
                direction: [sun_dir.x as f32, sun_dir.y as f32, sun_dir.z as f32],
                lit: if sun_on { 1.0 } else { 0.0 },
                radiance: [sun_radiance.x as f32, sun_radiance.y as f32, sun_radiance.z as f32],
                pad: 0.0,
            },
            tiling: WaveTilingBlock::new(o, mesh_origin, eye),
            water: WaterBlock {
                color: scene.water.color.map(|c| c as f32),
                extinction_per_m: scene.water.extinction_per_m as f32,
                eta,
                inv_eta: 1.0 / eta,
                volume_model: switch(shading.chiu_optics()),
                kd_per_m: scene.chiu.kd_per_m as f32,
            },
            hu: HuShadingBlock {
                phong_exponent: SUN_SPECULAR_EXPONENT,
                reflection_distortion: REFLECTION_DISTORTION,
                refraction_distortion: REFRACTION_DISTORTION,
                fresnel_scale: crate::tables::TextureMapping::grazing_scale(
                    plan.fresnel_table_size,
                ),
            },
            passes: PassFlags {
                waves: flag(Pass::Waves),
                reflection_map: flag(Pass::ReflectionMap),
                refraction_map: flag(Pass::RefractionMap),
                shadow_map: flag(Pass::ShadowMap),
            },
            ambient: AmbientBlock { sky: [0.0; 3], pad: 0.0 },
            far: FarFieldBlock::new(
                plan.techniques.far_field(),
                camera.fov_y,
                camera.height,
                (o.resolution, l_d),
                (o.bump_resolution, l_b),
            )
            .with_sun(sun_dir.normalize_or_zero().y, f64::from(SUN_SPECULAR_EXPONENT))
            .with_mesh(scene.quality.lod_split_threshold, l_d / f64::from(o.resolution.max(1))),
            grid: grid_block(scene, camera, plan),
            chiu: ChiuShadingBlock {
                zeta_m: scene.chiu.zeta_m as f32,
                shininess_per_m: scene.chiu.shininess_per_m as f32,
                clip_waves: switch(shading.chiu_optics()),
                pad1: 0.0,
            },
            terrain: TerrainBlock::new(
                scene.terrain.as_ref(),
                scene.chiu.open_sea_depth_m,
                eye,
                sun_on.then_some(sun_dir),
                scene.water.ior,
                damped_wavelengths(scene, plan),
            ),
            scales: if shading.chiu_optics() {
                MultiScaleBlock::new(&scene.chiu.scales, l_d, mesh_origin)
            } else {
                MultiScaleBlock::zeroed()
            },
            gerstner: match (plan.techniques.waves(), o.dispersion()) {
                (Waves::Gerstner, Ok(d)) => crate::waves::gerstner::GerstnerBlock::new(
                    &scene.gerstner.at(o.time_s, &d, o.wind_direction_deg),
                    mesh_origin,
                ),
                _ => Zeroable::zeroed(),
            },
            ggx: GgxShadingBlock::new(scene),
            clip: match crate::geometry::Clipmap::of_frame(scene, camera, plan) {
                Some(Ok(c)) => c.block(
                    o.wave_spectrum()
                        .ok()
                        .and_then(|s| s.peak_omega())
                        .map(|w| std::f64::consts::TAU * crate::GRAVITY / (w * w)),
                ),
                _ => Zeroable::zeroed(),
            },
            detail: detail_block(scene, shading, mesh_origin),
            foam: crate::foam::FoamBlock::new(
                scene,
                plan.techniques.foam(),
                plan.techniques.waves(),
                mesh_origin,
            ),
            coastal: match plan.techniques.waves() {
                Waves::Coastal => coastal_sea(scene, o.time_s)
                    .map_or_else(|_| Zeroable::zeroed(), |sea| sea.block(mesh_origin)),
                Waves::Fft | Waves::Gerstner => Zeroable::zeroed(),
            },
            coastal_shading: crate::waves::coastal::CoastalShadingBlock::new(
                &scene.coastal,
                scene.water.ior,
            ),
        }
    }
}

impl WaveTilingBlock {
    /// The maps' tiling for a mesh whose reference point is world (x, z) `mesh_origin`, seen
    /// from `eye`.
    fn new(o: &crate::scene::Ocean, mesh_origin: [f64; 2], eye: DVec3) -> Self {
        let l_d = o.patch_size_m;
        let l_b = o.patch_size_m / o.bump_patch_divisor as f64;
        WaveTilingBlock {
            displacement_origin: [
                mesh_origin[0].rem_euclid(l_d) as f32,
                mesh_origin[1].rem_euclid(l_d) as f32,
            ],
            bump_origin: [
                mesh_origin[0].rem_euclid(l_b) as f32,
                mesh_origin[1].rem_euclid(l_b) as f32,
            ],
            mesh_offset: [(mesh_origin[0] - eye.x) as f32, (mesh_origin[1] - eye.z) as f32],
            pad0: 0.0,
            pad1: 0.0,
            inv_displacement_size: (1.0 / l_d) as f32,
            inv_bump_size: (1.0 / l_b) as f32,
            displacement_half_texel: (0.5 / o.resolution as f64) as f32,
            bump_half_texel: (0.5 / o.bump_resolution as f64) as f32,
        }
    }
}

impl GgxShadingBlock {
    /// Shading `ggx`'s block of a scene's `[ggx]` and water.
    fn new(scene: &Scene) -> Self {
        let eta = scene.water.ior;
        GgxShadingBlock {
            alpha: crate::ggx::alpha_from_roughness(scene.ggx.roughness) as f32,
            schlick_fresnel: switch(scene.ggx.fresnel == crate::scene::GgxFresnel::Schlick),
            schlick_geometry: switch(scene.ggx.geometry == crate::scene::GgxGeometry::SchlickGgx),
            f0: (((eta - 1.0) / (eta + 1.0)).powi(2)) as f32,
        }
    }
}

/// The grid block of the frame's surface: the projected grid's or the shore grid's, zero for
/// the meshes drawn from vertex buffers or levels.
fn grid_block(scene: &Scene, camera: &Camera, plan: &FramePlan) -> ProjectedGridBlock {
    let cell_px = scene.quality.projected_grid_cell_px;
    match plan.techniques.surface() {
        Surface::ProjectedGrid => ProjectedGridBlock::new(camera, plan.wave_bound_m, cell_px),
        Surface::ShoreGrid => crate::geometry::shore_grid::block(camera, cell_px),
        Surface::HuPatches | Surface::Clipmap => ProjectedGridBlock::zeroed(),
    }
}

/// Shading `ggx`'s detail normal map (zero under the other shadings or without detail).
fn detail_block(
    scene: &Scene,
    shading: Shading,
    mesh_origin: [f64; 2],
) -> crate::detail::DetailBlock {
    let (g, o) = (&scene.ggx, &scene.ocean);
    if !(shading.detail_map() && g.detail_strength > 0.0) {
        return Zeroable::zeroed();
    }
    crate::detail::DetailBlock::new(
        &crate::detail::detail_waves(g.detail_wavelength_m, g.detail_strength),
        g.detail_speed_m_s,
        o.wind_direction_deg,
        o.time_s,
        mesh_origin,
    )
}

/// The height query of a frame of `plan` at time `t` (s): under waves `fft` the displacement
/// map's field, summed over eq. 1's scales when the frame's shading is `chiu` (as the water's
/// vertices sample it); under waves `gerstner` the frame's Gerstner waves. Either way a
/// floating object agrees with the picture. [`SurfaceSource`] makes it at many times.
///
/// # Errors
/// The scene's spectrum, modes or dispersion cannot be built, or a non-finite time.
pub fn surface_query(
    scene: &Scene,
    plan: &FramePlan,
    t: f64,
) -> crate::Result<crate::waves::WaveSurface> {
    SurfaceSource::new(scene, plan)?.at(t)
}

/// The height query of a frame's sea at any time ([`surface_query`]), with what does not
/// depend on time (the FFT's modes, the dispersion) made once: a boat's settle run asks for
/// the surface at every sub-step.
pub struct SurfaceSource<'a> {
    scene: &'a Scene,
    sea: Sea,
    /// The displacement's representative wavelength that `[terrain] wave_damping` scales
    /// ([`damped_wavelengths`]); `None` under waves `coastal`.
    damped_m: Option<f64>,
}

enum Sea {
    Gerstner(crate::dispersion::Dispersion),
    Fft { modes: crate::waves::WaveModes, chiu: bool },
    Coastal(Box<crate::waves::coastal::CoastalSea>),
}

impl<'a> SurfaceSource<'a> {
    /// The sea of `scene` as `plan` draws it.
    ///
    /// # Errors
    /// The scene's spectrum, modes or dispersion cannot be built.
    pub fn new(scene: &'a Scene, plan: &FramePlan) -> crate::Result<Self> {
        let o = &scene.ocean;
        let sea = match plan.techniques.waves() {
            Waves::Gerstner => Sea::Gerstner(o.dispersion()?),
            Waves::Coastal => Sea::Coastal(Box::new(coastal_sea(scene, o.time_s)?)),
            Waves::Fft => Sea::Fft {
                modes: o.displacement_modes()?,
                chiu: plan.techniques.shading().chiu_optics(),
            },
        };
        Ok(Self { scene, sea, damped_m: damped_wavelengths(scene, plan).map(|l| l[0]) })
    }

    /// The height query at time `t`, s.
    ///
    /// # Errors
    /// A non-finite time.
    pub fn at(&self, t: f64) -> crate::Result<crate::waves::WaveSurface> {
        let surface = self.undamped_at(t)?;
        // `[terrain] wave_damping`: the waves kept over the floor, as the vertices keep them.
        let inv = match (self.damped_m, &self.scene.terrain) {
            (Some(l), Some(t)) => {
                let v = 1.0 / (t.wave_damping * l);
                if v.is_finite() && v > 0.0 { v } else { 0.0 }
            }
            _ => 0.0,
        };
        if inv == 0.0 {
            return Ok(surface);
        }
        let terrain = Box::new(self.scene.terrain.clone().expect("matched above"));
        Ok(crate::waves::WaveSurface::Damped { inner: Box::new(surface), terrain, inv })
    }

    fn undamped_at(&self, t: f64) -> crate::Result<crate::waves::WaveSurface> {
        let o = &self.scene.ocean;
        match &self.sea {
            Sea::Gerstner(dispersion) => {
                finite_time(t)?;
                let sea = self.scene.gerstner.at(t, dispersion, o.wind_direction_deg);
                Ok(crate::waves::WaveSurface::Gerstner(sea))
            }
            Sea::Coastal(sea) => {
                finite_time(t)?;
                Ok(crate::waves::WaveSurface::Coastal(Box::new(sea.at_time(t))))
            }
            Sea::Fft { modes, chiu } => {
                let q = crate::waves::SurfaceQuery::new(modes, t, o.choppiness)?;
                Ok(crate::waves::WaveSurface::Fft(if *chiu {
                    q.with_scales(&self.scene.chiu.scales)
                } else {
                    q
                }))
            }
        }
    }
}

/// The sky of a scene: its sun, or, without one, the default sun's sky at zero intensity (the
/// daylight sky without a disc or sunlight). Both back ends draw the `sky` stage and the
/// water's reflections from it.
pub fn scene_sky(scene: &Scene) -> crate::Result<PreethamSky> {
    let default = Sun { intensity: 0.0, ..Sun::default() };
    let sun = scene.sun.as_ref().unwrap_or(&default);
    Ok(PreethamSky::new(SkyParams::new(sun.direction, sun.turbidity, sun.color, sun.intensity)?))
}

/// The sky's mean radiance weighted by cos θ over the upper hemisphere, i.e. the irradiance of
/// an upward surface divided by π: the objects' ambient term ([`AmbientBlock::sky`]).
/// A fixed 32 × 64 midpoint grid in (cos² θ, φ) — uniform in projected solid angle — so it is
/// deterministic.
///
/// Every frame asks for it and a sky seldom changes between frames, so it is kept
/// (`crate::kept`): the sum is 2,048 evaluations of the Preetham model, about 0.3 ms, which was
/// most of a real-time frame's CPU encode (issue 37).
pub fn sky_ambient(sky: &PreethamSky) -> [f32; 3] {
    static KEPT: crate::kept::Kept<PreethamSky, [f32; 3]> = crate::kept::Kept::new();
    KEPT.get(*sky, || sky_ambient_of(sky))
}

/// [`sky_ambient`] computed.
fn sky_ambient_of(sky: &PreethamSky) -> [f32; 3] {
    let (rows, cols) = (32, 64);
    let mut sum = DVec3::ZERO;
    for i in 0..rows {
        let cos2 = (i as f64 + 0.5) / rows as f64;
        let (cos_t, sin_t) = (cos2.sqrt(), (1.0 - cos2).sqrt());
        for j in 0..cols {
            let phi = std::f64::consts::TAU * (j as f64 + 0.5) / cols as f64;
            let d = [sin_t * phi.cos(), cos_t, sin_t * phi.sin()];
            sum += DVec3::from_array(sky.sky_radiance(d));
        }
    }
    let mean = sum / (rows * cols) as f64;
    [mean.x as f32, mean.y as f32, mean.z as f32]
}

/// Texels of the water stage's `displacement` binding: (disp_x, height, disp_z, jacobian),
/// row-major as the maps are stored.
pub fn displacement_texels(maps: &WaveMaps<f32>) -> Vec<[f32; 4]> {
    (0..maps.height.len())
        .map(|i| [maps.disp_x[i], maps.height[i], maps.disp_z[i], maps.jacobian[i]])
        .collect()
}

/// Texels of the water stage's `displacement_slopes` binding: (slope_x, slope_z, 0, 0).
pub fn displacement_slope_texels(maps: &WaveMaps<f32>) -> Vec<[f32; 4]> {
    (0..maps.height.len()).map(|i| [maps.slope_x[i], maps.slope_z[i], 0.0, 0.0]).collect()
}

/// Texels of the water stage's `bump` binding: (slope_x, slope_z, height, jacobian).
pub fn bump_texels(maps: &WaveMaps<f32>) -> Vec<[f32; 4]> {
    (0..maps.height.len())
        .map(|i| [maps.slope_x[i], maps.slope_z[i], maps.height[i], maps.jacobian[i]])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::ObjectKind;

    /// The kept answer is the asked sky's: two skies asked in turn each get their own sum,
    /// and the two sums differ (so a stale answer would be seen).
    #[test]
    fn the_kept_sky_ambient_is_the_asked_sky_s() {
        let sky = |turbidity: f64| {
            let params = crate::sky::SkyParams::new([0.3, 0.5, 0.2], turbidity, [1.0; 3], 1.0);
            PreethamSky::new(params.expect("a valid sky"))
        };
        let (clear, hazy) = (sky(2.5), sky(6.0));
        let (a, b) = (sky_ambient_of(&clear), sky_ambient_of(&hazy));
        assert_ne!(a, b);
        for _ in 0..3 {
            assert_eq!(sky_ambient(&clear), a);
            assert_eq!(sky_ambient(&clear), a);
            assert_eq!(sky_ambient(&hazy), b);
        }
    }

    fn object(kind: ObjectKind, center: [f64; 3]) -> Object {
        Object {
            kind,
            center,
            radius: None,
            size: None,
            heading_deg: None,
            mass_kg: None,
            color: [1.0; 3],
        }
    }

    /// Σ (p0 · (p1 × p2))/6 over triangles: the enclosed volume by the divergence theorem,
    /// positive when every face winds counter-clockwise seen from outside.
    fn signed_volume(tris: &[[ObjectVertex; 3]]) -> f64 {
        tris.iter()
            .map(|t| {
                let p = t.map(|v| DVec3::from(v.position.map(f64::from)));
                p[0].dot(p[1].cross(p[2])) / 6.0
            })
            .sum()
    }

    #[test]
    fn meshes_are_closed_and_outward() {
        let objects = [
            Object { radius: Some(2.0), ..object(ObjectKind::Sphere, [1.0, 2.0, 3.0]) },
            Object { size: Some([1.0, 2.0, 3.0]), ..object(ObjectKind::Box, [-10.0, 0.0, 0.0]) },
        ];
        let poses = ObjectPoses::default();
        let sphere = signed_volume(&object_triangles(&objects[..1], &poses, DVec3::ZERO));
        let cube = signed_volume(&object_triangles(&objects[1..], &poses, DVec3::ZERO));
        let exact = 4.0 / 3.0 * std::f64::consts::PI * 8.0;
        assert!((sphere / exact - 1.0).abs() < 0.02, "{sphere}");
        assert!((cube - 6.0).abs() < 1e-5, "{cube}");
    }

    #[test]
    fn the_hull_is_closed_outward_and_posed_by_the_model_matrix() {
        let (l, h, b) = (6.0, 1.0, 2.5);
        let boat = Object {
            size: Some([l, h, b]),
            heading_deg: Some(30.0),
            ..object(ObjectKind::Boat, [4.0, 0.0, -7.0])
        };
        let pose = BoatPose::from_angles(DVec3::new(4.0, -0.3, -7.0), 0.4, 0.1, -0.2);
        let mut poses =
            ObjectPoses::resting(&Scene { objects: vec![boat.clone()], ..Scene::builtin() });
        let resting = poses.get(0).copied().expect("a boat has a resting pose");
        poses = ObjectPoses::from_poses(vec![Some(pose)]);
        let tris = object_triangles(std::slice::from_ref(&boat), &poses, DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(tris.len(), HULL_TRIANGLES as usize);
        // Closed and wound outward: the volume is the prism's, B·H·(L − BOW_SHARE·L/2) = 12.75
        // m³, at any pose and from any eye (f32 positions: ~1e-6 relative).
        let prism = b * h * (l - BOW_SHARE * l / 2.0);
        let v = signed_volume(&tris);
        assert!((v / prism - 1.0).abs() < 1e-5, "{v} vs {prism}");
        // Every face's normal is its triangles' winding normal, and the keel's is −up.
        for t in &tris {
            let p = t.map(|v| DVec3::from(v.position.map(f64::from)));
            let n = DVec3::from(t[0].normal.map(f64::from));
            let winding = (p[1] - p[0]).cross(p[2] - p[0]).normalize();
            assert!(winding.dot(n) > 1.0 - 1e-5, "{winding} vs {n}");
        }
        // The keel: the lowest corners lie on the body's y = 0 plane through the pose.
        let keel: Vec<DVec3> = tris
            .iter()
            .filter(|t| DVec3::from(t[0].normal.map(f64::from)).dot(-pose.up) > 0.999)
            .flat_map(|t| {
                t.map(|v| DVec3::from(v.position.map(f64::from)) + DVec3::new(1.0, 2.0, 3.0))
            })
            .collect();
        assert_eq!(keel.len(), 9, "the keel pentagon's three triangles");
        for p in keel {
            assert!((p - pose.position).dot(pose.up).abs() < 1e-5, "{p}");
        }
        // At rest: level at its draft, the bow along heading_deg (from +x towards +z).
        let d = boat.boat_params().expect("a boat").still_water_draft_m();
        assert!((resting.position - DVec3::new(4.0, -d, -7.0)).length() < 1e-12);
        let heading = 30f64.to_radians();
        assert!((resting.forward - DVec3::new(heading.cos(), 0.0, heading.sin())).length() < 1e-12);
    }
}
