//! Scene files: TOML, every key defaulted, unknown keys and bad values reported with the key,
//! the file, the line and the column (docs/design.md, "Scene files").
//!
//! Parsing happens in two steps. serde reads the text into [`Scene`] (unknown keys and wrong
//! types are caught here, and the `toml` crate gives the byte span); then [`Scene::validate`]
//! checks the values (ranges, NaN) and reports the dotted key path, whose position is found
//! again in the document so that a value error also names its line and column.

use std::fmt;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::dispersion::Dispersion;
use crate::geometry::PatchParams;
use crate::spectrum::{SpectrumKind, SpectrumParams, WaveSpectrum};
use crate::waves::{ModeParams, OceanParams, OceanSurface, WaveModes};

mod foam;
mod ggx;
mod locate;
mod sea;
mod validate;
mod view;

pub use crate::clouds::Clouds;
pub use crate::objects::{Object, ObjectKind, Shape};
pub use crate::spray::Spray;
pub use crate::terrain::{Terrain, TerrainKind};
pub use crate::tonemap::Post;
pub use foam::Foam;
pub use ggx::{Ggx, GgxFresnel, GgxGeometry};
use locate::{key_at_offset, key_of_line, key_position, line_column};
pub use sea::coastal_sea;
pub(crate) use sea::finite_time;
pub use validate::{
    LIMITS, Limit, MAX_COLOUR, MAX_COORDINATE_M, MAX_SUN_INTENSITY, MIN_LENGTH_M, limit,
};

/// The built-in default scene (open sea at late afternoon with a buoy and a rock).
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../../../reference/scenes/default.toml");

/// The coastal system's own built-in scene, an island (`reference/scenes/coastal_island.toml`):
/// its waves need a shore, which the default scene's open sea does not have.
pub const COASTAL_SCENE_TOML: &str =
    include_str!("../../../../reference/scenes/coastal_island.toml");

/// Where a scene came from, for error messages.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SceneSource {
    /// The scene embedded in the binary.
    BuiltIn,
    /// A file on disk.
    File(PathBuf),
    /// Text given directly (tests, tools).
    Text,
}

impl fmt::Display for SceneSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneSource::BuiltIn => f.write_str("<built-in default scene>"),
            SceneSource::File(p) => write!(f, "{}", p.display()),
            SceneSource::Text => f.write_str("<scene text>"),
        }
    }
}

/// A scene error: what is wrong, where (file, line, column, key) and, for I/O, the cause.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read: `"PATH: why"` (missing, not a regular file, larger than
    /// [`MAX_SCENE_FILE_BYTES`], not UTF-8).
    #[error("cannot read scene file {0}")]
    Read(String),
    /// The text is not valid TOML, has an unknown key or a value of the wrong type, or a value
    /// out of range.
    #[error("{source_name}:{line}:{column}: {}{message}", key.as_ref().map(|k| format!("key `{k}`: ")).unwrap_or_default())]
    Invalid {
        /// Where the scene came from.
        source_name: SceneSource,
        /// 1-based line (0 when the position is unknown).
        line: usize,
        /// 1-based column in characters (0 when unknown).
        column: usize,
        /// The dotted key path (`ocean.resolution`), when one is known.
        key: Option<String>,
        /// What is wrong and what is allowed.
        message: String,
    },
}

/// A whole scene. Every field has a default, so a file holds only what it changes.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct Scene {
    /// The seed paper's system whose techniques the frame uses (`hu`, the default; see
    /// `plan::SYSTEMS`).
    pub system: crate::technique::System,
    /// Per-stage overrides of the system's techniques.
    pub techniques: TechniqueOverrides,
    /// The sea: spectrum, grid, time.
    pub ocean: Ocean,
    /// The viewpoint.
    pub camera: Camera,
    /// The sun; absent means no sun (no shadow map, no specular).
    pub sun: Option<Sun>,
    /// Optical properties of the water.
    pub water: Water,
    /// Objects above and below the water.
    pub objects: Vec<Object>,
    /// Waves technique `gerstner`'s waves (seed 002).
    pub gerstner: crate::waves::gerstner::Gerstner,
    /// Waves technique `coastal`'s radial and correction waves (seed 004).
    pub coastal: crate::waves::coastal::Coastal,
    /// The sea floor; absent means a bottomless sea.
    pub terrain: Option<Terrain>,
    /// Parameters of seed 001's techniques (shading `chiu`).
    pub chiu: Chiu,
    /// Parameters of shading technique `ggx` (seed 002).
    pub ggx: Ggx,
    /// The cloud layer of sky technique `preetham_clouds`.
    pub clouds: Clouds,
    /// The particles of spray technique `particles`.
    pub spray: Spray,
    /// The white water of the foam techniques.
    pub foam: Foam,
    /// The post-processing of the final pass (stage `post`): the tonemap's curve, the
    /// vignette.
    pub post: Post,
    /// Cost/accuracy knobs of the renderer (what `ocean report` measures).
    pub quality: Quality,
}

pub use crate::technique::TechniqueOverrides;

/// Default side of the 2D Fresnel textures (docs/design.md, "Tolerances": 256² is within 2e-3 of eq. 2 up to 76°
/// from the normal).
pub const DEFAULT_FRESNEL_TABLE_SIZE: u32 = 256;

/// The `[quality]` table: what a frame may trade for speed. The defaults are the settings the
/// goldens were made with; `ocean report` measures each knob's error against its time.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Quality {
    /// Side N of the N × N 2D Fresnel textures (whole hemisphere).
    pub fresnel_table_size: u32,
    /// Side of the reflection map as a fraction of the viewport's, in (0, 1]. The water pass
    /// looks the map up at normalised screen coordinates, so a smaller map is a blurrier
    /// reflection of the objects, not a shifted one.
    pub reflection_map_scale: f64,
    /// Near-patch refinement: a triangle is split while its hypotenuse subtends more than this
    /// angle, radians (`geometry::PatchParams::split_threshold`).
    pub lod_split_threshold: f64,
    /// Surface `projected_grid`: pixels between two grid lines of the projector's image (the
    /// grid has ⌈width/cell⌉ × ⌈height/cell⌉ quads).
    pub projected_grid_cell_px: f64,
    /// Surface `clipmap`: the side of level 0's quads, m (level l's are 2^l times that).
    pub clipmap_cell_m: f64,
    /// Surface `clipmap`: quads per level side, a multiple of 8 in [16, 256].
    pub clipmap_cells: u32,
}

impl Default for Quality {
    fn default() -> Self {
        Self {
            fresnel_table_size: DEFAULT_FRESNEL_TABLE_SIZE,
            reflection_map_scale: 1.0,
            lod_split_threshold: 0.05,
            projected_grid_cell_px: 4.0,
            clipmap_cell_m: 0.5,
            clipmap_cells: 64,
        }
    }
}

/// The `[ocean]` table.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Ocean {
    /// Which spectrum.
    pub spectrum: SpectrumKind,
    /// Wind speed U₁₀ at 10 m, m/s.
    pub wind_speed: f64,
    /// Direction the wind blows towards, degrees from +x towards +z.
    pub wind_direction_deg: f64,
    /// Fetch, km (JONSWAP, TMA).
    pub fetch_km: f64,
    /// Depth, m; `inf` for deep water.
    pub depth_m: f64,
    /// JONSWAP peak enhancement γ.
    pub peak_enhancement: f64,
    /// Side of the displacement-map patch, m.
    pub patch_size_m: f64,
    /// Displacement-map resolution N (N × N samples).
    pub resolution: u32,
    /// Bump-map resolution (N × N samples of the finer patch).
    pub bump_resolution: u32,
    /// The bump-map patch is `patch_size_m / bump_patch_divisor` on a side.
    pub bump_patch_divisor: u32,
    /// Tessendorf's choppiness λ (0 = no horizontal displacement).
    pub choppiness: f64,
    /// Seed of the random amplitudes.
    pub seed: u64,
    /// Time of the frame, s.
    pub time_s: f64,
    /// Loop period T, s (0 = no looping).
    pub loop_period_s: f64,
    /// Phillips amplitude A (`spectrum = "phillips"` only).
    pub phillips_amplitude: f64,
    /// Phillips small-wave suppression length l, m (`spectrum = "phillips"` only).
    pub phillips_small_wave_m: f64,
}

impl Default for Ocean {
    fn default() -> Self {
        let s = SpectrumParams::default();
        Self {
            spectrum: s.kind,
            wind_speed: s.wind_speed,
            wind_direction_deg: s.wind_direction.to_degrees(),
            fetch_km: s.fetch_m / 1000.0,
            depth_m: s.depth_m,
            peak_enhancement: s.peak_enhancement,
            patch_size_m: 256.0,
            resolution: 256,
            bump_resolution: 256,
            bump_patch_divisor: 8,
            choppiness: 1.0,
            seed: 1,
            time_s: 0.0,
            loop_period_s: 0.0,
            phillips_amplitude: s.phillips_amplitude,
            phillips_small_wave_m: s.phillips_small_wave_m,
        }
    }
}

impl Ocean {
    /// The spectrum parameters in SI units (degrees → radians, km → m).
    pub fn spectrum_params(&self) -> SpectrumParams {
        SpectrumParams {
            kind: self.spectrum,
            wind_speed: self.wind_speed,
            wind_direction: self.wind_direction_deg.to_radians(),
            fetch_m: self.fetch_km * 1000.0,
            depth_m: self.depth_m,
            peak_enhancement: self.peak_enhancement,
            phillips_amplitude: self.phillips_amplitude,
            phillips_small_wave_m: self.phillips_small_wave_m,
            gravity: crate::GRAVITY,
        }
    }
}

impl Ocean {
    /// The dispersion relation of this sea (depth, loop period).
    pub fn dispersion(&self) -> crate::Result<Dispersion> {
        Dispersion::new(crate::GRAVITY, self.depth_m, self.loop_period_s)
    }

    /// The spectrum of this sea.
    pub fn wave_spectrum(&self) -> crate::Result<WaveSpectrum> {
        WaveSpectrum::new(self.spectrum_params())
    }

    /// The parameters of the displacement map / bump map pair (seed 000 §2.1).
    pub fn ocean_params(&self) -> crate::Result<OceanParams> {
        Ok(OceanParams {
            patch_size_m: self.patch_size_m,
            displacement_resolution: self.resolution as usize,
            bump_ratio: self.bump_patch_divisor as usize,
            bump_resolution: self.bump_resolution as usize,
            seed: self.seed,
            dispersion: self.dispersion()?,
        })
    }

    /// The random amplitudes of the displacement map alone (what `ocean heightfield` writes).
    pub fn displacement_modes(&self) -> crate::Result<WaveModes> {
        let spectrum = self.wave_spectrum()?;
        WaveModes::new(
            &ModeParams::new(self.patch_size_m, self.resolution as usize, self.seed),
            self.dispersion()?,
            |kx, kz| spectrum.density(kx, kz),
        )
    }

    /// The displacement map and bump map modes of this sea.
    pub fn surface(&self) -> crate::Result<OceanSurface> {
        let spectrum = self.wave_spectrum()?;
        OceanSurface::new(&self.ocean_params()?, |kx, kz| spectrum.density(kx, kz))
    }
}

impl Scene {
    /// The water mesh's parameters: [`PatchParams::for_ocean`] of the displacement grid, with
    /// the `[quality]` refinement threshold.
    pub fn patch_params(&self) -> PatchParams {
        PatchParams {
            split_threshold: self.quality.lod_split_threshold,
            ..PatchParams::for_ocean(self.ocean.patch_size_m, self.ocean.resolution)
        }
    }

    /// The water mesh's parameters for a view from `camera`: [`Self::patch_params`] with the
    /// near patch grown to the reach of the displacement map's waves from the eye's height
    /// ([`crate::geometry::wave_reach_m`] of the patch side, the viewpoint height and the
    /// camera's pixel angle), so that an eye high above the sea still sees the swell — but no
    /// farther than [`NEAR_PATCH_REACH_OVER_HEIGHT`] times the height.
    pub fn patch_params_for(&self, camera: &crate::camera::Camera) -> PatchParams {
        let params = self.patch_params();
        let height = camera.eye.y.abs().max(params.min_height_m);
        let reach =
            crate::geometry::wave_reach_m(self.ocean.patch_size_m, height, camera.pixel_angle());
        params.with_reach(reach.min(NEAR_PATCH_REACH_OVER_HEIGHT * height))
    }
}

/// How far the near patch may grow, in eye heights ([`Scene::patch_params_for`]): the sea
/// beyond 20·H lies within atan(1/20) ≈ 2.9° of the horizon, where the flat far patch and the
/// far field's filtered shading stand for the displacement's waves — the split the far field
/// `variance` is built and verified on (`tests/far_field_frames.rs`). Grown to the horizon
/// from low eyes (6 m: a 1 km patch at 320×180), its horizon bands against the 64-sample frame
/// were 0.0600 and 0.0629 (limit 0.06) and 12 % too bright in the storm (limit 10 %).
pub const NEAR_PATCH_REACH_OVER_HEIGHT: f64 = 20.0;

/// The `[camera]` table.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Camera {
    /// Eye position, m.
    pub position: [f64; 3],
    /// A point the camera looks at, m.
    pub look_at: [f64; 3],
    /// Vertical field of view, degrees.
    pub fov_y_deg: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
    /// Exposure multiplier applied before tonemapping (8-bit output only). The default 0.6
    /// undoes the pre-exposure of Narkowicz's ACES fit, giving the original ACES curve.
    pub exposure: f64,
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: [0.0, 6.0, 30.0],
            look_at: [0.0, 1.0, -60.0],
            fov_y_deg: 55.0,
            width: 1280,
            height: 720,
            exposure: 0.6,
        }
    }
}

/// The optional `[sun]` table.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Sun {
    /// Direction *towards* the sun (normalised on use).
    pub direction: [f64; 3],
    /// Linear RGB colour.
    pub color: [f64; 3],
    /// Radiance of the sun's disc and scale of its light (scene units; the sky's zenith is
    /// ~0.3–0.5 at the default sky scale).
    pub intensity: f64,
    /// Atmospheric turbidity T of the Preetham sky (2 = very clear, 10 = hazy).
    pub turbidity: f64,
    /// Local apparent solar time, h: when given, the sun stands where it does at that time
    /// on `day_of_year` at `latitude_deg` ([`crate::solar`]) and `direction` is set from it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_of_day_h: Option<f64>,
    /// Latitude for `time_of_day_h`, degrees north.
    pub latitude_deg: f64,
    /// Day of the year for `time_of_day_h` (1 = 1 January).
    pub day_of_year: f64,
}

impl Default for Sun {
    fn default() -> Self {
        Self {
            direction: [0.3, 0.25, -1.0],
            color: [1.0, 0.9, 0.75],
            intensity: 5.0,
            turbidity: crate::sky::DEFAULT_TURBIDITY,
            time_of_day_h: None,
            latitude_deg: 45.0,
            day_of_year: 172.0,
        }
    }
}

/// The `[water]` table.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Water {
    /// Index of refraction of water relative to air (η of eq. 2).
    pub ior: f64,
    /// Colour of deep water seen from above, linear RGB radiance at sun intensity 1: the
    /// C_deep_water of eq. 4 and the water-volume colour under the surface.
    pub color: [f64; 3],
    /// Diffuse extinction coefficient K, 1/m: eq. 4's fog with depth and the downwelling
    /// light on objects under water (Jerlov: ~0.02 in the clearest ocean water, 0.1–0.2 in
    /// coastal water, ~1 in turbid water).
    pub extinction_per_m: f64,
}

impl Default for Water {
    fn default() -> Self {
        Self { ior: 1.333, color: DEEP_WATER_COLOR, extinction_per_m: WATER_EXTINCTION_PER_M }
    }
}

/// The `[chiu]` table: the constants of Chiu & Chang's optics (seed 001 §3.5), which the
/// paper leaves to the user.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Chiu {
    /// Eq. 6's ζ, m: the local reflection and refraction maps are looked up at
    /// screen + ζ·n_xz/d, d the point's view depth, so the shift by the bump shrinks with
    /// distance (0.5 m shifts by hu's fixed 0.04 at 12.5 m).
    pub zeta_m: f64,
    /// Eq. 5's shininess per metre of view depth: the sun's Phong exponent is
    /// shininess_per_m · d, so the glitter narrows with distance (4 gives hu's 400 at 100 m).
    pub shininess_per_m: f64,
    /// Eq. 8's k_d, 1/m: the water colour (0.30, 0.73, 0.63)^(k_d·y) at depth y, i.e.
    /// attenuation coefficients −k_d·ln(0.30, 0.73, 0.63) per metre. 0.3 puts red's at
    /// 0.36 /m, pure water's absorption at 650 nm (Pope & Fry 1997: 0.34 /m); green's and
    /// blue's are then 0.09 and 0.14 /m, coastal water's.
    pub kd_per_m: f64,
    /// Eq. 8's depth y, m, where there is no sea floor (a bottomless sea): eq. 8 goes to black
    /// as y grows, so the open sea's colour is that of this depth (20 m: a dark sea green).
    pub open_sea_depth_m: f64,
    /// Eq. 1's scales s_i (one to four): the surface is Σ a_i·D(x/s_i) of the displacement map
    /// D, a_i = 1/√n so the sea's variance is kept. Scales that are not ratios of small whole
    /// numbers keep the sum from repeating (the default's 2.618 = φ² is irrational).
    pub scales: Vec<f64>,
}

impl Default for Chiu {
    fn default() -> Self {
        Self {
            zeta_m: 0.5,
            shininess_per_m: 4.0,
            kd_per_m: 0.3,
            open_sea_depth_m: 20.0,
            scales: vec![1.0, 2.618_034],
        }
    }
}

/// Default of `water.extinction_per_m`: diffuse extinction coefficient K of clear ocean water, 1/m (Jerlov type II, ~0.1 /m at
/// 500 nm); used by eq. 4's fog-from-depth and the water-volume colour.
pub const WATER_EXTINCTION_PER_M: f64 = 0.12;
/// Default of `water.color`: colour of deep water seen from above (linear RGB radiance at sun intensity 1), the
/// C_deep_water of eq. 4.
pub const DEEP_WATER_COLOR: [f64; 3] = [0.004, 0.016, 0.028];

/// The most scales of eq. 1 (`[[chiu.scales]]`; the uniforms' `MultiScaleBlock` holds this many).
pub const MAX_SCALES: usize = 4;

/// The largest grid a scene may ask for: 4096² complex f64 fields are ~2 GiB of scratch,
/// the most a 24 GiB machine should be asked to hold with room for the rest.
pub const MAX_RESOLUTION: u32 = 4096;

/// The largest `ocean.bump_patch_divisor`: the bump map's modes sit on the lattice of the
/// displacement patch at index divisor × resolution, which must stay far inside the
/// generator's i32 key (65536 × 4096 = 2²⁸), and a bump patch 65536 times smaller than the
/// displacement patch is already below a millimetre for a 256 m sea.
pub const MAX_BUMP_PATCH_DIVISOR: u32 = 65_536;
/// The largest image side: a 16384² f32 RGBA frame is 4 GiB.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// The largest scene file read, bytes: the reference scenes are 1–3 KB and 64 Gerstner waves
/// take about 8 KB; a larger file is a mistake (a link to `/dev/zero` would never end).
pub const MAX_SCENE_FILE_BYTES: u64 = 4 << 20;

impl Scene {
    /// The built-in default scene.
    pub fn builtin() -> Self {
        // The embedded text is part of the binary and covered by a test; failing here is a
        // build defect, not a user error.
        match Self::from_toml(DEFAULT_SCENE_TOML, SceneSource::BuiltIn) {
            Ok(s) => s,
            Err(e) => panic!("the built-in scene is invalid: {e}"),
        }
    }

    /// The built-in scene of `system`: the default scene, or for `coastal` its island
    /// ([`COASTAL_SCENE_TOML`]).
    pub fn builtin_for(system: crate::technique::System) -> Self {
        if system != crate::technique::System::Coastal {
            return Self::builtin();
        }
        match Self::from_toml(COASTAL_SCENE_TOML, SceneSource::BuiltIn) {
            Ok(s) => s,
            Err(e) => panic!("the built-in coastal scene is invalid: {e}"),
        }
    }

    /// Reads and validates a scene file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let text = crate::input::read_text(path, MAX_SCENE_FILE_BYTES).map_err(SceneError::Read)?;
        Self::from_toml(&text, SceneSource::File(path.to_owned()))
    }

    /// Parses and validates scene text.
    pub fn from_toml(text: &str, source: SceneSource) -> Result<Self, SceneError> {
        let scene: Scene = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map(|s| line_column(text, s.start)).unwrap_or((0, 0));
            SceneError::Invalid {
                source_name: source.clone(),
                line,
                column,
                key: e
                    .span()
                    .and_then(|s| key_at_offset(text, s.start).or_else(|| key_of_line(text, s))),
                message: e.message().trim().to_string(),
            }
        })?;
        let mut scene = scene;
        if let Err((key, message)) = scene.validate().and_then(|()| scene.load_assets(&source)) {
            let (line, column) = key_position(text, &key).unwrap_or((0, 0));
            return Err(SceneError::Invalid {
                source_name: source,
                line,
                column,
                key: Some(key),
                message,
            });
        }
        scene.place_sun();
        Ok(scene)
    }

    /// Sets `[sun] direction` from `time_of_day_h`, `day_of_year` and `latitude_deg` when a
    /// time is given ([`crate::solar::sun_direction`]); the scene loader calls it after
    /// validation, a caller that changes those keys calls it again.
    pub fn place_sun(&mut self) {
        if let Some(s) = &mut self.sun
            && let Some(t) = s.time_of_day_h
        {
            s.direction = crate::solar::sun_direction(s.latitude_deg, s.day_of_year, t);
        }
    }

    /// Reads the files the scene names (a `heightmap` floor's relief), relative to the scene
    /// file's folder, or to the working folder for text.
    fn load_assets(&mut self, source: &SceneSource) -> Result<(), (String, String)> {
        let base = match source {
            SceneSource::File(p) => p.parent().map(Path::to_owned).unwrap_or_default(),
            SceneSource::BuiltIn | SceneSource::Text => PathBuf::new(),
        };
        if let Some(t) = &mut self.terrain {
            if let (TerrainKind::Heightmap, Some(path)) = (t.kind, &t.heightmap) {
                let relief = crate::terrain::load_relief(path, &base, t.height_range_m)
                    .map_err(|e| ("terrain.heightmap".to_owned(), e))?;
                t.relief = Some(relief);
            }
            t.prepare();
        }
        Ok(())
    }

    /// The technique of every stage: the system's, with `[techniques]` applied.
    pub fn techniques(&self) -> crate::technique::Techniques {
        crate::technique::Techniques::of_overrides(self.system, &self.techniques)
    }

    /// The format of the frame's colour buffers: `[post] frame_format`, else the system's.
    pub fn frame_format(&self) -> crate::frame_format::FrameFormat {
        self.post.frame_format.unwrap_or(self.system.info().frame_format)
    }

    /// The scene rendered with another system: `system` replaced, `[techniques]` kept.
    ///
    /// # Errors
    /// As [`Self::validate`], when the system (or an override on top of it) cannot be
    /// rendered.
    pub fn with_system(mut self, system: crate::technique::System) -> Result<Self, SceneError> {
        self.system = system;
        if let Err((key, message)) = self.validate() {
            return Err(SceneError::Invalid {
                source_name: SceneSource::Text,
                line: 0,
                column: 0,
                key: Some(key),
                message,
            });
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> (usize, usize, Option<String>, String) {
        match Scene::from_toml(text, SceneSource::Text) {
            Err(SceneError::Invalid { line, column, key, message, .. }) => {
                (line, column, key, message)
            }
            other => panic!("expected an error for {text:?}, got {other:?}"),
        }
    }

    #[test]
    fn builtin_scene_parses() {
        let s = Scene::builtin();
        assert!(s.sun.is_some());
        assert!(!s.objects.is_empty());
    }

    #[test]
    fn empty_text_is_all_defaults() {
        let s = Scene::from_toml("", SceneSource::Text).unwrap();
        assert_eq!(s, Scene::default());
        assert!(s.sun.is_none());
    }

    #[test]
    fn unknown_key_names_key_line_and_column() {
        let (line, col, _, msg) = err("[ocean]\nwind_speed = 3.0\n  resolutoin = 64\n");
        assert_eq!((line, col), (3, 3));
        assert!(msg.contains("resolutoin"), "{msg}");
    }

    #[test]
    fn wrong_type_is_located() {
        let (line, _, key, msg) = err("[ocean]\n\nresolution = \"big\"\n");
        assert_eq!(line, 3);
        assert_eq!(key.as_deref(), Some("ocean.resolution"));
        let (line, _, key, _) =
            err("[[objects]]\nkind = \"sphere\"\ncenter = [0,0,0]\nradius = \"x\"\n");
        assert_eq!(line, 4);
        assert_eq!(key.as_deref(), Some("objects.0.radius"));
        assert!(msg.contains("invalid type") || msg.contains("expected"), "{msg}");
    }

    #[test]
    fn bad_values_name_key_and_line() {
        let (line, col, key, _) = err("[ocean]\nresolution = 0\n");
        assert_eq!(key.as_deref(), Some("ocean.resolution"));
        assert_eq!((line, col), (2, 1));
        let (line, _, key, _) = err("[camera]\nfov_y_deg = -10\n");
        assert_eq!(key.as_deref(), Some("camera.fov_y_deg"));
        assert_eq!(line, 2);
        let (line, _, key, _) = err("[ocean]\nwind_speed = nan\n");
        assert_eq!(key.as_deref(), Some("ocean.wind_speed"));
        assert_eq!(line, 2);
        let (line, _, key, _) = err(
            "[[objects]]\nkind = \"sphere\"\ncenter = [0,0,0]\nradius = 1\n\n[[objects]]\nkind = \"sphere\"\ncenter = [0,0,0]\nradius = -1\n",
        );
        assert_eq!(key.as_deref(), Some("objects.1.radius"));
        assert_eq!(line, 9);
    }

    #[test]
    fn infinite_depth_is_accepted_and_objects_parse() {
        let s = Scene::from_toml(
            "[ocean]\ndepth_m = inf\nspectrum = \"tma\"\n[[objects]]\nkind = \"box\"\ncenter = [1, 2, 3]\nsize = [1, 1, 1]\n",
            SceneSource::Text,
        )
        .unwrap();
        assert!(s.ocean.depth_m.is_infinite());
        assert_eq!(s.ocean.spectrum, SpectrumKind::Tma);
        assert!(matches!(s.objects[0].shape(), Some(Shape::Box { .. })));
        let (_, _, _, msg) = err("[[objects]]\nkind = \"cone\"\n");
        assert!(msg.contains("cone"), "{msg}");
        let (line, _, _, msg) =
            err("[[objects]]\nkind = \"sphere\"\ncenter = [0,0,0]\nradius = 1\nradus = 2\n");
        assert!(msg.contains("radus"), "{msg}");
        assert_eq!(line, 5);
        let (line, _, key, _) = err("[[objects]]\nkind = \"sphere\"\ncenter = [0,0,0]\n");
        assert_eq!(key.as_deref(), Some("objects.0.radius"));
        assert_eq!(line, 1);
        let (line, _, key, _) =
            err("[[objects]]\nkind = \"box\"\ncenter = [0,0,0]\nsize = [1,1,1]\nradius = 2\n");
        assert_eq!(key.as_deref(), Some("objects.0.radius"));
        assert_eq!(line, 5);
    }

    #[test]
    fn error_message_names_file_line_column_and_key() {
        let e = Scene::from_toml("[ocean]\nresolution = 0\n", SceneSource::File("sea.toml".into()))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("sea.toml:2:1: key `ocean.resolution`: "), "{e}");
    }
}
