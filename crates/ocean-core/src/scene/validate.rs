//! [`Scene::validate`]: every value checked against what the f32 pipeline, the geometry and
//! the GPU can represent, so that **validation accepts ⇒ both back ends render only finite
//! pixels** (`tests/scene_properties.rs` holds the scenes at these limits to that).
//!
//! Two layers:
//! - [`LIMITS`], one range per numeric key (vectors and colours per component), each with the
//!   reason for its bounds. docs/scenes.md's table, the property test's extreme scenes and the
//!   fuzzer read the same table.
//! - Cross-key checks: the quantities the frame derives from several keys (the bump map's
//!   band, the time the wave phase holds, the view, the spectrum, the water mesh) are built
//!   here with the constructors the frame uses, and a failure is reported as the scene key it
//!   comes from, never as the internal quantity.

use super::{ObjectKind, Scene, Shape};
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

/// Every numeric key's range, in scene-file order.
pub const LIMITS: &[Limit] = &[
    real(
        "ocean.wind_speed",
        0.0,
        200.0,
        "m/s at 10 m; 0 is a flat sea, 200 is above any measured surface wind",
    ),
    real("ocean.wind_direction_deg", -1.0e6, 1.0e6, "degrees; any angle, within f32 range"),
    real(
        "ocean.fetch_km",
        1.0e-3,
        2.0e4,
        "JONSWAP/TMA fetch from 1 m to half the Earth's circumference",
    ),
    real("ocean.depth_m", 1.0e-2, f64::INFINITY, "m; inf is deep water"),
    real(
        "ocean.peak_enhancement",
        1.0,
        20.0,
        "JONSWAP γ: 1 is Pierson–Moskowitz, 3.3 the JONSWAP mean",
    ),
    real(
        "ocean.patch_size_m",
        1.0e-2,
        65536.0,
        "m; at most 16 m per sample of the largest grid (MAX_GRID_SPACING_M × 4096)",
    ),
    whole(
        "ocean.resolution",
        2.0,
        super::MAX_RESOLUTION as f64,
        "4096² complex f64 fields are ~2 GiB of scratch",
    ),
    whole("ocean.bump_resolution", 2.0, super::MAX_RESOLUTION as f64, "as ocean.resolution"),
    whole(
        "ocean.bump_patch_divisor",
        1.0,
        super::MAX_BUMP_PATCH_DIVISOR as f64,
        "the bump modes' lattice index divisor × resolution stays far inside i32",
    ),
    real("ocean.choppiness", 0.0, 10.0, "Tessendorf's λ; beyond ~2 the surface folds everywhere"),
    real(
        "ocean.time_s",
        -f64::MAX,
        f64::MAX,
        "s; without a loop period |t| < 2^55 s, what the wave phase's tick count holds",
    ),
    real(
        "ocean.loop_period_s",
        0.0,
        crate::waves::uniforms::MAX_TIME_S,
        "s; 0 = no looping; at most 2^55 s, so the reduced time fits the wave phase",
    ),
    real(
        "ocean.phillips_amplitude",
        0.0,
        1.0,
        "775 × the default α/(2π); steeper than any sea that does not break",
    ),
    real("ocean.phillips_small_wave_m", 0.0, 1.0e5, "m; as ocean.patch_size_m"),
    real(
        "camera.position",
        -MAX_COORDINATE_M,
        MAX_COORDINATE_M,
        "m; the height y within ±1e6 m: the water mesh is built for |eye.y| ≤ 1e6 m",
    ),
    real("camera.look_at", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; as camera.position"),
    real(
        "camera.fov_y_deg",
        1.0e-2,
        179.0,
        "degrees; the projection's 1/tan(fov/2) stays below 2e4",
    ),
    whole(
        "camera.width",
        1.0,
        super::MAX_IMAGE_SIDE as f64,
        "pixels; a 16384² f32 RGBA frame is 4 GiB",
    ),
    whole("camera.height", 1.0, super::MAX_IMAGE_SIDE as f64, "pixels; as camera.width"),
    real("camera.exposure", 1.0e-6, 1.0e6, "multiplier before the tonemap; the tonemap needs > 0"),
    real(
        "sun.direction",
        -MAX_COORDINATE_M,
        MAX_COORDINATE_M,
        "normalised on use; its length must be at least 1e-6",
    ),
    real("sun.color", 0.0, MAX_COLOUR, "linear RGB"),
    real(
        "sun.intensity",
        0.0,
        MAX_SUN_INTENSITY,
        "radiance of the disc; keeps radiance × exposure inside f32",
    ),
    real("sun.turbidity", crate::sky::TURBIDITY_MIN, crate::sky::TURBIDITY_MAX, "Preetham's fit"),
    real("sun.time_of_day_h", 0.0, 24.0, "h, local apparent solar time; sets sun.direction"),
    real("sun.latitude_deg", -90.0, 90.0, "degrees north, for sun.time_of_day_h"),
    real("sun.day_of_year", 1.0, 366.0, "1 = 1 January, for sun.time_of_day_h"),
    real(
        "water.ior",
        1.0e-2,
        1.0e2,
        "η; 1 is no interface, < 1 total internal reflection from above",
    ),
    real("water.color", 0.0, MAX_COLOUR, "linear RGB radiance at sun intensity 1"),
    real("water.extinction_per_m", 0.0, 1.0e3, "1/m; 1e3 is opaque within a millimetre"),
    whole(
        "quality.fresnel_table_size",
        2.0,
        crate::tables::MAX_TABLE_SIZE as f64,
        "texels per side",
    ),
    real("quality.reflection_map_scale", 1.0e-3, 1.0, "fraction of the viewport's side"),
    real(
        "quality.lod_split_threshold",
        1.0e-4,
        10.0,
        "radians; small values make large meshes (the memory estimate bounds them)",
    ),
    real(
        "quality.projected_grid_cell_px",
        0.5,
        64.0,
        "pixels between the projected grid's lines (surface `projected_grid`)",
    ),
    real("quality.clipmap_cell_m", 1.0e-2, 1.0e2, "m, level 0's quad side (surface `clipmap`)"),
    whole(
        "quality.clipmap_cells",
        16.0,
        256.0,
        "quads per level side, a multiple of 8 (surface `clipmap`)",
    ),
    real("terrain.depth_m", -1.0e4, 1.0e4, "m below the sea plane at terrain.center"),
    real("terrain.center", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; as camera.position"),
    real("terrain.slope", 0.0, 10.0, "metres of rise per metre; 10 is 84°"),
    real("terrain.slope_direction_deg", -360.0, 360.0, "degrees from +x towards +z"),
    real("terrain.extent_m", 1.0, 1.0e5, "m, the side of the drawn square"),
    real("terrain.color", 0.0, MAX_COLOUR, "linear RGB albedo"),
    real(
        "terrain.height_range_m",
        -1.0e4,
        1.0e4,
        "m at heightmap samples 0 and 1, added to the plane",
    ),
    real("terrain.island_radius_m", 0.0, 1.0e4, "m, the island's waterline on a flat floor"),
    real("terrain.island_height_m", 0.0, 1.0e4, "m, the island's top above the sea plane"),
    real("terrain.shore_slope", 1.0e-3, 10.0, "fall per metre of the island's shore"),
    real(
        "terrain.wave_damping",
        0.0,
        4.0,
        "waves fft/gerstner kept over h: clamp(h/(r·λ)); 0.5 Crest's",
    ),
    real("ggx.roughness", 0.01, 1.0, "perceptual; α = roughness²"),
    real("ggx.detail_strength", 0.0, 1.0, "RMS slope of the detail normal map; 0 leaves it out"),
    real("ggx.detail_wavelength_m", 1.0e-3, 100.0, "m, the detail map's median wavelength"),
    real("ggx.detail_speed_m_s", -100.0, 100.0, "m/s, the detail map's drift with the wind"),
    real("chiu.zeta_m", 0.0, 100.0, "m; eq. 6's map shift at 1 m of view depth"),
    real("chiu.shininess_per_m", 1.0e-3, 1.0e3, "eq. 5's Phong exponent per metre of depth"),
    real("chiu.kd_per_m", 0.0, 10.0, "1/m; eq. 8's k_d"),
    real("chiu.open_sea_depth_m", 0.0, 1.0e4, "m; eq. 8's y without a sea floor"),
    real("chiu.scales", 0.01, 100.0, "eq. 1's scale factors, one to four"),
    real("clouds.coverage", 0.0, 1.0, "0 a clear sky, 1 overcast"),
    real("clouds.altitude_m", 1.0, 1.0e5, "m above the sea"),
    real("clouds.scale_m", 1.0, 1.0e6, "m, the noise's coarsest cell"),
    real("clouds.wind", -200.0, 200.0, "m/s, (x, z)"),
    real("clouds.albedo", 0.0, 1.0, "the clouds' reflectance"),
    whole("clouds.seed", 0.0, 4_294_967_295.0, "any u32"),
    whole("spray.particles", 1.0, 1_048_576.0, "slots; 2^20 particles are 32 MiB of state"),
    real("spray.emit_chance", 0.0, 1.0, "per step and free slot"),
    real("spray.speed", 0.0, 100.0, "m/s"),
    real("spray.lifetime_s", 1.0e-3, 100.0, "s"),
    real("spray.step_s", 1.0e-4, 1.0, "s, one step per frame"),
    whole("spray.warmup_steps", 0.0, 10_000.0, "steps before a state's first frame"),
    real("spray.size_m", 1.0e-3, 10.0, "m, a sprite's side"),
    real("spray.intensity", 0.0, MAX_COLOUR, "radiance of a sprite's centre"),
    real("spray.color", 0.0, MAX_COLOUR, "linear RGB"),
    real("foam.coverage", 0.0, 1.0, "the largest share of a pixel the foam covers"),
    real("foam.color", 0.0, 1.0, "linear RGB albedo"),
    real("foam.threshold", -10.0, 10.0, "J below which foam forms (1: flat, < 0: folded)"),
    real("foam.softness", 1.0e-3, 10.0, "width in J of the ramp to full foam"),
    real("foam.crest_height_m", 1.0e-3, 100.0, "m above the mean sea plane"),
    real("foam.crest_slope", 1.0e-3, 100.0, "slope of the displaced surface"),
    real("foam.texture_scale_m", 1.0e-2, 1.0e3, "m, one cell of the foam texture"),
    whole("foam.seed", 0.0, 4_294_967_295.0, "any u32"),
    real("foam.decay_s", 1.0e-3, 1.0e4, "s, e-folding time of accumulated foam"),
    real("foam.growth_per_s", 0.0, 1.0e3, "foam per second a full ramp below the threshold"),
    real("foam.step_s", 1.0e-4, 1.0, "s, one step per frame"),
    whole("foam.warmup_steps", 0.0, 1000.0, "steps before a state's first frame"),
    whole("foam.grid", 2.0, 4096.0, "texels per side (power of two)"),
    real("foam.cell_m", 1.0e-2, 100.0, "m between the lattice's points"),
    real("post.vignette", 0.0, 1.0, "0 none; 1 black at the image's corners"),
    real(
        "post.bloom_threshold",
        0.0,
        crate::tonemap::HDR_MAX as f64,
        "exposed units; what exceeds it blooms (the tonemap clamps at 65504)",
    ),
    real("post.bloom_strength", 0.0, 10.0, "the blurred light's share added to the frame"),
    whole(
        "post.bloom_levels",
        1.0,
        crate::bloom::MAX_BLOOM_LEVELS as f64,
        "levels of the blur pyramid, each twice as wide",
    ),
    real("objects.*.center", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; as camera.position"),
    real("objects.*.radius", MIN_LENGTH_M, MAX_COORDINATE_M, "m"),
    real(
        "objects.*.size",
        MIN_LENGTH_M,
        MAX_COORDINATE_M,
        "m, each edge; a boat's are length, hull depth, beam",
    ),
    real("objects.*.heading_deg", -360.0, 360.0, "degrees from +x towards +z; a boat's bow"),
    real(
        "objects.*.mass_kg",
        1.0e-6,
        1.0e24,
        "kg, a boat's; below its hull's ρ·L·B·H (else it sinks: refused)",
    ),
    real("objects.*.color", 0.0, MAX_COLOUR, "linear RGB albedo"),
    whole("gerstner.count", 0.0, MAX_GERSTNER_WAVES as f64, "waves the generator keeps at a time"),
    real("gerstner.median_wavelength_m", 0.01, 1.0e4, "m"),
    real("gerstner.median_amplitude_m", 0.0, 1.0e3, "m"),
    real("gerstner.spread_deg", 0.0, 180.0, "degrees either side of the wind; the seed's 135"),
    real("gerstner.choppiness", 0.0, 1.0, "each drawn steepness is about 0.95 times it"),
    real("gerstner.min_lifetime_s", 0.01, 1.0e6, "s"),
    real("gerstner.max_lifetime_s", 0.01, 1.0e6, "s, at least gerstner.min_lifetime_s"),
    whole("gerstner.seed", 0.0, 4_294_967_295.0, "any u32; the generator's draws"),
    real("gerstner.waves.*.amplitude_m", 0.0, 1.0e3, "m"),
    real("gerstner.waves.*.wavelength_m", 0.01, 1.0e4, "m"),
    real("gerstner.waves.*.direction_deg", -360.0, 360.0, "degrees from +x towards +z"),
    real("gerstner.waves.*.steepness", 0.0, 1.0, "0 a sine wave, 1 a cusp at the crest"),
    real("gerstner.waves.*.phase", -1.0e3, 1.0e3, "radians"),
    real("coastal.center", -MAX_COORDINATE_M, MAX_COORDINATE_M, "m; the point the waves run to"),
    real("coastal.amplitude_m", 0.0, 100.0, "m, crest above trough in deep water"),
    real("coastal.wavelength_m", 0.1, 1.0e4, "m, the radial waves' deep-water wavelength"),
    whole("coastal.power", 1.0, 15.0, "odd powers keep the seed's shape; the seed's 7"),
    real("coastal.back_factor", 1.0, 8.0, "the seed's temp2 (2): the front's steepening"),
    real("coastal.corrections.*.direction_deg", -360.0, 360.0, "degrees from +x towards +z"),
    real("coastal.corrections.*.wavelength_m", 0.1, 1.0e4, "m"),
    real("coastal.corrections.*.amplitude_m", 0.0, 100.0, "m, the seed's Amplitudes/2"),
    whole("coastal.shininess", 1.0, 10000.0, "the highlight's Blinn–Phong exponent; the seed's 30"),
    real("coastal.dull_factor", 0.0, 1.0, "the dull colour's share at the crests"),
    real("coastal.dull_color", 0.0, MAX_COLOUR, "linear RGB albedo"),
    real("coastal.distortion", 0.0, 1.0, "screen units per unit of normal tilt"),
];

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

fn check_u32(key: &str, v: u32) -> Result<(), Refusal> {
    check(key, &[f64::from(v)])
}

impl Scene {
    /// Checks every value against [`LIMITS`] and every derived quantity the frame needs.
    /// Returns the dotted key path of the first bad value and what is allowed.
    pub fn validate(&self) -> Result<(), Refusal> {
        self.check_techniques()?;
        self.check_ocean_and_camera()?;
        self.check_sun_water_quality()?;
        self.check_terrain()?;
        self.check_gerstner()?;
        self.check_coastal()?;
        self.check_shading_sections()?;
        self.check_spray_foam_post()?;
        self.check_objects()?;
        self.check_derived()
    }

    /// The `[ocean]` and `[camera]` keys.
    fn check_ocean_and_camera(&self) -> Result<(), Refusal> {
        let o = &self.ocean;
        check("ocean.wind_speed", &[o.wind_speed])?;
        check("ocean.wind_direction_deg", &[o.wind_direction_deg])?;
        check("ocean.fetch_km", &[o.fetch_km])?;
        check("ocean.depth_m", &[o.depth_m])?;
        check("ocean.peak_enhancement", &[o.peak_enhancement])?;
        check("ocean.patch_size_m", &[o.patch_size_m])?;
        check_u32("ocean.resolution", o.resolution)?;
        check_u32("ocean.bump_resolution", o.bump_resolution)?;
        check_u32("ocean.bump_patch_divisor", o.bump_patch_divisor)?;
        check("ocean.choppiness", &[o.choppiness])?;
        check("ocean.time_s", &[o.time_s])?;
        check("ocean.loop_period_s", &[o.loop_period_s])?;
        check("ocean.phillips_amplitude", &[o.phillips_amplitude])?;
        check("ocean.phillips_small_wave_m", &[o.phillips_small_wave_m])?;
        let c = &self.camera;
        check("camera.position", &c.position)?;
        check("camera.look_at", &c.look_at)?;
        check("camera.fov_y_deg", &[c.fov_y_deg])?;
        check_u32("camera.width", c.width)?;
        check_u32("camera.height", c.height)?;
        check("camera.exposure", &[c.exposure])?;
        Ok(())
    }

    /// The `[sun]`, `[water]` and `[quality]` keys.
    fn check_sun_water_quality(&self) -> Result<(), Refusal> {
        if let Some(s) = &self.sun {
            check("sun.direction", &s.direction)?;
            check("sun.color", &s.color)?;
            check("sun.intensity", &[s.intensity])?;
            check("sun.turbidity", &[s.turbidity])?;
            check("sun.latitude_deg", &[s.latitude_deg])?;
            check("sun.day_of_year", &[s.day_of_year])?;
            if let Some(t) = s.time_of_day_h {
                check("sun.time_of_day_h", &[t])?;
            }
        }
        let w = &self.water;
        check("water.ior", &[w.ior])?;
        check("water.color", &w.color)?;
        check("water.extinction_per_m", &[w.extinction_per_m])?;
        let q = &self.quality;
        check_u32("quality.fresnel_table_size", q.fresnel_table_size)?;
        check("quality.reflection_map_scale", &[q.reflection_map_scale])?;
        check("quality.lod_split_threshold", &[q.lod_split_threshold])?;
        check("quality.projected_grid_cell_px", &[q.projected_grid_cell_px])?;
        check("quality.clipmap_cell_m", &[q.clipmap_cell_m])?;
        check_u32("quality.clipmap_cells", q.clipmap_cells)?;
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
            check("terrain.depth_m", &[t.depth_m])?;
            check("terrain.center", &t.center)?;
            check("terrain.slope", &[t.slope])?;
            check("terrain.slope_direction_deg", &[t.slope_direction_deg])?;
            check("terrain.extent_m", &[t.extent_m])?;
            check("terrain.color", &t.color)?;
            check("terrain.height_range_m", &t.height_range_m)?;
            check("terrain.island_radius_m", &[t.island_radius_m])?;
            check("terrain.island_height_m", &[t.island_height_m])?;
            check("terrain.shore_slope", &[t.shore_slope])?;
            check("terrain.wave_damping", &[t.wave_damping])?;
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

    /// The `[ggx]`, `[chiu]` and `[clouds]` keys.
    fn check_shading_sections(&self) -> Result<(), Refusal> {
        check("ggx.roughness", &[self.ggx.roughness])?;
        check("ggx.detail_strength", &[self.ggx.detail_strength])?;
        check("ggx.detail_wavelength_m", &[self.ggx.detail_wavelength_m])?;
        check("ggx.detail_speed_m_s", &[self.ggx.detail_speed_m_s])?;
        let ch = &self.chiu;
        check("chiu.zeta_m", &[ch.zeta_m])?;
        check("chiu.shininess_per_m", &[ch.shininess_per_m])?;
        check("chiu.kd_per_m", &[ch.kd_per_m])?;
        check("chiu.open_sea_depth_m", &[ch.open_sea_depth_m])?;
        check("chiu.scales", &ch.scales)?;
        if !(1..=super::MAX_SCALES).contains(&ch.scales.len()) {
            return Err((
                "chiu.scales".into(),
                format!("eq. 1 takes one to {} scales, got {}", super::MAX_SCALES, ch.scales.len()),
            ));
        }
        let cl = &self.clouds;
        check("clouds.coverage", &[cl.coverage])?;
        check("clouds.altitude_m", &[cl.altitude_m])?;
        check("clouds.scale_m", &[cl.scale_m])?;
        check("clouds.wind", &cl.wind)?;
        check("clouds.albedo", &[cl.albedo])?;
        check_u32("clouds.seed", cl.seed)?;
        Ok(())
    }

    /// The `[spray]`, `[foam]` and `[post]` keys.
    fn check_spray_foam_post(&self) -> Result<(), Refusal> {
        let sp = &self.spray;
        check_u32("spray.particles", sp.particles)?;
        check("spray.emit_chance", &[sp.emit_chance])?;
        check("spray.speed", &[sp.speed])?;
        check("spray.lifetime_s", &[sp.lifetime_s])?;
        check("spray.step_s", &[sp.step_s])?;
        check_u32("spray.warmup_steps", sp.warmup_steps)?;
        check("spray.size_m", &[sp.size_m])?;
        check("spray.intensity", &[sp.intensity])?;
        check("spray.color", &sp.color)?;
        let fo = &self.foam;
        check("foam.coverage", &[fo.coverage])?;
        check("foam.color", &fo.color)?;
        check("foam.threshold", &[fo.threshold])?;
        check("foam.softness", &[fo.softness])?;
        check("foam.crest_height_m", &[fo.crest_height_m])?;
        check("foam.crest_slope", &[fo.crest_slope])?;
        check("foam.texture_scale_m", &[fo.texture_scale_m])?;
        check_u32("foam.seed", fo.seed)?;
        check("foam.decay_s", &[fo.decay_s])?;
        check("foam.growth_per_s", &[fo.growth_per_s])?;
        check("foam.step_s", &[fo.step_s])?;
        check_u32("foam.warmup_steps", fo.warmup_steps)?;
        check_u32("foam.grid", fo.grid)?;
        if !fo.grid.is_power_of_two() {
            return Err((
                "foam.grid".into(),
                format!("the foam lattice's side must be a power of two, got {}", fo.grid),
            ));
        }
        check("foam.cell_m", &[fo.cell_m])?;
        check("post.vignette", &[self.post.vignette])?;
        check("post.bloom_threshold", &[self.post.bloom_threshold])?;
        check("post.bloom_strength", &[self.post.bloom_strength])?;
        check_u32("post.bloom_levels", self.post.bloom_levels)?;
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
        check_u32("gerstner.count", g.count)?;
        check("gerstner.median_wavelength_m", &[g.median_wavelength_m])?;
        check("gerstner.median_amplitude_m", &[g.median_amplitude_m])?;
        check("gerstner.spread_deg", &[g.spread_deg])?;
        check("gerstner.choppiness", &[g.choppiness])?;
        check("gerstner.min_lifetime_s", &[g.min_lifetime_s])?;
        check("gerstner.max_lifetime_s", &[g.max_lifetime_s])?;
        check_u32("gerstner.seed", g.seed)?;
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
        for (i, w) in g.waves.iter().enumerate() {
            let key = |f: &str| format!("gerstner.waves.{i}.{f}");
            check(&key("amplitude_m"), &[w.amplitude_m])?;
            check(&key("wavelength_m"), &[w.wavelength_m])?;
            check(&key("direction_deg"), &[w.direction_deg])?;
            check(&key("steepness"), &[w.steepness])?;
            check(&key("phase"), &[w.phase])?;
        }
        Ok(())
    }

    fn check_coastal(&self) -> Result<(), Refusal> {
        let c = &self.coastal;
        if let Some(center) = &c.center {
            check("coastal.center", center)?;
        }
        check("coastal.amplitude_m", &[c.amplitude_m])?;
        check("coastal.wavelength_m", &[c.wavelength_m])?;
        check_u32("coastal.power", c.power)?;
        check("coastal.back_factor", &[c.back_factor])?;
        check_u32("coastal.shininess", c.shininess)?;
        check("coastal.dull_factor", &[c.dull_factor])?;
        check("coastal.dull_color", &c.dull_color)?;
        check("coastal.distortion", &[c.distortion])?;
        if c.corrections.len() > MAX_CORRECTION_WAVES {
            return Err((
                "coastal.corrections".into(),
                format!(
                    "at most {MAX_CORRECTION_WAVES} correction waves (the seed's float4), got {}",
                    c.corrections.len()
                ),
            ));
        }
        for (i, w) in c.corrections.iter().enumerate() {
            let key = |f: &str| format!("coastal.corrections.{i}.{f}");
            check(&key("direction_deg"), &[w.direction_deg])?;
            check(&key("wavelength_m"), &[w.wavelength_m])?;
            check(&key("amplitude_m"), &[w.amplitude_m])?;
        }
        Ok(())
    }

    fn check_objects(&self) -> Result<(), Refusal> {
        for (i, obj) in self.objects.iter().enumerate() {
            let key = |f: &str| format!("objects.{i}.{f}");
            check(&key("center"), &obj.center)?;
            check(&key("color"), &obj.color)?;
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
                Some(Shape::Sphere { radius }) => check(&key("radius"), &[radius])?,
                Some(Shape::Box { size }) => check(&key("size"), &size)?,
                Some(Shape::Boat { size, heading_deg, mass_kg }) => {
                    check(&key("size"), &size)?;
                    check(&key("heading_deg"), &[heading_deg])?;
                    if let Some(m) = mass_kg {
                        check(&key("mass_kg"), &[m])?;
                    }
                    self.check_boat(i, obj)?;
                }
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
