//! Ocean wave spectra: Phillips (Tessendorf), Pierson–Moskowitz, JONSWAP, TMA, with normalised
//! directional spreading. TO BE WRITTEN (helper: spectrum).

/// Which spectrum a scene uses (scene key `ocean.spectrum`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpectrumKind {
    /// Phillips spectrum with Tessendorf's small-wave suppression and cos² spreading.
    Phillips,
    /// Fully developed sea (Pierson & Moskowitz 1964).
    PiersonMoskowitz,
    /// Fetch-limited sea (Hasselmann et al. 1973).
    Jonswap,
    /// JONSWAP in finite depth (Bouws et al. 1985).
    Tma,
}

/// Everything a spectrum needs, in SI units.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectrumParams {
    /// Which spectrum.
    pub kind: SpectrumKind,
    /// Wind speed U₁₀ at 10 m above the sea, m/s (≥ 0; 0 means a flat sea).
    pub wind_speed: f64,
    /// Direction the wind blows towards, radians, measured from +x towards +z.
    pub wind_direction: f64,
    /// Fetch, metres (JONSWAP, TMA).
    pub fetch_m: f64,
    /// Water depth, metres; `f64::INFINITY` for deep water.
    pub depth_m: f64,
    /// JONSWAP peak enhancement factor γ (Hasselmann 1973: 3.3).
    pub peak_enhancement: f64,
    /// Phillips amplitude A (only for `Phillips`).
    pub phillips_amplitude: f64,
    /// Phillips small-wave suppression length l, metres (only for `Phillips`).
    pub phillips_small_wave_m: f64,
    /// Gravitational acceleration, m/s².
    pub gravity: f64,
}

impl Default for SpectrumParams {
    fn default() -> Self {
        Self {
            kind: SpectrumKind::Jonswap,
            wind_speed: 10.0,
            wind_direction: 0.0,
            fetch_m: 100e3,
            depth_m: f64::INFINITY,
            peak_enhancement: 3.3,
            phillips_amplitude: 8.1e-3 / std::f64::consts::TAU,
            phillips_small_wave_m: 0.01,
            gravity: crate::GRAVITY,
        }
    }
}
