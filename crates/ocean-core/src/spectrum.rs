//! Ocean wave spectra: Phillips (Tessendorf), Pierson–Moskowitz, JONSWAP, TMA, with normalised
//! directional spreading.
//!
//! Three views of one spectrum, all one-sided and in SI units:
//!
//! - the frequency spectrum S(ω), m²·s, with variance m₀ = ∫₀^∞ S(ω) dω;
//! - the omnidirectional wavenumber spectrum S_k(k), m³, with m₀ = ∫₀^∞ S_k(k) dk. For the
//!   spectra defined in ω (Pierson–Moskowitz, JONSWAP, TMA) S_k(k) = S(ω(k)) dω/dk, with the
//!   *continuous* finite-depth dispersion ω² = g k tanh(k h) (loop quantisation is a property
//!   of the synthesis, not of the sea's energy);
//! - the directional wavenumber spectrum F(k), m⁴, on the (kx, kz) plane, with
//!   m₀ = ∫∫ F dkx dkz and F(k) = S_k(|k|) D(|k|, θ) / |k| (the 1/|k| is the polar Jacobian).
//!
//! D(k, θ) is the directional spreading, θ the wave direction relative to the direction the wind
//! blows towards; ∫_{−π}^{π} D dθ = 1 exactly (in closed form), so spreading moves energy between
//! directions but never changes how much there is (docs/design.md, "Spectra").
//!
//! The significant wave height is Hs = 4 sqrt(m₀) (the spectral estimate H_m0).
//!
//! Quadrature (one place): every integral here is composite 8-point Gauss–Legendre on panels no
//! wider than a fixed step, with panel edges placed on every point where the integrand is not
//! smooth (the JONSWAP peak, where σ jumps; the spreading's break points r = 0.56, 0.95, 1.6).
//! Integrals along k use u = ln k as the variable (the spectra span decades).

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI, SQRT_2, TAU};

use crate::dispersion::Dispersion;
use crate::{Error, Result};

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

/// Phillips' constant α of the Pierson–Moskowitz spectrum (Pierson & Moskowitz 1964, J.
/// Geophys. Res. 69(24), 5181, who adopt Phillips' 1958 value 8.1·10⁻³).
pub const PM_ALPHA: f64 = 8.1e-3;

/// The Pierson–Moskowitz shape constant β in exp(−β (g/(U₁₉.₅ ω))⁴) (Pierson & Moskowitz 1964).
pub const PM_BETA: f64 = 0.74;

/// U₁₉.₅ / U₁₀: Pierson & Moskowitz measured the wind at 19.5 m; for a neutral log profile with
/// drag coefficient 1.3·10⁻³ the wind there is 1.026 times the 10 m wind (docs/design.md "Spectra";
/// Stewart, *Introduction to Physical Oceanography*, 2008, ch. 16).
pub const U19_5_PER_U10: f64 = 1.026;

/// JONSWAP mean peak enhancement γ (Hasselmann et al. 1973, Dtsch. Hydrogr. Z. A8(12)).
pub const JONSWAP_GAMMA_DEFAULT: f64 = 3.3;

/// JONSWAP peak width σ below the peak, ω ≤ ω_p (Hasselmann et al. 1973: σ_a = 0.07).
const JONSWAP_SIGMA_BELOW: f64 = 0.07;

/// JONSWAP peak width σ above the peak, ω > ω_p (Hasselmann et al. 1973: σ_b = 0.09).
const JONSWAP_SIGMA_ABOVE: f64 = 0.09;

/// The exp(−5/4 (ω_p/ω)⁴) of JONSWAP: the Pierson–Moskowitz form written with its own peak,
/// since d/dω [ω⁻⁵ exp(−b (ω_p/ω)⁴)] = 0 at ω_p requires b = 5/4 (Hasselmann et al. 1973).
const JONSWAP_SHAPE: f64 = 1.25;

/// The Phillips amplitude A that makes the Phillips spectrum's k⁻⁴ saturation range equal the
/// Pierson–Moskowitz tail in deep water.
///
/// Derivation: for ω ≫ ω_p, S(ω) → α g² ω⁻⁵; with ω = sqrt(g k), dω/dk = ω / (2k), so
/// S_k = S(ω) dω/dk → α/(2 k³) (Phillips 1958, J. Fluid Mech. 4, 426, the k⁻³ saturation range).
/// The Phillips spectrum integrated over direction is S_k = ∫ F k dθ = A π / k³ × (the two
/// cut-off exponentials), since ∫ cos²θ dθ = π. Equal tails: A π = α/2, so A = α/(2π)
/// = 8.1·10⁻³/(2π) ≈ 1.289·10⁻³ (dimensionless).
pub const PHILLIPS_AMPLITUDE_DEFAULT: f64 = PM_ALPHA / TAU;

/// Default Phillips small-wave suppression length l, metres: the capillary length
/// sqrt(σ_s/(ρ g)) of sea water, 2.7 mm (σ_s ≈ 0.073 N/m, IAPWS 2014 gives 0.0727 N/m for pure
/// water at 20 °C and sea water is ~1 % higher; ρ ≈ 1025 kg/m³; g = 9.81 m/s²).
///
/// Reasoning: the spectra here use gravity-wave dispersion only. At k = sqrt(ρ g/σ_s) ≈ 370
/// rad/m (wavelength 1.7 cm, the minimum phase speed) surface tension is as strong as gravity,
/// so shorter waves are not the waves this model describes. With l at the capillary length the
/// factor exp(−k² l²) is e⁻¹ at that crossover and leaves the gravity range (k ≪ 370 rad/m,
/// everything a rendering grid resolves) untouched: at k = 10 rad/m it is 0.9993.
pub const PHILLIPS_SMALL_WAVE_DEFAULT_M: f64 = 2.7e-3;

/// Largest accepted wind speed U₁₀, m/s. No measured surface wind comes near it (the WMO record
/// 3-second gust is 113.2 m/s, Barrow Island, 1996); bounding it keeps every formula here away
/// from overflow (U² and α g² ω⁻⁵ stay far inside f64).
pub const MAX_WIND_SPEED: f64 = 200.0;

/// Largest accepted fetch, metres: half the Earth's circumference (2·10⁷ m), the longest
/// great-circle distance wind can blow over. Bounds the JONSWAP peak level α g² ω_p⁻⁵ ∝ F^1.45.
pub const MAX_FETCH_M: f64 = 2.0e7;

/// Cap on the sech² spreading exponent β. Banner's extension 10^ε grows without bound as
/// r = ω/ω_p → 0 (it would overflow f64 below r ≈ 0.005); the cap is reached at r ≈ 0.29, where
/// the spectrum carries < 10⁻⁷⁰ of its peak density, so it changes no integral, and the lobe is
/// then 1 mrad wide, narrower than any grid resolves.
const SPREADING_BETA_MAX: f64 = 1.0e3;

/// exp(−x) underflows to 0 in f64 beyond this x (the smallest subnormal is 4.9·10⁻³²⁴ = e^−744.4);
/// returning 0 there avoids forming 0 · ∞ with a power of a tiny k or ω.
const EXP_UNDERFLOW: f64 = 745.0;

/// Ratio of the integration range to the spectral peak wavenumber k_p: [k_p/100, 10⁶ k_p].
/// Below k_p/100 (ω < ω_p/10 in deep water, less in shallow water) every spectrum here is below
/// exp(−1.25·10⁴) of its peak; above 10⁶ k_p the k⁻³ tail holds a fraction ~(k_p/k)² < 10⁻¹²
/// of the variance.
const RANGE_BELOW_PEAK: f64 = 1e-2;
/// Upper end of the integration range over k_p, see `RANGE_BELOW_PEAK`.
const RANGE_ABOVE_PEAK: f64 = 1e6;

/// Widest Gauss–Legendre panel along u = ln k. The narrowest feature is the JONSWAP peak,
/// exp(−(ω−ω_p)²/(2σ²ω_p²)) with σ = 0.07: 0.14 wide in ln k; eight nodes on 0.05 resolve it
/// to round-off (the unit tests halve the panel and see < 10⁻¹⁴ change).
const PANEL_LN_K: f64 = 0.05;

/// Widest Gauss–Legendre panel along ψ in the corner integral of `variance_over_square`
/// (k = W / cos ψ, so d ln k = tan ψ dψ ≤ dψ: finer than `PANEL_LN_K`).
const PANEL_PSI: f64 = 0.005;

/// Spreading break points r = ω/ω_p of Donelan, Hamilton & Hui (1985) and Banner (1990).
const SPREADING_BREAKS: [f64; 3] = [0.56, 0.95, 1.6];

impl Default for SpectrumParams {
    /// A JONSWAP sea: 10 m/s wind towards +x, 100 km fetch, deep water, γ = 3.3 (Hs ≈ 2.1 m,
    /// peak period ≈ 6.2 s); Phillips parameters at their defaults; g = [`crate::GRAVITY`].
    fn default() -> Self {
        Self {
            kind: SpectrumKind::Jonswap,
            wind_speed: 10.0,
            wind_direction: 0.0,
            fetch_m: 100.0e3,
            depth_m: f64::INFINITY,
            peak_enhancement: JONSWAP_GAMMA_DEFAULT,
            phillips_amplitude: PHILLIPS_AMPLITUDE_DEFAULT,
            phillips_small_wave_m: PHILLIPS_SMALL_WAVE_DEFAULT_M,
            gravity: crate::GRAVITY,
        }
    }
}

/// A validated wave spectrum with its derived constants.
#[derive(Clone, Debug)]
pub struct WaveSpectrum {
    params: SpectrumParams,
    dispersion: Dispersion,
    /// No wind: every density is 0.
    flat: bool,
    /// Unit vector the wind blows towards, (x, z).
    wind_unit: (f64, f64),
    /// α of the PM or JONSWAP form (dimensionless); unused for Phillips.
    alpha: f64,
    /// PM: ω₀ = g/U₁₉.₅; unused otherwise.
    omega_0: f64,
    /// Peak angular frequency ω_p of the deep-water frequency spectrum, rad/s: the scale of
    /// the spreading's r = ω/ω_p. ∞ for a flat sea.
    omega_p: f64,
    /// Phillips' largest wave L = V²/g, metres.
    phillips_l: f64,
    /// Wavenumber of ω_p under this water's dispersion, rad/m; centres the integration ranges.
    k_p: f64,
}

fn invalid(name: &'static str, value: f64, reason: &str) -> Error {
    Error::InvalidParameter { name, value, reason: reason.into() }
}

impl WaveSpectrum {
    /// Validates `params` and derives the spectrum's constants.
    ///
    /// Checked for every kind: gravity finite and > 0; wind speed finite, in [0,
    /// [`MAX_WIND_SPEED`]]; wind direction finite; depth > 0 (∞ allowed). JONSWAP and TMA also:
    /// fetch finite, in (0, [`MAX_FETCH_M`]]; γ finite and ≥ 1 (γ < 1 would turn the peak into
    /// a trough). Phillips also: amplitude finite and ≥ 0, small-wave length finite and ≥ 0.
    /// Parameters a kind does not use are not checked.
    pub fn new(params: SpectrumParams) -> Result<Self> {
        let p = &params;
        let g = p.gravity;
        if !(g > 0.0 && g.is_finite()) {
            return Err(invalid("gravity", g, "must be finite and > 0 m/s²"));
        }
        let u10 = p.wind_speed;
        if !(0.0..=MAX_WIND_SPEED).contains(&u10) {
            return Err(invalid(
                "wind_speed",
                u10,
                "must be in [0, 200] m/s (wind at 10 m; 0 = flat sea; 200 is above any \
                 measured surface wind)",
            ));
        }
        if !p.wind_direction.is_finite() {
            return Err(invalid("wind_direction", p.wind_direction, "must be finite (radians)"));
        }
        if p.depth_m.is_nan() || p.depth_m <= 0.0 {
            return Err(invalid("depth_m", p.depth_m, "must be > 0 m (use inf for deep water)"));
        }
        let fetch_limited = matches!(p.kind, SpectrumKind::Jonswap | SpectrumKind::Tma);
        if fetch_limited {
            if !(p.fetch_m > 0.0 && p.fetch_m <= MAX_FETCH_M) {
                return Err(invalid(
                    "fetch_m",
                    p.fetch_m,
                    "must be in (0, 2e7] m for JONSWAP/TMA (for an unlimited fetch use \
                     pierson-moskowitz)",
                ));
            }
            if !(p.peak_enhancement >= 1.0 && p.peak_enhancement.is_finite()) {
                return Err(invalid(
                    "peak_enhancement",
                    p.peak_enhancement,
                    "JONSWAP γ must be finite and ≥ 1 (1 = Pierson–Moskowitz shape, 3.3 = \
                     JONSWAP mean)",
                ));
            }
        }
        if p.kind == SpectrumKind::Phillips {
            if !(p.phillips_amplitude >= 0.0 && p.phillips_amplitude.is_finite()) {
                return Err(invalid(
                    "phillips_amplitude",
                    p.phillips_amplitude,
                    "must be finite and ≥ 0 (default α/(2π) ≈ 1.289e-3)",
                ));
            }
            if !(p.phillips_small_wave_m >= 0.0 && p.phillips_small_wave_m.is_finite()) {
                return Err(invalid(
                    "phillips_small_wave_m",
                    p.phillips_small_wave_m,
                    "must be finite and ≥ 0 m (0 = no small-wave suppression)",
                ));
            }
        }
        // The depth was checked above; loop_period 0 is always valid.
        let dispersion = Dispersion::new(g, p.depth_m, 0.0)?;

        let u19_5 = U19_5_PER_U10 * u10;
        let (alpha, omega_0, omega_p) = if u10 == 0.0 {
            (0.0, f64::INFINITY, f64::INFINITY)
        } else {
            match p.kind {
                SpectrumKind::PiersonMoskowitz => {
                    let omega_0 = g / u19_5;
                    (PM_ALPHA, omega_0, pm_peak_factor(PM_BETA) * omega_0)
                }
                SpectrumKind::Jonswap | SpectrumKind::Tma => {
                    let (alpha, omega_p) = jonswap_fetch_laws(u10, p.fetch_m, g);
                    (alpha, 0.0, omega_p)
                }
                // Deep-water Phillips is PM with β = 1 and U₁₉.₅ → V (see `peak_omega`).
                SpectrumKind::Phillips => (0.0, 0.0, pm_peak_factor(1.0) * g / u10),
            }
        };
        // A wind so weak that its peak frequency or α overflows f64 (a subnormal U₁₀, below
        // ~1e-308 m/s; found by the fuzzer: 5e-324 gave NaN densities) raises no wave a grid
        // can hold: a flat sea.
        let flat = u10 == 0.0 || !(omega_p.is_finite() && alpha.is_finite());
        let (alpha, omega_0, omega_p) =
            if flat { (0.0, f64::INFINITY, f64::INFINITY) } else { (alpha, omega_0, omega_p) };
        let phillips_l = u10 * u10 / g;
        let k_p = if flat {
            0.0
        } else if p.kind == SpectrumKind::Phillips {
            // Phillips is defined in k, whatever the depth: its deep-water peak.
            omega_p * omega_p / g
        } else {
            wavenumber(&dispersion, omega_p)
        };
        let (sin_w, cos_w) = p.wind_direction.sin_cos();
        Ok(Self {
            params,
            dispersion,
            flat,
            wind_unit: (cos_w, sin_w),
            alpha,
            omega_0,
            omega_p,
            phillips_l,
            k_p,
        })
    }

    /// The parameters this spectrum was built from.
    pub fn params(&self) -> &SpectrumParams {
        &self.params
    }

    /// Whether the sea is flat (no wind): every density is 0.
    pub fn is_flat(&self) -> bool {
        self.flat
    }

    /// The dispersion relation of this water (depth from the parameters), without looping:
    /// the spectrum's energy is defined with the continuous ω; the caller applies looping.
    pub fn dispersion(&self) -> Dispersion {
        self.dispersion
    }

    /// The α of the PM or JONSWAP form (`None` for Phillips or a flat sea).
    pub fn alpha(&self) -> Option<f64> {
        (!self.flat && self.params.kind != SpectrumKind::Phillips).then_some(self.alpha)
    }

    /// Peak angular frequency ω_p of the deep-water frequency spectrum, rad/s; `None` for a
    /// flat sea.
    ///
    /// - Pierson–Moskowitz: dS/dω = 0 ⇔ ω_p⁴ = (4β/5) ω₀⁴, so ω_p = (4β/5)^¼ g/U₁₉.₅
    ///   ≈ 0.877 g/U₁₉.₅.
    /// - JONSWAP, TMA: the fetch law ω_p = 22 (g²/(U₁₀ F))^⅓ (Hasselmann et al. 1973:
    ///   f_p = 3.5 (g/U₁₀) x̃^−0.33 with x̃ = gF/U₁₀², and 2π·3.5 ≈ 22). For TMA this is the
    ///   parameter of the JONSWAP factor; the depth factor moves the actual maximum slightly.
    /// - Phillips: in deep water its S(ω) = A π · 2 g² ω⁻⁵ exp(−(g/(V ω))⁴) (times the small-wave
    ///   factor) is the PM form with β = 1 and U₁₉.₅ → V, so ω_p = (4/5)^¼ g/V (l neglected).
    ///
    /// The spreading's r = ω/ω_p uses this value.
    pub fn peak_omega(&self) -> Option<f64> {
        (!self.flat).then_some(self.omega_p)
    }

    /// The frequency spectrum S(ω), m²·s (one-sided; ω ≤ 0, NaN or ∞ give 0).
    ///
    /// - Pierson–Moskowitz (1964): S = α g² ω⁻⁵ exp(−β (ω₀/ω)⁴), α = [`PM_ALPHA`],
    ///   β = [`PM_BETA`], ω₀ = g/U₁₉.₅, U₁₉.₅ = [`U19_5_PER_U10`] U₁₀.
    /// - JONSWAP (Hasselmann et al. 1973): S = α g² ω⁻⁵ exp(−5/4 (ω_p/ω)⁴) γ^r,
    ///   r = exp(−(ω − ω_p)²/(2 σ² ω_p²)), σ = 0.07 (ω ≤ ω_p) or 0.09, α = 0.076 (U₁₀²/(F g))^0.22,
    ///   ω_p = 22 (g²/(U₁₀ F))^⅓.
    /// - TMA (Bouws et al. 1985): JONSWAP × Φ(ω_h), the Kitaigorodskii depth factor, in its
    ///   exact form (see [`kitaigorodskii_depth_factor`]); α and ω_p keep JONSWAP's deep-water
    ///   fetch laws.
    /// - Phillips is defined in k; this returns its equivalent S(ω) = S_k(k(ω)) dk/dω under
    ///   this water's dispersion, so that ∫ S dω = ∫ S_k dk still holds.
    pub fn frequency_spectrum(&self, omega: f64) -> f64 {
        if self.flat || !(omega > 0.0 && omega.is_finite()) {
            return 0.0;
        }
        match self.params.kind {
            SpectrumKind::PiersonMoskowitz => {
                pm_form(self.alpha, self.params.gravity, PM_BETA, self.omega_0, omega)
            }
            SpectrumKind::Jonswap => self.jonswap(omega),
            SpectrumKind::Tma => {
                let h = self.params.depth_m;
                let phi = if h.is_finite() {
                    kitaigorodskii_depth_factor(omega * (h / self.params.gravity).sqrt())
                } else {
                    1.0
                };
                self.jonswap(omega) * phi
            }
            SpectrumKind::Phillips => {
                let k = wavenumber(&self.dispersion, omega);
                if !k.is_finite() {
                    return 0.0; // ω so large that ω²/g overflows: far beyond any spectrum
                }
                let c_g = self.dispersion.group_velocity(k);
                self.phillips_omnidirectional(k) / c_g
            }
        }
    }

    /// The omnidirectional wavenumber spectrum S_k(k), m³: m₀ = ∫₀^∞ S_k dk. k is a magnitude
    /// (negative k is read as |k|); k = 0, ∞ or NaN give 0.
    ///
    /// PM, JONSWAP, TMA: S_k(k) = S(ω(k)) dω/dk with the continuous finite-depth dispersion.
    /// Phillips: S_k = A π exp(−1/(kL)²) exp(−k² l²) / k³ (Tessendorf 2001 integrated over
    /// direction; ∫ cos²θ dθ = π).
    ///
    /// S_k(0) = 0: as k → 0 every spectrum here vanishes like exp(−c/k²) (PM, JONSWAP: ω → 0
    /// in exp(−β(ω₀/ω)⁴); Phillips: exp(−1/(kL)²)), faster than the powers of 1/k grow.
    pub fn omnidirectional(&self, k: f64) -> f64 {
        let k = k.abs();
        if self.flat || !(k > 0.0 && k.is_finite()) {
            return 0.0;
        }
        if self.params.kind == SpectrumKind::Phillips {
            return self.phillips_omnidirectional(k);
        }
        let d = &self.dispersion;
        let omega = d.omega_continuous(k);
        let s_omega = match self.params.kind {
            SpectrumKind::PiersonMoskowitz => {
                pm_form(self.alpha, self.params.gravity, PM_BETA, self.omega_0, omega)
            }
            SpectrumKind::Tma if self.params.depth_m.is_finite() => {
                // k is known here, so Φ comes from k h without inverting the dispersion.
                self.jonswap(omega) * kitaigorodskii_from_kh(k * self.params.depth_m)
            }
            _ => self.jonswap(omega),
        };
        if s_omega == 0.0 {
            // Skip dω/dk: at k ≲ 1e-150 in finite depth ω² underflows and
            // `Dispersion::group_velocity` returns ∞, and 0 · ∞ would be NaN.
            return 0.0;
        }
        s_omega * d.group_velocity(k)
    }

    /// The directional spreading D(k, θ), rad⁻¹, θ the wave direction relative to the wind
    /// (any real θ; it is wrapped to (−π, π]). ∫_{−π}^{π} D dθ = 1 exactly, D ≥ 0.
    ///
    /// - Phillips: D = cos²θ / π, Tessendorf's |k̂·ŵ|² normalised. It sends as much energy
    ///   upwind (θ = π) as downwind (θ = 0).
    /// - PM, JONSWAP, TMA: D = β/(2 tanh(βπ)) sech²(βθ) (Donelan, Hamilton & Hui 1985, Phil.
    ///   Trans. R. Soc. A 315, 509), r = ω(k)/ω_p:
    ///   β = 2.61 r^1.3 for 0.56 < r < 0.95, β = 2.28 r^−0.65 for 0.95 ≤ r < 1.6 (Donelan et
    ///   al. 1985), else β = 10^ε, ε = −0.4 + 0.8393 exp(−0.567 ln r²) (Banner 1990, J. Phys.
    ///   Oceanogr. 20, 966, for r > 1.6; applied below r = 0.56 too, as compiled by Horvath 2015,
    ///   "Empirical directional wave spectra for computer graphics"). β is capped at 1000
    ///   (see `SPREADING_BETA_MAX`); the normalisation uses the capped β, so it stays exact.
    ///   ∫ sech²(βθ) dθ over (−π, π] = 2 tanh(βπ)/β, hence the factor.
    /// - Flat sea: no wind direction; D = 1/(2π).
    pub fn spreading(&self, k: f64, theta: f64) -> f64 {
        if self.flat {
            return 1.0 / TAU;
        }
        let theta = wrap_angle(theta);
        match self.params.kind {
            SpectrumKind::Phillips => {
                let cos_theta = theta.cos();
                cos_theta * cos_theta / PI
            }
            _ => {
                let beta = self.spreading_beta(k);
                let sech = 1.0 / (beta * theta).cosh(); // cosh overflow → sech = 0, the limit
                beta / (2.0 * (beta * PI).tanh()) * sech * sech
            }
        }
    }

    /// The directional wavenumber spectrum F(kx, kz), m⁴: m₀ = ∫∫ F dkx dkz.
    /// F = S_k(|k|) D(|k|, θ) / |k|, θ = atan2(kz, kx) − wind direction.
    ///
    /// Phillips is evaluated as docs/design.md writes it (Tessendorf 2001):
    /// P(k) = A exp(−1/(kL)²)/k⁴ |k̂·ŵ|² exp(−k²l²), L = V²/g; it equals S_k D/k with
    /// S_k = Aπ exp(…) exp(…)/k³ and D = cos²θ/π.
    ///
    /// F(0) = 0: the limit, since S_k vanishes like exp(−c/k²) while 1/k (or 1/k⁴) grows only
    /// as a power. Non-finite k gives 0.
    pub fn density(&self, kx: f64, kz: f64) -> f64 {
        let k = kx.hypot(kz);
        if self.flat || !(k > 0.0 && k.is_finite()) {
            return 0.0;
        }
        if self.params.kind == SpectrumKind::Phillips {
            let (wx, wz) = self.wind_unit;
            let k_dot_w = (kx * wx + kz * wz) / k;
            let kl = k * self.phillips_l;
            let x = 1.0 / (kl * kl);
            if x > EXP_UNDERFLOW {
                return 0.0; // exp(−x) is 0; k⁴ may underflow too, so avoid 0/0
            }
            let l = self.params.phillips_small_wave_m;
            return self.params.phillips_amplitude * (-x).exp() / k.powi(4)
                * (k_dot_w * k_dot_w)
                * (-(k * k * l * l)).exp();
        }
        let theta = kz.atan2(kx) - self.params.wind_direction;
        self.omnidirectional(k) * self.spreading(k, theta) / k
    }

    /// The variance m₀ = ∫₀^∞ S_k dk of the surface elevation, m².
    ///
    /// Gauss–Legendre (8 nodes) on panels ≤ 0.05 wide in ln k over [k_p/100, 10⁶ k_p], a panel
    /// edge at k_p. Relative error ≈ 10⁻¹², all of it the k⁻³ tail left above 10⁶ k_p (for PM
    /// that tail is β (k₀/10⁶k_p)² m₀ = 1.25·10⁻¹² m₀: the tests measure Hs 6.3·10⁻¹³ below the
    /// closed form); the quadrature itself changes < 10⁻¹⁴ when the panels are halved.
    /// Cost: ~3000 evaluations of S_k.
    pub fn variance(&self) -> f64 {
        if self.flat {
            return 0.0;
        }
        let (k_lo, k_hi) = self.k_range();
        let breaks = self.k_breaks();
        integrate_ln_k(k_lo, k_hi, &breaks, PANEL_LN_K, |k| self.omnidirectional(k))
    }

    /// The significant wave height Hs = 4 sqrt(m₀), metres (see [`Self::variance`] for the
    /// quadrature and its accuracy).
    pub fn significant_wave_height(&self) -> f64 {
        4.0 * self.variance().sqrt()
    }

    /// ∫∫ F dkx dkz over the square |kx|, |kz| ≤ `half_width`, leaving out the disc
    /// |k| < `exclude_below`, m². This is the variance a grid resolves: an N × N FFT on a patch
    /// of side L holds the modes |kx|, |kz| < πN/L (pass `half_width = π N / L`), and its k = 0
    /// mode carries no wave (pass e.g. `exclude_below = π / L`, half the mode spacing, or 0).
    ///
    /// Method, in polar coordinates (F k dk dθ = S_k D dk dθ):
    /// - k ≤ W (= `half_width`): the whole circle lies in the square and ∫ D dθ = 1, so this
    ///   part is ∫ S_k dk over [max(exclude_below, k_p/100), W] — the 1D quadrature of
    ///   [`Self::variance`].
    /// - W < k ≤ W√2: the circle crosses the square; with ψ = arccos(W/k) the part inside is the
    ///   four arcs [mπ/2 + ψ, mπ/2 + π/2 − ψ], over which D is integrated in closed form
    ///   (sech² → tanh, cos² → θ/2 + sin 2θ/4). The radial integral is taken in ψ
    ///   (k = W/cos ψ, dk = W sin ψ/cos²ψ dψ), which removes the sqrt(k − W) singularity of
    ///   the arc length at k = W; panels ≤ 0.005 wide in ψ, edges at every k where the spreading
    ///   or JONSWAP σ switch.
    ///
    /// Accuracy: converged to round-off (halving the panels changes it by < 10⁻¹⁵; the unit
    /// tests assert 10⁻¹²), 10⁻¹³ against a 2D Simpson integral of the smooth Phillips F
    /// (integration tests); the contract asked for 10⁻⁴. `half_width` ≤ 0 or NaN gives 0; `half_width` = ∞ gives the variance outside the
    /// disc.
    pub fn variance_over_square(&self, half_width: f64, exclude_below: f64) -> f64 {
        self.variance_over_square_with(half_width, exclude_below, PANEL_LN_K, PANEL_PSI)
    }

    fn variance_over_square_with(
        &self,
        half_width: f64,
        exclude_below: f64,
        panel_ln_k: f64,
        panel_psi: f64,
    ) -> f64 {
        let w = half_width;
        if self.flat || w.is_nan() || w <= 0.0 {
            return 0.0;
        }
        // NaN or negative: nothing excluded.
        let e = if exclude_below > 0.0 { exclude_below } else { 0.0 };
        let (k_lo, k_hi) = self.k_range();
        let breaks = self.k_breaks();
        let s_k = |k: f64| self.omnidirectional(k);

        // The full circles, k ∈ [e, W].
        let lo = e.max(k_lo);
        let hi = w.min(k_hi);
        let mut v = if lo < hi { integrate_ln_k(lo, hi, &breaks, panel_ln_k, s_k) } else { 0.0 };

        // The corners, k ∈ [max(W, e), W√2].
        if w.is_finite() && e < w * SQRT_2 {
            let psi_start = if e > w { (w / e).acos() } else { 0.0 };
            let psi_breaks: Vec<f64> =
                breaks.iter().filter(|&&kb| kb > w).map(|&kb| (w / kb).acos()).collect();
            v += integrate_panels(psi_start, FRAC_PI_4, &psi_breaks, panel_psi, |psi| {
                let (sin_psi, cos_psi) = psi.sin_cos();
                let k = w / cos_psi;
                let dk_dpsi = w * sin_psi / (cos_psi * cos_psi);
                s_k(k) * self.spreading_inside_square(k, psi) * dk_dpsi
            });
        }
        v
    }

    /// ∫ D(k, θ) dθ over the four arcs [mπ/2 + ψ, mπ/2 + π/2 − ψ] (absolute directions) of the
    /// circle of radius k = W/cos ψ that lie inside the square |kx|, |kz| ≤ W.
    fn spreading_inside_square(&self, k: f64, psi: f64) -> f64 {
        let wind = self.params.wind_direction;
        (0..4)
            .map(|m| {
                let a = f64::from(m) * FRAC_PI_2 + psi - wind;
                let b = f64::from(m) * FRAC_PI_2 + FRAC_PI_2 - psi - wind;
                self.spreading_cumulative(k, b) - self.spreading_cumulative(k, a)
            })
            .sum()
    }

    /// C(θ) = ∫₀^θ D(k, θ') dθ' for any real θ (continuous: each full turn adds exactly 1).
    fn spreading_cumulative(&self, k: f64, theta: f64) -> f64 {
        let wrapped = wrap_angle(theta);
        let turns = ((theta - wrapped) / TAU).round();
        let partial = if self.flat {
            wrapped / TAU
        } else {
            match self.params.kind {
                SpectrumKind::Phillips => {
                    // ∫ cos²/π = (θ/2 + sin 2θ/4)/π.
                    (wrapped + wrapped.sin() * wrapped.cos()) / TAU
                }
                _ => {
                    let beta = self.spreading_beta(k);
                    (beta * wrapped).tanh() / (2.0 * (beta * PI).tanh())
                }
            }
        };
        turns + partial
    }

    /// The sech² exponent β(r), r = ω(k)/ω_p (Donelan et al. 1985; Banner 1990), capped.
    fn spreading_beta(&self, k: f64) -> f64 {
        let r = self.dispersion.omega_continuous(k) / self.omega_p;
        donelan_banner_beta(r)
    }

    /// JONSWAP's S(ω) with this spectrum's α, ω_p, γ.
    fn jonswap(&self, omega: f64) -> f64 {
        let omega_p = self.omega_p;
        let sigma = if omega <= omega_p { JONSWAP_SIGMA_BELOW } else { JONSWAP_SIGMA_ABOVE };
        let dw = (omega - omega_p) / (sigma * omega_p);
        let r = (-0.5 * dw * dw).exp();
        let pm = pm_form(self.alpha, self.params.gravity, JONSWAP_SHAPE, omega_p, omega);
        pm * self.params.peak_enhancement.powf(r)
    }

    /// Phillips S_k = A π exp(−1/(kL)²) exp(−k²l²)/k³, k > 0.
    fn phillips_omnidirectional(&self, k: f64) -> f64 {
        let kl = k * self.phillips_l;
        let x = 1.0 / (kl * kl);
        if x > EXP_UNDERFLOW {
            return 0.0;
        }
        let l = self.params.phillips_small_wave_m;
        self.params.phillips_amplitude * PI * (-x).exp() / (k * k * k) * (-(k * k * l * l)).exp()
    }

    /// [k_p/100, 10⁶ k_p], see `RANGE_BELOW_PEAK`.
    fn k_range(&self) -> (f64, f64) {
        (self.k_p * RANGE_BELOW_PEAK, self.k_p * RANGE_ABOVE_PEAK)
    }

    /// Wavenumbers where S_k or D is not smooth: k_p (JONSWAP, TMA: σ switches) and the
    /// spreading break points (PM, JONSWAP, TMA).
    fn k_breaks(&self) -> Vec<f64> {
        if self.flat || self.params.kind == SpectrumKind::Phillips {
            return Vec::new();
        }
        let mut breaks: Vec<f64> = SPREADING_BREAKS
            .iter()
            .map(|&r| wavenumber(&self.dispersion, r * self.omega_p))
            .collect();
        if self.params.kind != SpectrumKind::PiersonMoskowitz {
            breaks.push(self.k_p);
        }
        breaks
    }
}

/// (4β/5)^¼: ω_p/ω₀ of the form ω⁻⁵ exp(−β (ω₀/ω)⁴).
fn pm_peak_factor(beta: f64) -> f64 {
    (0.8 * beta).powf(0.25)
}

/// α g² ω⁻⁵ exp(−β (ω₀/ω)⁴), the Pierson–Moskowitz form (ω > 0). Returns 0 where the
/// exponential underflows, where ω⁻⁵ could otherwise overflow (0 · ∞).
fn pm_form(alpha: f64, g: f64, beta: f64, omega_0: f64, omega: f64) -> f64 {
    let u = omega_0 / omega;
    let x = beta * (u * u) * (u * u);
    if x > EXP_UNDERFLOW {
        return 0.0;
    }
    alpha * g * g / omega.powi(5) * (-x).exp()
}

/// JONSWAP's fetch laws (Hasselmann et al. 1973): α = 0.076 (U₁₀²/(F g))^0.22 and
/// ω_p = 22 (g²/(U₁₀ F))^⅓ (from f_p = 3.5 (g/U₁₀) (gF/U₁₀²)^−0.33, 2π·3.5 ≈ 22).
fn jonswap_fetch_laws(u10: f64, fetch: f64, g: f64) -> (f64, f64) {
    let alpha = 0.076 * (u10 * u10 / (fetch * g)).powf(0.22);
    let omega_p = 22.0 * (g * g / (u10 * fetch)).cbrt();
    (alpha, omega_p)
}

/// β(r) of the sech² spreading: Donelan, Hamilton & Hui (1985) for 0.56 < r < 1.6, Banner (1990)
/// elsewhere, capped at `SPREADING_BETA_MAX` (r = 0 gives the cap, not ∞).
fn donelan_banner_beta(r: f64) -> f64 {
    let beta = if r > 0.56 && r < 0.95 {
        2.61 * r.powf(1.3)
    } else if (0.95..1.6).contains(&r) {
        2.28 * r.powf(-0.65)
    } else {
        let epsilon = -0.4 + 0.8393 * (-0.567 * (r * r).ln()).exp();
        10f64.powf(epsilon)
    };
    beta.min(SPREADING_BETA_MAX)
}

/// θ wrapped to (−π, π].
fn wrap_angle(theta: f64) -> f64 {
    // rem_euclid is exact except that a tiny negative θ rounds to 2π, which maps to 0 below.
    let t = theta.rem_euclid(TAU);
    if t > PI { t - TAU } else { t }
}

/// The wavenumber k ≥ 0 with ω(k) = ω under the continuous dispersion ω² = g k tanh(k h).
///
/// Deep water: k = ω²/g. Finite depth: y = k h solves y tanh y = ω_h², ω_h = ω sqrt(h/g),
/// by Newton's method from Eckart's (1952) estimate y₀ = ω_h²/sqrt(tanh ω_h²), safeguarded by
/// bisection on the bracket [max(ω_h, ω_h²), ω_h + ω_h²] (y tanh y ≤ min(y, y²) gives the lower
/// end, tanh y ≥ y/(1+y) the upper); converges to a few ulp in ≤ 6 steps.
fn wavenumber(d: &Dispersion, omega: f64) -> f64 {
    let omega = omega.abs();
    let g = d.gravity;
    let h = d.depth_m;
    let k_deep = omega * omega / g;
    if h.is_infinite() || omega.is_nan() || omega == 0.0 {
        return k_deep;
    }
    let w2 = k_deep * h; // ω_h²
    // tanh(y) = 1 in f64 for y ≥ 19.1, and y ≥ ω_h², so then y = ω_h² (the `DEEP_KH` rule of
    // `Dispersion`).
    if w2 > 20.0 {
        return k_deep;
    }
    let w = w2.sqrt();
    let (mut lo, mut hi) = (w.max(w2), w + w2);
    let mut y = (w2 / w2.tanh().sqrt()).clamp(lo, hi);
    for _ in 0..60 {
        let t = y.tanh();
        let f = y * t - w2;
        if f > 0.0 {
            hi = y;
        } else {
            lo = y;
        }
        let df = t + y * (1.0 - t * t);
        let mut next = y - f / df;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - y).abs() <= 4.0 * f64::EPSILON * y {
            y = next;
            break;
        }
        y = next;
    }
    y / h
}

/// The Kitaigorodskii depth factor Φ(ω_h), ω_h = ω sqrt(h/g) (Kitaigorodskii, Krasitskii &
/// Zaslavskii 1975, J. Phys. Oceanogr. 5, 410), exact form: the ratio of the k⁻³ saturation
/// range mapped to ω in depth h to the same in deep water,
/// Φ = [k⁻³ dk/dω]_h / [k⁻³ dk/dω]_∞ = tanh²(kh) / (1 + 2kh / sinh 2kh), k from the finite-depth
/// dispersion. Φ → ω_h²/2 as ω_h → 0 and → 1 as ω_h → ∞.
///
/// [`kitaigorodskii_depth_factor_thompson_vincent`] is the usual piecewise approximation.
pub fn kitaigorodskii_depth_factor(omega_h: f64) -> f64 {
    // With g = h = 1, k h = y solves y tanh y = ω_h².
    let unit = Dispersion { gravity: 1.0, depth_m: 1.0, loop_period_s: 0.0 };
    kitaigorodskii_from_kh(wavenumber(&unit, omega_h))
}

/// Φ from y = k h: tanh²y / (1 + 2y/sinh 2y). y = 0 gives the limit 0; large y gives 1
/// (sinh overflows to ∞ and 2y/∞ = 0).
fn kitaigorodskii_from_kh(y: f64) -> f64 {
    if y.is_nan() || y <= 0.0 {
        return 0.0;
    }
    if y > 400.0 {
        // 2y/sinh 2y < 10⁻³⁴⁰ rounds to 0 and tanh y to 1: Φ = 1, as the formula gives for
        // finite y; the test also keeps y = ∞ away from ∞/∞.
        return 1.0;
    }
    let t = y.tanh();
    t * t / (1.0 + 2.0 * y / (2.0 * y).sinh())
}

/// Thompson & Vincent's (1983, "Prediction of wave height in shallow water", Proc. Coastal
/// Structures '83, ASCE) piecewise approximation of [`kitaigorodskii_depth_factor`]:
/// Φ = ω_h²/2 for ω_h ≤ 1, 1 − (2 − ω_h)²/2 for 1 < ω_h ≤ 2, 1 beyond. Its error against the
/// exact form is bounded in the tests (4.1 % at worst, at ω_h ≈ 1.07).
pub fn kitaigorodskii_depth_factor_thompson_vincent(omega_h: f64) -> f64 {
    let w = omega_h.abs();
    if w <= 1.0 {
        0.5 * w * w
    } else if w <= 2.0 {
        1.0 - 0.5 * (2.0 - w) * (2.0 - w)
    } else {
        1.0
    }
}

/// Nodes and weights of N-point Gauss–Legendre quadrature on [−1, 1], by Newton's method on
/// the Legendre polynomial P_N (Numerical Recipes' `gauleg`).
fn gauss_legendre<const N: usize>() -> ([f64; N], [f64; N]) {
    let mut x = [0.0; N];
    let mut wt = [0.0; N];
    for i in 0..N.div_ceil(2) {
        let mut z = (PI * (i as f64 + 0.75) / (N as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_N(z) and P_{N−1}(z) by the three-term recurrence.
            let (mut p1, mut p2) = (1.0, 0.0);
            for j in 0..N {
                let p3 = p2;
                p2 = p1;
                p1 = ((2 * j + 1) as f64 * z * p2 - j as f64 * p3) / (j + 1) as f64;
            }
            dp = N as f64 * (z * p1 - p2) / (z * z - 1.0);
            let z_prev = z;
            z = z_prev - p1 / dp;
            if (z - z_prev).abs() <= 1e-16 {
                break;
            }
        }
        x[i] = -z;
        x[N - 1 - i] = z;
        wt[i] = 2.0 / ((1.0 - z * z) * dp * dp);
        wt[N - 1 - i] = wt[i];
    }
    (x, wt)
}

/// ∫_a^b f(x) dx by 8-point Gauss–Legendre on equal panels ≤ `max_width` between consecutive
/// points of {a, b} ∪ (breaks ∩ (a, b)).
fn integrate_panels(a: f64, b: f64, breaks: &[f64], max_width: f64, f: impl Fn(f64) -> f64) -> f64 {
    if a.partial_cmp(&b) != Some(std::cmp::Ordering::Less) {
        return 0.0;
    }
    let (nodes, weights) = gauss_legendre::<8>();
    let mut edges: Vec<f64> = std::iter::once(a)
        .chain(breaks.iter().copied().filter(|&x| x > a && x < b))
        .chain(std::iter::once(b))
        .collect();
    edges.sort_by(f64::total_cmp);
    let mut total = 0.0;
    for seg in edges.windows(2) {
        let (s0, s1) = (seg[0], seg[1]);
        let n = ((s1 - s0) / max_width).ceil().max(1.0) as usize;
        let width = (s1 - s0) / n as f64;
        for p in 0..n {
            let mid = s0 + (p as f64 + 0.5) * width;
            let half = 0.5 * width;
            let panel: f64 = nodes.iter().zip(&weights).map(|(&x, &w)| w * f(mid + half * x)).sum();
            total += half * panel;
        }
    }
    total
}

/// ∫_a^b f(k) dk = ∫ f(e^u) e^u du over u = ln k, panels ≤ `max_width` in u, edges at `breaks`
/// (given in k). Requires 0 < a.
fn integrate_ln_k(a: f64, b: f64, breaks: &[f64], max_width: f64, f: impl Fn(f64) -> f64) -> f64 {
    if !(a > 0.0 && a < b) {
        return 0.0;
    }
    let ln_breaks: Vec<f64> = breaks.iter().filter(|&&k| k > 0.0).map(|k| k.ln()).collect();
    integrate_panels(a.ln(), b.ln(), &ln_breaks, max_width, |u| {
        let k = u.exp();
        f(k) * k
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: f64 = crate::GRAVITY;

    fn spectrum(kind: SpectrumKind, depth_m: f64) -> WaveSpectrum {
        let params = SpectrumParams { kind, depth_m, ..SpectrumParams::default() };
        WaveSpectrum::new(params).expect("valid parameters")
    }

    #[test]
    fn gauss_legendre_is_exact_to_degree_15() {
        let (x, w) = gauss_legendre::<8>();
        for p in 0..=17 {
            let q: f64 = x.iter().zip(&w).map(|(&x, &w)| w * x.powi(p)).sum();
            let exact = if p % 2 == 1 { 0.0 } else { 2.0 / (p as f64 + 1.0) };
            let err = (q - exact).abs();
            if p <= 15 {
                assert!(err < 1e-14, "degree {p}: {q} vs {exact}");
            } else if p == 16 {
                // Negative control: degree 2N = 16 is not integrated exactly.
                assert!(err > 1e-6, "degree 16 should not be exact: err {err}");
            }
        }
    }

    #[test]
    fn wavenumber_inverts_the_dispersion() {
        for h in [f64::INFINITY, 1e4, 5.0, 0.01, 1e-6] {
            let d = Dispersion { gravity: G, depth_m: h, loop_period_s: 0.0 };
            for &k in &[1e-9, 1e-4, 0.01, 0.1, 1.0, 3.0, 100.0, 1e5] {
                let omega = d.omega_continuous(k);
                let back = wavenumber(&d, omega);
                assert!((back - k).abs() <= 1e-13 * k, "h={h} k={k}: {back}");
            }
            assert_eq!(wavenumber(&d, 0.0), 0.0);
        }
    }

    #[test]
    fn wrap_angle_lands_in_half_open_interval() {
        for &t in &[0.0, PI, -PI, 3.0 * PI, -3.0 * PI, 1e-300, -1e-300, 7.0, -7.0, 1e6] {
            let w = wrap_angle(t);
            assert!(w > -PI && w <= PI, "{t} -> {w}");
            assert!((w.sin() - t.sin()).abs() < 1e-9 && (w.cos() - t.cos()).abs() < 1e-9);
        }
        assert_eq!(wrap_angle(-PI), PI);
    }

    #[test]
    fn spreading_cumulative_matches_numeric_integral() {
        for kind in [SpectrumKind::Phillips, SpectrumKind::Jonswap] {
            let s = spectrum(kind, f64::INFINITY);
            let k_p = s.k_p;
            for &k in &[0.5 * k_p, k_p, 3.0 * k_p] {
                for &(a, b) in &[(-0.3, 1.2), (2.0, 5.0), (-7.0, 1.0), (0.1, 0.1 + TAU)] {
                    let closed = s.spreading_cumulative(k, b) - s.spreading_cumulative(k, a);
                    // Panel edges at D's peak (0) and its kinks (±π, ±3π: sech² is wrapped).
                    let edges = [0.0, -PI, PI, -3.0 * PI, 3.0 * PI];
                    let numeric = integrate_panels(a, b, &edges, 0.01, |t| s.spreading(k, t));
                    assert!((closed - numeric).abs() < 1e-12, "{kind:?} k={k} [{a},{b}]");
                }
            }
        }
    }

    #[test]
    fn quadratures_converge_under_panel_halving() {
        for kind in [
            SpectrumKind::Phillips,
            SpectrumKind::PiersonMoskowitz,
            SpectrumKind::Jonswap,
            SpectrumKind::Tma,
        ] {
            let s = spectrum(kind, if kind == SpectrumKind::Tma { 5.0 } else { f64::INFINITY });
            let (lo, hi) = s.k_range();
            let breaks = s.k_breaks();
            let f = |k: f64| s.omnidirectional(k);
            let a = integrate_ln_k(lo, hi, &breaks, PANEL_LN_K, f);
            let b = integrate_ln_k(lo, hi, &breaks, 0.5 * PANEL_LN_K, f);
            println!("{kind:?}: m₀ changes by {:.1e} when panels are halved", (a - b) / b);
            assert!((a - b).abs() <= 1e-13 * b, "{kind:?}: {a} vs {b}");
            for w in [0.7 * s.k_p, 1.3 * s.k_p, 4.0 * s.k_p] {
                let a = s.variance_over_square_with(w, 0.0, PANEL_LN_K, PANEL_PSI);
                let b = s.variance_over_square_with(w, 0.0, 0.5 * PANEL_LN_K, 0.5 * PANEL_PSI);
                println!(
                    "  W = {:.1} k_p: square variance changes by {:.1e}",
                    w / s.k_p,
                    (a - b) / b
                );
                assert!((a - b).abs() <= 1e-12 * b, "{kind:?} W={w}: {a} vs {b}");
            }
            // Negative control: panels 20× wider than the chosen ones are visibly worse.
            let coarse = integrate_ln_k(lo, hi, &breaks, 20.0 * PANEL_LN_K, f);
            assert!((coarse - b).abs() > 1e-13 * b, "{kind:?}: coarse {coarse} vs {b}");
        }
    }

    #[test]
    fn tma_tail_is_the_depth_independent_saturation_range() {
        // Kitaigorodskii et al. 1975: with Φ the k⁻³ range α/(2k³) holds in any depth.
        for h in [f64::INFINITY, 50.0, 5.0, 0.5] {
            let s = spectrum(SpectrumKind::Tma, h);
            let alpha = s.alpha().expect("JONSWAP α");
            let k = 1e4 * s.k_p;
            let ratio = s.omnidirectional(k) * k * k * k / (0.5 * alpha);
            assert!((ratio - 1.0).abs() < 1e-6, "h={h}: {ratio}");
        }
    }

    #[test]
    fn thompson_vincent_error_is_bounded() {
        let mut worst: f64 = 0.0;
        for i in 1..=4000 {
            let w = f64::from(i) * 1e-3;
            let exact = kitaigorodskii_depth_factor(w);
            let approx = kitaigorodskii_depth_factor_thompson_vincent(w);
            worst = worst.max((approx - exact).abs() / exact);
        }
        println!("Thompson–Vincent vs exact Φ, worst relative error on (0, 4]: {worst:.4}");
        // Measured 4.09 % (at ω_h ≈ 1.07, just past the joint of the first two branches).
        assert!(worst < 0.045, "{worst}");
        assert!(worst > 0.01, "the approximation is not exact: {worst}");
    }
}
