//! [`Scene::validate`]: every value checked against what the f32 pipeline, the geometry and
//! the GPU can represent, so that **validation accepts ⇒ both back ends render only finite
//! pixels** (`tests/scene_properties.rs` holds the scenes at these limits to that).
//!
//! Two layers:
//! - [`LIMITS`], one range per numeric key (vectors and colours per component), each with the
//!   reason for its bounds, declared once (`keys!`) with where a scene holds the key, which
//!   is what validation checks. docs/scenes.md's table, the property test's extreme scenes and
//!   the fuzzer read the same table; `tests/scene_properties.rs` sets each key just past
//!   either bound and expects the refusal to name it.
//! - Cross-key checks: the quantities the frame derives from several keys (the bump map's
//!   band, the time the wave phase holds, the view, the spectrum, the water mesh) are built
//!   here with the constructors the frame uses, and a failure is reported as the scene key it
//!   comes from, never as the internal quantity.

use super::{Object, ObjectKind, Scene, Shape};
use crate::error::number;
use crate::waves::coastal::MAX_CORRECTION_WAVES;
use crate::waves::gerstner::MAX_GERSTNER_WAVES;

/// The accepted range of one numeric scene key, inclusive at both ends (NaN never passes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limit {
    /// The dotted key; `objects.*.` stands for every object.
    pub key: &'static str,
    /// Smallest accepted value (of each component, for a vector).
    pub min: f64,
    /// Largest accepted value (of each component); `inf` where infinity is meaningful.
    pub max: f64,
    /// Why the bounds are where they are.
    pub why: &'static str,
    /// The key takes whole numbers (written without a decimal point).
    pub whole: bool,
}

const fn real(key: &'static str, min: f64, max: f64, why: &'static str) -> Limit {
    Limit { key, min, max, why, whole: false }
}

const fn whole(key: &'static str, min: f64, max: f64, why: &'static str) -> Limit {
    Limit { key, min, max, why, whole: true }
}

/// The largest distance from the origin of any position, per axis, metres. At 1e7 m an f32
/// holds a position to 1 m, and the frame works camera-relative, so coordinates this large
/// still render finite pictures (the camera's own height is bounded more tightly, by the
/// water mesh: [`crate::geometry::MAX_HEIGHT_M`]).
pub const MAX_COORDINATE_M: f64 = 1.0e7;

/// The largest colour component: albedos and radiances beyond a thousand carry no meaning the
/// sun's intensity does not, and the bound keeps radiance × exposure far inside f32.
pub const MAX_COLOUR: f64 = 1.0e3;

/// The largest `sun.intensity`. With [`MAX_COLOUR`] and the largest exposure (1e6), HDR
/// values stay below ~1e17, and the tonemap's x² below 1e35 < f32::MAX (3.4e38).
pub const MAX_SUN_INTENSITY: f64 = 1.0e6;

/// The shortest camera-to-target distance and object size, metres: below a millimetre f32
/// camera-relative positions of 1e6 m scenes can no longer tell the ends apart.
pub const MIN_LENGTH_M: f64 = 1.0e-3;

/// The coarsest displacement grid accepted, metres per sample (`patch_size_m / resolution`).
/// The property test (`tests/scene_properties.rs`) found NaN pixels at the horizon with
/// coarser grids: 21.3 m (a 256 m patch at resolution 12) and coarser, with the camera
/// 1e5 m or more from the origin, at every field of view from 120° to 179°; 16 m never did.
/// The cause, 1/w interpolating to exactly 0 on a far-patch triangle, is open.
pub const MAX_GRID_SPACING_M: f64 = 16.0;

/// What a scene holds of one key: per element (its index, for a key with a `*`), the value's
/// components; empty where the scene does not set the key (an absent `[sun]` or `[terrain]`,
/// an object of another kind).
type Values = Vec<(usize, Vec<f64>)>;

fn one(v: f64) -> Values {
    vec![(0, vec![v])]
}

fn vector(v: &[f64]) -> Values {
    vec![(0, v.to_vec())]
}

/// The elements of an array section that hold the key.
fn each<T>(items: &[T], f: impl Fn(&T) -> Option<Vec<f64>>) -> Values {
    items.iter().enumerate().filter_map(|(i, x)| f(x).map(|v| (i, v))).collect()
}

/// A sphere's radius.
fn radius(o: &Object) -> Option<Vec<f64>> {
    match o.shape() {
        Some(Shape::Sphere { radius }) => Some(vec![radius]),
        _ => None,
    }
}

/// A box's or a boat's size.
fn size(o: &Object) -> Option<Vec<f64>> {
    match o.shape() {
        Some(Shape::Box { size } | Shape::Boat { size, .. }) => Some(size.to_vec()),
        _ => None,
    }
}

/// A boat's heading.
fn heading(o: &Object) -> Option<Vec<f64>> {
    match o.shape() {
        Some(Shape::Boat { heading_deg, .. }) => Some(vec![heading_deg]),
        _ => None,
    }
}

/// A boat's mass, where given.
fn mass(o: &Object) -> Option<Vec<f64>> {
    match o.shape() {
        Some(Shape::Boat { mass_kg: Some(m), .. }) => Some(vec![m]),
        _ => None,
    }
}

/// Declares every numeric key once: its range and why ([`LIMITS`], which docs/scenes.md's
/// table, the fuzzers and the property tests read) and where a scene holds it (which
/// [`Scene::validate`] checks against the range).
macro_rules! keys {
    ($( $kind:ident($key:literal, $min:expr, $max:expr, $why:expr $(,)?) => $values:expr; )+) => {
        /// Every numeric key's range, in scene-file order.
        pub const LIMITS: &[Limit] = &[ $( $kind($key, $min, $max, $why), )+ ];

        /// Where a scene holds each key of [`LIMITS`], in the same order.
        const VALUES: &[fn(&Scene) -> Values] = &[ $( $values, )+ ];
    };
}

keys! {
    real(
        "ocean.wind_speed",
        0.0,
        200.0,
        "m/s at 10 m; 0 is a flat sea, 200 is above any measured surface wind",
    ) => |s| one(s.ocean.wind_speed);
    real("ocean.wind_direction_deg", -1.0e6, 1.0e6, "degrees; any angle, within f32 range")
        => |s| one(s.ocean.wind_direction_deg);
    real(
        "ocean.fetch_km",
        1.0e-3,
        2.0e4,
        "JONSWAP/TMA fetch from 1 m to half the Earth's circumference",
    ) => |s| one(s.ocean.fetch_km);
    real("ocean.depth_m", 1.0e-2, f64::INFINITY, "m; inf is deep water")
        => |s| one(s.ocean.depth_m);
    real(
        "ocean.peak_enhancement",
        1.0,
        20.0,
        "JONSWAP γ: 1 is Pierson–Moskowitz, 3.3 the JONSWAP mean",
    ) => |s| one(s.ocean.peak_enhancement);
    real(
        "ocean.patch_size_m",
        1.0e-2,
        65536.0,
        "m; at most 16 m per sample of the largest grid (MAX_GRID_SPACING_M × 4096)",
    ) => |s| one(s.ocean.patch_size_m);
    whole(
        "ocean.resolution",
        2.0,
        super::MAX_RESOLUTION as f64,
        "4096² complex f64 fields are ~2 GiB of scratch",
    ) => |s| one(f64::from(s.ocean.resolution));
    whole("ocean.bump_resolution", 2.0, super::MAX_RESOLUTION as f64, "as ocean.resolution")
        => |s| one(f64::from(s.ocean.bump_resolution));
    whole(
        "ocean.bump_patch_divisor",
        1.0,
        super::MAX_BUMP_PATCH_DIVISOR as f64,
        "the bump modes' lattice index divisor × resolution stays far inside i32",
    ) => |s| one(f64::from(s.ocean.bump_patch_divisor));
    real("ocean.choppiness", 0.0, 10.0, "Tessendorf's λ; beyond ~2 the surface folds everywhere")
        => |s| one(s.ocean.choppiness);
    real(
        "ocean.time_s",
        -f64::MAX,
        f64::MAX,
        "s; without a loop period |t| < 2^55 s, what the wave phase's tick count holds",
    ) => |s| one(s.ocean.time_s);
    real(
        "ocean.loop_period_s",
        0.0,
        crate::waves::uniforms::MAX_TIME_S,
        "s; 0 = no looping; at most 2^55 s, so the reduced time fits the wave phase",
    ) => |s| one(s.ocean.loop_period_s);
    real(
        "ocean.phillips_amplitude",
        0.0,
        1.0,
        "775 × the default α/(2π); steeper than any sea that does not break",
    ) => |s| one(s.ocean.phillips_amplitude);
    real("ocean.phillips_small_wave_m", 0.0, 1.0e5, "m; as ocean.patch_size_m")
        => |s| one(s.ocean.phillips_small_wave_m);
    real(
        "camera.position",
        -MAX_COORDINATE_M,
        MAX_COORDINATE_M,
        "m; the height y within ±1e6 m: the water mesh is built for |eye.y| ≤ 1e6 m",
    ) => |s| vector(&s.camera.position);
    real("camera.look_at", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; as camera.position")
        => |s| vector(&s.camera.look_at);
    real(
        "camera.fov_y_deg",
        1.0e-2,
        179.0,
        "degrees; the projection's 1/tan(fov/2) stays below 2e4",
    ) => |s| one(s.camera.fov_y_deg);
    whole(
        "camera.width",
        1.0,
        super::MAX_IMAGE_SIDE as f64,
        "pixels; a 16384² f32 RGBA frame is 4 GiB",
    ) => |s| one(f64::from(s.camera.width));
    whole("camera.height", 1.0, super::MAX_IMAGE_SIDE as f64, "pixels; as camera.width")
        => |s| one(f64::from(s.camera.height));
    real("camera.exposure", 1.0e-6, 1.0e6, "multiplier before the tonemap; the tonemap needs > 0")
        => |s| one(s.camera.exposure);
    real(
        "sun.direction",
        -MAX_COORDINATE_M,
        MAX_COORDINATE_M,
        "normalised on use; its length must be at least 1e-6",
    ) => |s| s.sun.as_ref().map_or_else(Vec::new, |x| vector(&x.direction));
    real("sun.color", 0.0, MAX_COLOUR, "linear RGB")
        => |s| s.sun.as_ref().map_or_else(Vec::new, |x| vector(&x.color));
    real(
        "sun.intensity",
        0.0,
        MAX_SUN_INTENSITY,
        "radiance of the disc; keeps radiance × exposure inside f32",
    ) => |s| s.sun.as_ref().map_or_else(Vec::new, |x| one(x.intensity));
    real("sun.turbidity", crate::sky::TURBIDITY_MIN, crate::sky::TURBIDITY_MAX, "Preetham's fit")
        => |s| s.sun.as_ref().map_or_else(Vec::new, |x| one(x.turbidity));
    real("sun.time_of_day_h", 0.0, 24.0, "h, local apparent solar time; sets sun.direction")
        => |s| s.sun.as_ref().and_then(|x| x.time_of_day_h).map_or_else(Vec::new, one);
    real("sun.latitude_deg", -90.0, 90.0, "degrees north, for sun.time_of_day_h")
        => |s| s.sun.as_ref().map_or_else(Vec::new, |x| one(x.latitude_deg));
    real("sun.day_of_year", 1.0, 366.0, "1 = 1 January, for sun.time_of_day_h")
        => |s| s.sun.as_ref().map_or_else(Vec::new, |x| one(x.day_of_year));
    real(
        "water.ior",
        1.0e-2,
        1.0e2,
        "η; 1 is no interface, < 1 total internal reflection from above",
    ) => |s| one(s.water.ior);
    real("water.color", 0.0, MAX_COLOUR, "linear RGB radiance at sun intensity 1")
        => |s| vector(&s.water.color);
    real("water.extinction_per_m", 0.0, 1.0e3, "1/m; 1e3 is opaque within a millimetre")
        => |s| one(s.water.extinction_per_m);
    whole(
        "quality.fresnel_table_size",
        2.0,
        crate::tables::MAX_TABLE_SIZE as f64,
        "texels per side",
    ) => |s| one(f64::from(s.quality.fresnel_table_size));
    real("quality.reflection_map_scale", 1.0e-3, 1.0, "fraction of the viewport's side")
        => |s| one(s.quality.reflection_map_scale);
    real(
        "quality.lod_split_threshold",
        1.0e-4,
        10.0,
        "radians; small values make large meshes (the memory estimate bounds them)",
    ) => |s| one(s.quality.lod_split_threshold);
    real(
        "quality.projected_grid_cell_px",
        0.5,
        64.0,
        "pixels between the projected grid's lines (surface `projected_grid`)",
    ) => |s| one(s.quality.projected_grid_cell_px);
    real("quality.clipmap_cell_m", 1.0e-2, 1.0e2, "m, level 0's quad side (surface `clipmap`)")
        => |s| one(s.quality.clipmap_cell_m);
    whole(
        "quality.clipmap_cells",
        16.0,
        256.0,
        "quads per level side, a multiple of 8 (surface `clipmap`)",
    ) => |s| one(f64::from(s.quality.clipmap_cells));
    real("terrain.depth_m", -1.0e4, 1.0e4, "m below the sea plane at terrain.center")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.depth_m));
    real("terrain.center", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; as camera.position")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| vector(&t.center));
    real("terrain.slope", 0.0, 10.0, "metres of rise per metre; 10 is 84°")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.slope));
    real("terrain.slope_direction_deg", -360.0, 360.0, "degrees from +x towards +z")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.slope_direction_deg));
    real("terrain.extent_m", 1.0, 1.0e5, "m, the side of the drawn square")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.extent_m));
    real("terrain.color", 0.0, MAX_COLOUR, "linear RGB albedo")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| vector(&t.color));
    real(
        "terrain.height_range_m",
        -1.0e4,
        1.0e4,
        "m at heightmap samples 0 and 1, added to the plane",
    ) => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| vector(&t.height_range_m));
    real("terrain.island_radius_m", 0.0, 1.0e4, "m, the island's waterline on a flat floor")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.island_radius_m));
    real("terrain.island_height_m", 0.0, 1.0e4, "m, the island's top above the sea plane")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.island_height_m));
    real("terrain.shore_slope", 1.0e-3, 10.0, "fall per metre of the island's shore")
        => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.shore_slope));
    real(
        "terrain.wave_damping",
        0.0,
        4.0,
        "waves fft/gerstner kept over h: clamp(h/(r·λ)); 0.5 Crest's",
    ) => |s| s.terrain.as_ref().map_or_else(Vec::new, |t| one(t.wave_damping));
    real("ggx.roughness", 0.01, 1.0, "perceptual; α = roughness²") => |s| one(s.ggx.roughness);
    real("ggx.detail_strength", 0.0, 1.0, "RMS slope of the detail normal map; 0 leaves it out")
        => |s| one(s.ggx.detail_strength);
    real("ggx.detail_wavelength_m", 1.0e-3, 100.0, "m, the detail map's median wavelength")
        => |s| one(s.ggx.detail_wavelength_m);
    real("ggx.detail_speed_m_s", -100.0, 100.0, "m/s, the detail map's drift with the wind")
        => |s| one(s.ggx.detail_speed_m_s);
    real("chiu.zeta_m", 0.0, 100.0, "m; eq. 6's map shift at 1 m of view depth")
        => |s| one(s.chiu.zeta_m);
    real("chiu.shininess_per_m", 1.0e-3, 1.0e3, "eq. 5's Phong exponent per metre of depth")
        => |s| one(s.chiu.shininess_per_m);
    real("chiu.kd_per_m", 0.0, 10.0, "1/m; eq. 8's k_d") => |s| one(s.chiu.kd_per_m);
    real("chiu.open_sea_depth_m", 0.0, 1.0e4, "m; eq. 8's y without a sea floor")
        => |s| one(s.chiu.open_sea_depth_m);
    real("chiu.scales", 0.01, 100.0, "eq. 1's scale factors, one to four")
        => |s| vector(&s.chiu.scales);
    real("clouds.coverage", 0.0, 1.0, "0 a clear sky, 1 overcast") => |s| one(s.clouds.coverage);
    real("clouds.altitude_m", 1.0, 1.0e5, "m above the sea") => |s| one(s.clouds.altitude_m);
    real("clouds.scale_m", 1.0, 1.0e6, "m, the noise's coarsest cell") => |s| one(s.clouds.scale_m);
    real("clouds.wind", -200.0, 200.0, "m/s, (x, z)") => |s| vector(&s.clouds.wind);
    real("clouds.albedo", 0.0, 1.0, "the clouds' reflectance") => |s| one(s.clouds.albedo);
    whole("clouds.seed", 0.0, 4_294_967_295.0, "any u32") => |s| one(f64::from(s.clouds.seed));
    whole("spray.particles", 1.0, 1_048_576.0, "slots; 2^20 particles are 32 MiB of state")
        => |s| one(f64::from(s.spray.particles));
    real("spray.emit_chance", 0.0, 1.0, "per step and free slot") => |s| one(s.spray.emit_chance);
    real("spray.speed", 0.0, 100.0, "m/s") => |s| one(s.spray.speed);
    real("spray.lifetime_s", 1.0e-3, 100.0, "s") => |s| one(s.spray.lifetime_s);
    real("spray.step_s", 1.0e-4, 1.0, "s, one step per frame") => |s| one(s.spray.step_s);
    whole("spray.warmup_steps", 0.0, 10_000.0, "steps before a state's first frame")
        => |s| one(f64::from(s.spray.warmup_steps));
    real("spray.size_m", 1.0e-3, 10.0, "m, a sprite's side") => |s| one(s.spray.size_m);
    real("spray.intensity", 0.0, MAX_COLOUR, "radiance of a sprite's centre")
        => |s| one(s.spray.intensity);
    real("spray.color", 0.0, MAX_COLOUR, "linear RGB") => |s| vector(&s.spray.color);
    real("foam.coverage", 0.0, 1.0, "the largest share of a pixel the foam covers")
        => |s| one(s.foam.coverage);
    real("foam.color", 0.0, 1.0, "linear RGB albedo") => |s| vector(&s.foam.color);
    real("foam.threshold", -10.0, 10.0, "J below which foam forms (1: flat, < 0: folded)")
        => |s| one(s.foam.threshold);
    real("foam.softness", 1.0e-3, 10.0, "width in J of the ramp to full foam")
        => |s| one(s.foam.softness);
    real("foam.crest_height_m", 1.0e-3, 100.0, "m above the mean sea plane")
        => |s| one(s.foam.crest_height_m);
    real("foam.crest_slope", 1.0e-3, 100.0, "slope of the displaced surface")
        => |s| one(s.foam.crest_slope);
    real("foam.texture_scale_m", 1.0e-2, 1.0e3, "m, one cell of the foam texture")
        => |s| one(s.foam.texture_scale_m);
    whole("foam.seed", 0.0, 4_294_967_295.0, "any u32") => |s| one(f64::from(s.foam.seed));
    real("foam.decay_s", 1.0e-3, 1.0e4, "s, e-folding time of accumulated foam")
        => |s| one(s.foam.decay_s);
    real("foam.growth_per_s", 0.0, 1.0e3, "foam per second a full ramp below the threshold")
        => |s| one(s.foam.growth_per_s);
    real("foam.step_s", 1.0e-4, 1.0, "s, one step per frame") => |s| one(s.foam.step_s);
    whole("foam.warmup_steps", 0.0, 1000.0, "steps before a state's first frame")
        => |s| one(f64::from(s.foam.warmup_steps));
    whole("foam.grid", 2.0, 4096.0, "texels per side (power of two)")
        => |s| one(f64::from(s.foam.grid));
    real("foam.cell_m", 1.0e-2, 100.0, "m between the lattice's points") => |s| one(s.foam.cell_m);
    real("post.vignette", 0.0, 1.0, "0 none; 1 black at the image's corners")
        => |s| one(s.post.vignette);
    real(
        "post.bloom_threshold",
        0.0,
        crate::tonemap::HDR_MAX as f64,
        "exposed units; what exceeds it blooms (the tonemap clamps at 65504)",
    ) => |s| one(s.post.bloom_threshold);
    real("post.bloom_strength", 0.0, 10.0, "the blurred light's share added to the frame")
        => |s| one(s.post.bloom_strength);
    whole(
        "post.bloom_levels",
        1.0,
        crate::bloom::MAX_BLOOM_LEVELS as f64,
        "levels of the blur pyramid, each twice as wide",
    ) => |s| one(f64::from(s.post.bloom_levels));
    real("objects.*.center", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; as camera.position")
        => |s| each(&s.objects, |o| Some(o.center.to_vec()));
    real("objects.*.radius", MIN_LENGTH_M, MAX_COORDINATE_M, "m")
        => |s| each(&s.objects, radius);
    real(
        "objects.*.size",
        MIN_LENGTH_M,
        MAX_COORDINATE_M,
        "m, each edge; a boat's are length, hull depth, beam",
    )
        => |s| each(&s.objects, size);
    real("objects.*.heading_deg", -360.0, 360.0, "degrees from +x towards +z; a boat's bow")
        => |s| each(&s.objects, heading);
    real(
        "objects.*.mass_kg",
        1.0e-6,
        1.0e24,
        "kg, a boat's; below its hull's ρ·L·B·H (else it sinks: refused)",
    )
        => |s| each(&s.objects, mass);
    real("objects.*.color", 0.0, MAX_COLOUR, "linear RGB albedo")
        => |s| each(&s.objects, |o| Some(o.color.to_vec()));
    whole("gerstner.count", 0.0, MAX_GERSTNER_WAVES as f64, "waves the generator keeps at a time")
        => |s| one(f64::from(s.gerstner.count));
    real("gerstner.median_wavelength_m", 0.01, 1.0e4, "m")
        => |s| one(s.gerstner.median_wavelength_m);
    real("gerstner.median_amplitude_m", 0.0, 1.0e3, "m") => |s| one(s.gerstner.median_amplitude_m);
    real("gerstner.spread_deg", 0.0, 180.0, "degrees either side of the wind; the seed's 135")
        => |s| one(s.gerstner.spread_deg);
    real("gerstner.choppiness", 0.0, 1.0, "each drawn steepness is about 0.95 times it")
        => |s| one(s.gerstner.choppiness);
    real("gerstner.min_lifetime_s", 0.01, 1.0e6, "s") => |s| one(s.gerstner.min_lifetime_s);
    real("gerstner.max_lifetime_s", 0.01, 1.0e6, "s, at least gerstner.min_lifetime_s")
        => |s| one(s.gerstner.max_lifetime_s);
    whole("gerstner.seed", 0.0, 4_294_967_295.0, "any u32; the generator's draws")
        => |s| one(f64::from(s.gerstner.seed));
    real("gerstner.waves.*.amplitude_m", 0.0, 1.0e3, "m")
        => |s| each(&s.gerstner.waves, |w| Some(vec![w.amplitude_m]));
    real("gerstner.waves.*.wavelength_m", 0.01, 1.0e4, "m")
        => |s| each(&s.gerstner.waves, |w| Some(vec![w.wavelength_m]));
    real("gerstner.waves.*.direction_deg", -360.0, 360.0, "degrees from +x towards +z")
        => |s| each(&s.gerstner.waves, |w| Some(vec![w.direction_deg]));
    real("gerstner.waves.*.steepness", 0.0, 1.0, "0 a sine wave, 1 a cusp at the crest")
        => |s| each(&s.gerstner.waves, |w| Some(vec![w.steepness]));
    real("gerstner.waves.*.phase", -1.0e3, 1.0e3, "radians")
        => |s| each(&s.gerstner.waves, |w| Some(vec![w.phase]));
    real("coastal.center", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; the point the waves run to")
        => |s| s.coastal.center.as_ref().map_or_else(Vec::new, |c| vector(c));
    real("coastal.amplitude_m", 0.0, 100.0, "m, crest above trough in deep water")
        => |s| one(s.coastal.amplitude_m);
    real("coastal.wavelength_m", 0.1, 1.0e4, "m, the radial waves' deep-water wavelength")
        => |s| one(s.coastal.wavelength_m);
    whole("coastal.power", 1.0, 15.0, "odd powers keep the seed's shape; the seed's 7")
        => |s| one(f64::from(s.coastal.power));
    real("coastal.back_factor", 1.0, 8.0, "the seed's temp2 (2): the front's steepening")
        => |s| one(s.coastal.back_factor);
    real("coastal.corrections.*.direction_deg", -360.0, 360.0, "degrees from +x towards +z")
        => |s| each(&s.coastal.corrections, |w| Some(vec![w.direction_deg]));
    real("coastal.corrections.*.wavelength_m", 0.1, 1.0e4, "m")
        => |s| each(&s.coastal.corrections, |w| Some(vec![w.wavelength_m]));
    real("coastal.corrections.*.amplitude_m", 0.0, 100.0, "m, the seed's Amplitudes/2")
        => |s| each(&s.coastal.corrections, |w| Some(vec![w.amplitude_m]));
    whole(
        "coastal.shininess",
        1.0,
        10000.0,
        "the highlight's Blinn–Phong exponent; the seed's 30",
    ) => |s| one(f64::from(s.coastal.shininess));
    real("coastal.dull_factor", 0.0, 1.0, "the dull colour's share at the crests")
        => |s| one(s.coastal.dull_factor);
    real("coastal.dull_color", 0.0, MAX_COLOUR, "linear RGB albedo")
        => |s| vector(&s.coastal.dull_color);
    real("coastal.distortion", 0.0, 1.0, "screen units per unit of normal tilt")
        => |s| one(s.coastal.distortion);
}

/// The limit of a key (`objects.3.radius` finds `objects.*.radius`: an index stands for every
/// element of its array).
pub fn limit(key: &str) -> Option<&'static Limit> {
    let pattern: Vec<&str> =
        key.split('.').map(|p| if p.parse::<usize>().is_ok() { "*" } else { p }).collect();
    let pattern = pattern.join(".");
    LIMITS.iter().find(|l| l.key == pattern)
}

type Refusal = (String, String);

/// Checks `values` (one or the components of a vector) against the limit of `key`.
fn check(key: &str, values: &[f64]) -> Result<(), Refusal> {
    let Some(l) = limit(key) else {
        return Err((key.to_owned(), "internal: no limit for this key".to_owned()));
    };
    if values.iter().all(|v| (l.min..=l.max).contains(v)) {
        return Ok(());
    }
    let got = if values.len() == 1 {
        number(values[0])
    } else {
        format!("[{}]", values.iter().map(|v| number(*v)).collect::<Vec<_>>().join(", "))
    };
    let each = if values.len() > 1 { "every component " } else { "" };
    Err((
        key.to_owned(),
        format!(
            "{each}must be between {} and {} ({}), got {got}",
            number(l.min),
            number(l.max),
            l.why
        ),
    ))
}

impl Scene {
    /// Checks every value against [`LIMITS`] and every derived quantity the frame needs.
    /// Returns the dotted key path of the first bad value and what is allowed.
    pub fn validate(&self) -> Result<(), Refusal> {
        self.check_techniques()?;
        self.check_ranges()?;
        self.check_quality()?;
        self.check_terrain()?;
        self.check_gerstner()?;
        self.check_coastal()?;
        self.check_shading_sections()?;
        self.check_foam()?;
        self.check_objects()?;
        self.check_derived()
    }

    /// Every key of [`LIMITS`] the scene holds, in the table's order, against its range.
    fn check_ranges(&self) -> Result<(), Refusal> {
        for (limit, values) in LIMITS.iter().zip(VALUES) {
            for (i, v) in values(self) {
                check(&limit.key.replace('*', &i.to_string()), &v)?;
            }
        }
        Ok(())
    }

    /// `[quality]`'s clipmap cells, a multiple of 8.
    fn check_quality(&self) -> Result<(), Refusal> {
        let q = &self.quality;
        if !q.clipmap_cells.is_multiple_of(8) {
            return Err((
                "quality.clipmap_cells".into(),
                format!("{} is not a multiple of 8 (16, 24, …, 256)", q.clipmap_cells),
            ));
        }
        Ok(())
    }

    /// The `[terrain]` keys, and what an island or a heightmap needs.
    fn check_terrain(&self) -> Result<(), Refusal> {
        if let Some(t) = &self.terrain {
            if t.kind == crate::scene::TerrainKind::Island {
                let reach = crate::terrain::island_reach(t);
                if t.extent_m < 2.0 * reach {
                    return Err((
                        "terrain.extent_m".into(),
                        format!(
                            "the island's shore meets the floor {reach:.1} m from its centre \
                             (island_radius_m + depth_m / shore_slope); extent_m = {} cuts it \
                             off: it must be at least {:.1}",
                            t.extent_m,
                            2.0 * reach
                        ),
                    ));
                }
                if t.depth_m <= 0.0 {
                    return Err((
                        "terrain.depth_m".into(),
                        format!(
                            "an island rises from a floor below the sea: depth_m must be \
                             positive, got {}",
                            t.depth_m
                        ),
                    ));
                }
            }
            match (t.kind, &t.heightmap) {
                (crate::scene::TerrainKind::Heightmap, None) => {
                    return Err((
                        "terrain.kind".into(),
                        "a `heightmap` floor needs `heightmap = \"FILE\"` (a 16-bit grayscale \
                         PNG or an EXR)"
                            .into(),
                    ));
                }
                (
                    kind @ (crate::scene::TerrainKind::Plane | crate::scene::TerrainKind::Island),
                    Some(_),
                ) => {
                    let name =
                        if kind == crate::scene::TerrainKind::Plane { "plane" } else { "island" };
                    return Err((
                        "terrain.heightmap".into(),
                        format!("a `{name}` floor has no heightmap (set `kind = \"heightmap\"`)"),
                    ));
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// `[chiu]`'s scales: one to [`super::MAX_SCALES`].
    fn check_shading_sections(&self) -> Result<(), Refusal> {
        let ch = &self.chiu;
        if !(1..=super::MAX_SCALES).contains(&ch.scales.len()) {
            return Err((
                "chiu.scales".into(),
                format!("eq. 1 takes one to {} scales, got {}", super::MAX_SCALES, ch.scales.len()),
            ));
        }
        Ok(())
    }

    /// `[foam]`'s lattice side, a power of two.
    fn check_foam(&self) -> Result<(), Refusal> {
        let fo = &self.foam;
        if !fo.grid.is_power_of_two() {
            return Err((
                "foam.grid".into(),
                format!("the foam lattice's side must be a power of two, got {}", fo.grid),
            ));
        }
        Ok(())
    }

    fn check_techniques(&self) -> Result<(), Refusal> {
        use crate::technique::TechniqueError;
        let techniques = self.techniques();
        techniques.check().map_err(|e| {
            let key = match &e {
                TechniqueError::Incompatible { stage_a, stage_b, .. } => {
                    let key = if techniques.is_overridden(*stage_b) { stage_b } else { stage_a };
                    format!("techniques.{key}")
                }
                _ => "system".to_owned(),
            };
            (key, e.to_string())
        })
    }

    fn check_gerstner(&self) -> Result<(), Refusal> {
        let g = &self.gerstner;
        if g.max_lifetime_s < g.min_lifetime_s {
            return Err((
                "gerstner.max_lifetime_s".into(),
                format!(
                    "must be at least gerstner.min_lifetime_s ({}), got {}",
                    number(g.min_lifetime_s),
                    number(g.max_lifetime_s)
                ),
            ));
        }
        if g.waves.len() > MAX_GERSTNER_WAVES {
            return Err((
                "gerstner.waves".into(),
                format!("at most {MAX_GERSTNER_WAVES} waves, got {}", g.waves.len()),
            ));
        }
        Ok(())
    }

    fn check_coastal(&self) -> Result<(), Refusal> {
        let c = &self.coastal;
        if c.corrections.len() > MAX_CORRECTION_WAVES {
            return Err((
                "coastal.corrections".into(),
                format!(
                    "at most {MAX_CORRECTION_WAVES} correction waves (the seed's float4), got {}",
                    c.corrections.len()
                ),
            ));
        }
        Ok(())
    }

    fn check_objects(&self) -> Result<(), Refusal> {
        for (i, obj) in self.objects.iter().enumerate() {
            let key = |f: &str| format!("objects.{i}.{f}");
            let boat = obj.kind == ObjectKind::Boat;
            let needs = if obj.kind == ObjectKind::Sphere { "radius" } else { "size" };
            let given = [
                ("radius", obj.radius.is_some()),
                ("size", obj.size.is_some()),
                ("heading_deg", obj.heading_deg.is_some()),
                ("mass_kg", obj.mass_kg.is_some()),
            ];
            // A key only a boat takes, or the other shape's key.
            let forbidden = |f: &str| f != needs && (f == "radius" || !boat);
            if let Some((f, _)) = given.iter().find(|&&(f, set)| set && forbidden(f)) {
                return Err((
                    key(f),
                    format!("a {:?} has no `{f}` (it takes `{needs}`)", obj.kind),
                ));
            }
            match obj.shape() {
                Some(Shape::Sphere { .. } | Shape::Box { .. }) => {}
                Some(Shape::Boat { .. }) => self.check_boat(i, obj)?,
                None => return Err((key(needs), format!("a {:?} needs `{needs}`", obj.kind))),
            }
        }
        Ok(())
    }

    /// A boat's build, made as the frame makes it: it must float (its mass below its hull's
    /// full displacement), or there is no pose to draw.
    fn check_boat(&self, i: usize, obj: &super::Object) -> Result<(), Refusal> {
        let Some(p) = obj.boat_params() else { return Ok(()) };
        let key = |f: &str| format!("objects.{i}.{f}");
        p.validate().map_err(|e| (key("size"), format!("boat #{i}: {e}")))?;
        if !p.floats() {
            let displacement = p.water_density_kg_m3 * p.length_m * p.beam_m * p.hull_depth_m;
            return Err((
                key("mass_kg"),
                format!(
                    "boat #{i} cannot float: its mass, {} kg, is not below what its whole hull \
                     displaces, ρ·L·B·H = {} kg (size = [length, hull depth, beam]); make it \
                     lighter or its hull bigger",
                    number(p.mass_kg),
                    number(displacement)
                ),
            ));
        }
        Ok(())
    }

    /// The quantities the frame derives from several keys, built as the frame builds them.
    fn check_derived(&self) -> Result<(), Refusal> {
        let o = &self.ocean;
        // The bump map holds the waves the displacement map cannot: those from index
        // ⌈N_d / 2r⌉ of its own lattice up to its Nyquist N_b / 2 (waves::surface).
        let first_bump_index = o.resolution.div_ceil(2 * o.bump_patch_divisor);
        if o.bump_resolution <= 2 * first_bump_index {
            return Err((
                "ocean.bump_resolution".into(),
                format!(
                    "must exceed {} (2·⌈resolution / (2·bump_patch_divisor)⌉), else the bump \
                     map holds no wave finer than the displacement map's; got {}",
                    2 * first_bump_index,
                    o.bump_resolution
                ),
            ));
        }
        let dispersion = o.dispersion().map_err(|e| ("ocean.depth_m".to_owned(), e.to_string()))?;
        let tau = dispersion.reduced_time(o.time_s);
        if tau.abs() >= crate::waves::uniforms::MAX_TIME_S {
            return Err((
                "ocean.time_s".into(),
                format!(
                    "must be within ±2^55 s ({}) without a loop period (the wave phase counts \
                     2⁻⁸ s ticks in 64 bits); got {}; set ocean.loop_period_s to render later \
                     times",
                    number(crate::waves::uniforms::MAX_TIME_S),
                    number(o.time_s)
                ),
            ));
        }
        o.wave_spectrum().map_err(|e| (spectrum_key(&e).to_owned(), e.to_string()))?;

        let c = &self.camera;
        let d = [0, 1, 2].map(|i| c.look_at[i] - c.position[i]);
        let distance = d[0].hypot(d[1]).hypot(d[2]);
        if distance < MIN_LENGTH_M {
            return Err((
                "camera.look_at".into(),
                format!(
                    "must be at least {} m from camera.position, got {}",
                    number(MIN_LENGTH_M),
                    number(distance)
                ),
            ));
        }
        let camera = crate::camera::Camera::from_scene(c)
            .map_err(|e| ("camera.look_at".to_owned(), e.to_string()))?;
        let view_proj = camera.view_proj();
        if !view_proj.is_finite()
            || crate::camera_uniforms::invert(&view_proj.to_cols_array_2d()).is_none()
        {
            return Err((
                "camera.fov_y_deg".into(),
                "the view-projection matrix of this camera is singular".into(),
            ));
        }
        if let Some(s) = &self.sun {
            let length = s.direction[0].hypot(s.direction[1]).hypot(s.direction[2]);
            if length < 1.0e-6 {
                return Err((
                    "sun.direction".into(),
                    format!("must have a length of at least 1e-6, got {}", number(length)),
                ));
            }
        }
        let grid = self.patch_params();
        if grid.grid_spacing_m > MAX_GRID_SPACING_M {
            return Err((
                "ocean.resolution".into(),
                format!(
                    "must be at least patch_size_m / {} = {} (a grid spacing of at most {} m), \
                     got {} (a spacing of {} m): on coarser grids the water mesh's far patch can \
                     leave non-finite pixels at the horizon",
                    number(MAX_GRID_SPACING_M),
                    (o.patch_size_m / MAX_GRID_SPACING_M).ceil(),
                    number(MAX_GRID_SPACING_M),
                    o.resolution,
                    number(grid.grid_spacing_m)
                ),
            ));
        }
        let refuse_grid = |e: crate::Error| {
            (
                "ocean.patch_size_m".to_owned(),
                format!(
                    "with ocean.resolution = {} (a grid spacing of {} m) the water mesh cannot \
                     be built: {e}",
                    o.resolution,
                    number(grid.grid_spacing_m)
                ),
            )
        };
        crate::geometry::near_patch_square(&grid, [c.position[0], c.position[2]])
            .map_err(refuse_grid)?;
        if c.position[1].abs() > crate::geometry::MAX_HEIGHT_M {
            return Err((
                "camera.position".into(),
                format!(
                    "the height (y) must be within ±{} m of the sea plane (the water mesh's \
                     range), got {}",
                    number(crate::geometry::MAX_HEIGHT_M),
                    number(c.position[1])
                ),
            ));
        }
        Ok(())
    }
}

/// The scene key of a spectrum parameter the spectrum refused.
fn spectrum_key(e: &crate::Error) -> &'static str {
    let crate::Error::InvalidParameter { name, .. } = e else { return "ocean.spectrum" };
    match *name {
        "wind_speed" => "ocean.wind_speed",
        "wind_direction" => "ocean.wind_direction_deg",
        "depth_m" => "ocean.depth_m",
        "fetch_m" => "ocean.fetch_km",
        "peak_enhancement" => "ocean.peak_enhancement",
        "phillips_amplitude" => "ocean.phillips_amplitude",
        "phillips_small_wave_m" => "ocean.phillips_small_wave_m",
        _ => "ocean.spectrum",
    }
}
