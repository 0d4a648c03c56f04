//! The viewer's parameter panel as data: what the sliders hold ([`ViewParams`]), how they map
//! onto a [`Scene`] ([`ViewParams::apply`]), and the presets ([`Preset`]). No window here: the
//! tests check the mapping directly.
//!
//! The mapping is exact where nothing changed: `ViewParams::from_scene(&s).apply(&s)` is `s`
//! bit for bit (the sun's direction is rewritten from the sliders only when they moved), so a
//! viewer that was not touched renders what `ocean render` renders.

use glam::DVec3;
use ocean_core::scene::Scene;
use ocean_core::spectrum::SpectrumKind;

/// Slider ranges, in the units the panel shows. Every value inside passes
/// [`Scene::validate`]; the wider scene-file ranges stay reachable through a scene file.
pub mod range {
    /// Wind speed U₁₀, m/s.
    pub const WIND_SPEED: (f64, f64) = (0.0, 40.0);
    /// Fetch, km.
    pub const FETCH_KM: (f64, f64) = (0.5, 2000.0);
    /// Depth for finite-depth water, m.
    pub const DEPTH_M: (f64, f64) = (0.5, 500.0);
    /// Choppiness λ.
    pub const CHOPPINESS: (f64, f64) = (0.0, 2.5);
    /// Patch size, m.
    pub const PATCH_SIZE_M: (f64, f64) = (16.0, 2048.0);
    /// Sun elevation, degrees (below 0: no sunlight, the planner drops the shadow map).
    pub const SUN_ELEVATION_DEG: (f64, f64) = (-10.0, 90.0);
    /// Water colour per channel (linear radiance at sun intensity 1).
    pub const WATER_COLOR: (f32, f32) = (1e-4, 0.5);
    /// Extinction K, 1/m.
    pub const EXTINCTION_PER_M: (f64, f64) = (0.01, 2.0);
    /// Simulated seconds per wall-clock second.
    pub const TIME_SCALE: (f64, f64) = (0.0, 10.0);
    /// Waves `gerstner`: the drawn waves' median amplitude, m.
    pub const GERSTNER_AMPLITUDE_M: (f64, f64) = (0.0, 3.0);
    /// Waves `gerstner`: the drawn waves' median wavelength, m.
    pub const GERSTNER_WAVELENGTH_M: (f64, f64) = (1.0, 200.0);
    /// Waves `coastal`: the radial waves' deep-water height A, m.
    pub const COASTAL_AMPLITUDE_M: (f64, f64) = (0.0, 3.0);
    /// Waves `coastal`: the radial waves' deep-water wavelength, m.
    pub const COASTAL_WAVELENGTH_M: (f64, f64) = (5.0, 120.0);
    /// The sea's level over the scene's floor (`[terrain]`), m: the floor moves down by it.
    pub const WATER_LEVEL_M: (f64, f64) = (-2.0, 2.0);
}

/// What the panel edits.
#[derive(Clone, Debug, PartialEq)]
pub struct ViewParams {
    /// Spectrum kind.
    pub spectrum: SpectrumKind,
    /// Wind speed U₁₀, m/s.
    pub wind_speed: f64,
    /// Direction the wind blows towards, degrees from +x towards +z.
    pub wind_direction_deg: f64,
    /// Fetch, km (JONSWAP, TMA).
    pub fetch_km: f64,
    /// Deep water (depth = ∞); else [`Self::depth_m`].
    pub deep: bool,
    /// Depth when not deep, m.
    pub depth_m: f64,
    /// Choppiness λ.
    pub choppiness: f64,
    /// Side of the displacement patch, m.
    pub patch_size_m: f64,
    /// Waves `gerstner`: the drawn waves' median amplitude, m.
    pub gerstner_amplitude_m: f64,
    /// Waves `gerstner`: the drawn waves' median wavelength, m.
    pub gerstner_wavelength_m: f64,
    /// Waves `coastal`: A, m (`coastal.amplitude_m`).
    pub coastal_amplitude_m: f64,
    /// Waves `coastal`: the deep-water wavelength, m (`coastal.wavelength_m`).
    pub coastal_wavelength_m: f64,
    /// The sea's level above the scene file's, m: `terrain.depth_m` grows by it, so the whole
    /// floor (the island's relief too) moves down (seed 004's water-level slider).
    pub water_level_m: f64,
    /// Whether the scene has a sun.
    pub sun: bool,
    /// Sun elevation above the horizon, degrees.
    pub sun_elevation_deg: f64,
    /// Sun azimuth, degrees: 0 towards −z (ahead of the default camera), 90 towards +x.
    pub sun_azimuth_deg: f64,
    /// Deep-water colour (`water.color`).
    pub water_color: [f32; 3],
    /// Extinction K, 1/m (`water.extinction_per_m`).
    pub extinction_per_m: f64,
    /// Simulated seconds per second of wall-clock time.
    pub time_scale: f64,
    /// Time stands still.
    pub paused: bool,
}

impl ViewParams {
    /// The panel's values for a scene (time scale 1, running).
    pub fn from_scene(scene: &Scene) -> Self {
        let o = &scene.ocean;
        let sun = scene.sun.clone().unwrap_or_default();
        let (elevation, azimuth) = sun_angles(sun.direction);
        Self {
            spectrum: o.spectrum,
            wind_speed: o.wind_speed,
            wind_direction_deg: o.wind_direction_deg,
            fetch_km: o.fetch_km,
            deep: o.depth_m.is_infinite(),
            depth_m: if o.depth_m.is_finite() { o.depth_m } else { 20.0 },
            choppiness: o.choppiness,
            patch_size_m: o.patch_size_m,
            gerstner_amplitude_m: scene.gerstner.median_amplitude_m,
            gerstner_wavelength_m: scene.gerstner.median_wavelength_m,
            coastal_amplitude_m: scene.coastal.amplitude_m,
            coastal_wavelength_m: scene.coastal.wavelength_m,
            water_level_m: 0.0,
            sun: scene.sun.is_some(),
            sun_elevation_deg: elevation,
            sun_azimuth_deg: azimuth,
            water_color: scene.water.color.map(|c| c as f32),
            extinction_per_m: scene.water.extinction_per_m,
            time_scale: 1.0,
            paused: false,
        }
    }

    /// `base` with these values, validated.
    ///
    /// # Errors
    /// `key: message` of the first value [`Scene::validate`] refuses.
    pub fn apply(&self, base: &Scene) -> Result<Scene, String> {
        let mut scene = base.clone();
        let o = &mut scene.ocean;
        o.spectrum = self.spectrum;
        o.wind_speed = self.wind_speed;
        o.wind_direction_deg = self.wind_direction_deg;
        o.fetch_km = self.fetch_km;
        o.depth_m = if self.deep { f64::INFINITY } else { self.depth_m };
        o.choppiness = self.choppiness;
        o.patch_size_m = self.patch_size_m;
        scene.gerstner.median_amplitude_m = self.gerstner_amplitude_m;
        scene.gerstner.median_wavelength_m = self.gerstner_wavelength_m;
        scene.coastal.amplitude_m = self.coastal_amplitude_m;
        scene.coastal.wavelength_m = self.coastal_wavelength_m;
        // The relief (an island's profile made at load) rides on the plane `depth_m` down, so
        // a deeper plane lowers every point of the floor alike.
        if let (Some(t), Some(b)) = (scene.terrain.as_mut(), base.terrain.as_ref())
            && self.water_level_m != 0.0
        {
            t.depth_m = b.depth_m + self.water_level_m;
        }
        let unchanged = Self::from_scene(base);
        scene.sun = if self.sun {
            let mut sun = base.sun.clone().unwrap_or_default();
            let moved = (self.sun_elevation_deg, self.sun_azimuth_deg)
                != (unchanged.sun_elevation_deg, unchanged.sun_azimuth_deg);
            if moved || base.sun.is_none() {
                sun.direction = sun_direction(self.sun_elevation_deg, self.sun_azimuth_deg);
            }
            Some(sun)
        } else {
            None
        };
        if self.water_color != unchanged.water_color {
            scene.water.color = self.water_color.map(f64::from);
        }
        scene.water.extinction_per_m = self.extinction_per_m;
        scene.validate().map_err(|(key, message)| format!("{key}: {message}"))?;
        Ok(scene)
    }

    /// These values with a preset's sea, water and sun; camera, time scale and pause kept.
    pub fn with_preset(&self, preset: Preset) -> Self {
        let mut p = self.clone();
        let (spectrum, wind, fetch, depth, chop, patch) = match preset {
            Preset::CalmLake => (SpectrumKind::Tma, 2.5, 3.0, Some(15.0), 0.4, 64.0),
            Preset::OpenOcean => (SpectrumKind::Jonswap, 9.0, 120.0, None, 1.0, 256.0),
            Preset::Storm => (SpectrumKind::Jonswap, 22.0, 500.0, None, 1.6, 512.0),
            Preset::ShallowReef => (SpectrumKind::Tma, 8.0, 20.0, Some(4.0), 0.8, 128.0),
            Preset::WelchCalmDay => (SpectrumKind::Jonswap, 6.0, 60.0, None, 0.8, 256.0),
            Preset::WelchStormySunset => (SpectrumKind::Jonswap, 17.0, 300.0, None, 1.4, 512.0),
            // The coastal presets' sea is the radial waves; the spectrum stays a light breeze's
            // for any system drawn with them.
            Preset::CoastalNoon => (SpectrumKind::Jonswap, 6.0, 60.0, None, 0.8, 256.0),
            Preset::CoastalSunset => (SpectrumKind::Jonswap, 8.0, 100.0, None, 1.0, 256.0),
        };
        // Seed 002's two looks (reference/scenes/welch_*.toml): the Gerstner waves too, and a
        // noon or a setting sun ahead; the other presets keep the Gerstner sea as it is.
        match preset {
            Preset::WelchCalmDay => {
                (p.gerstner_amplitude_m, p.gerstner_wavelength_m) = (0.08, 12.0)
            }
            Preset::WelchStormySunset => {
                (p.gerstner_amplitude_m, p.gerstner_wavelength_m) = (0.3, 28.0);
            }
            // Seed 004's two screenshots (reference/scenes/coastal_island.toml and
            // coastal_sunset.toml): the radial waves, and the level back at the scene's.
            Preset::CoastalNoon => {
                (p.coastal_amplitude_m, p.coastal_wavelength_m) = (0.9, 30.0);
                p.water_level_m = 0.0;
            }
            Preset::CoastalSunset => {
                (p.coastal_amplitude_m, p.coastal_wavelength_m) = (1.1, 36.0);
                p.water_level_m = 0.0;
            }
            _ => {}
        }
        p.spectrum = spectrum;
        p.wind_speed = wind;
        p.fetch_km = fetch;
        p.deep = depth.is_none();
        p.depth_m = depth.unwrap_or(p.depth_m);
        p.choppiness = chop;
        p.patch_size_m = patch;
        // Colours: deep blue open water (the scene default); greener, more turbid lake water;
        // dark storm water; turquoise over a bright reef floor, the clearest water.
        let (color, k, elevation) = match preset {
            Preset::CalmLake => ([0.006, 0.018, 0.014], 0.35, 35.0),
            Preset::OpenOcean => {
                let c = ocean_core::frame::DEEP_WATER_COLOR;
                (
                    [c[0] as f32, c[1] as f32, c[2] as f32],
                    ocean_core::frame::WATER_EXTINCTION_PER_M,
                    12.0,
                )
            }
            Preset::Storm => ([0.003, 0.010, 0.014], 0.2, 20.0),
            Preset::ShallowReef => ([0.010, 0.060, 0.060], 0.06, 40.0),
            Preset::WelchCalmDay => ([0.004, 0.016, 0.030], 0.12, 55.0),
            Preset::WelchStormySunset => ([0.003, 0.010, 0.014], 0.2, 3.0),
            Preset::CoastalNoon => {
                let c = ocean_core::frame::DEEP_WATER_COLOR;
                (
                    [c[0] as f32, c[1] as f32, c[2] as f32],
                    ocean_core::frame::WATER_EXTINCTION_PER_M,
                    55.0,
                )
            }
            Preset::CoastalSunset => ([0.004, 0.014, 0.020], 0.15, 5.0),
        };
        p.water_color = color;
        p.extinction_per_m = k;
        p.sun = true;
        p.sun_elevation_deg = elevation;
        if matches!(preset, Preset::WelchStormySunset | Preset::CoastalSunset) {
            p.sun_azimuth_deg = 0.0;
        }
        p
    }
}

/// The presets of the panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Preset {
    /// Light air over a 3 km lake, 15 m deep (TMA).
    CalmLake,
    /// The default scene's sea: 9 m/s over 120 km, deep.
    OpenOcean,
    /// 22 m/s over 500 km, choppy enough that crests fold.
    Storm,
    /// 8 m/s over 20 km in 4 m of clear water (TMA, finite-depth dispersion).
    ShallowReef,
    /// Seed 002's calm day: low Gerstner swell (8 cm, 12 m) under a high sun.
    WelchCalmDay,
    /// Seed 002's stormy sunset: 30 cm, 28 m Gerstner waves, 17 m/s, the sun 3° up ahead.
    WelchStormySunset,
    /// Seed 004's island at noon: 0.9 m, 30 m radial waves (waves `coastal`), a high sun.
    CoastalNoon,
    /// Seed 004's beach at sunset: 1.1 m, 36 m radial waves, the sun 5° up ahead.
    CoastalSunset,
}

impl Preset {
    /// Every preset, in the panel's order.
    pub const ALL: [Preset; 8] = [
        Preset::CalmLake,
        Preset::OpenOcean,
        Preset::Storm,
        Preset::ShallowReef,
        Preset::WelchCalmDay,
        Preset::WelchStormySunset,
        Preset::CoastalNoon,
        Preset::CoastalSunset,
    ];

    /// The button's label.
    pub fn label(self) -> &'static str {
        match self {
            Preset::CalmLake => "Calm lake",
            Preset::OpenOcean => "Open ocean",
            Preset::Storm => "Storm",
            Preset::ShallowReef => "Shallow reef",
            Preset::WelchCalmDay => "Calm day (Welch)",
            Preset::WelchStormySunset => "Stormy sunset (Welch)",
            Preset::CoastalNoon => "Island at noon (coastal)",
            Preset::CoastalSunset => "Beach at sunset (coastal)",
        }
    }
}

/// (elevation, azimuth) in degrees of a direction towards the sun (any length).
pub fn sun_angles(direction: [f64; 3]) -> (f64, f64) {
    let d = DVec3::from_array(direction);
    let elevation = d.y.atan2(d.x.hypot(d.z)).to_degrees();
    let azimuth = d.x.atan2(-d.z).to_degrees();
    (elevation, azimuth)
}

/// The unit direction towards a sun at `elevation_deg` above the horizon and `azimuth_deg`
/// (0 = −z, 90 = +x).
pub fn sun_direction(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (se, ce) = elevation_deg.to_radians().sin_cos();
    let (sa, ca) = azimuth_deg.to_radians().sin_cos();
    [sa * ce, se, -ca * ce]
}
