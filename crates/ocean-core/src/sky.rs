//! Daylight sky radiance: Preetham, Shirley & Smits (1999), "A practical analytic model for
//! daylight", SIGGRAPH '99 — the sky colour `C_skycolor` of Chiu & Chang's eq. 4 (seed 001).
//!
//! The model, in the paper's notation (θ: zenith angle of the view direction, γ: angle between
//! the view direction and the sun, θ_s: zenith angle of the sun, T: turbidity):
//!
//! - Perez et al. (1993) distribution, the paper's eq. 3 (here [`perez`]):
//!   F(θ, γ) = (1 + A e^{B / cos θ}) (1 + C e^{D γ} + E cos² γ).
//! - Each of Y (luminance), x and y (CIE chromaticity) follows it relative to the zenith:
//!   Y(θ, γ) = Y_z F_Y(θ, γ) / F_Y(0, θ_s), and the same for x and y (the paper's eq. 4).
//! - Coefficients A…E for each channel are linear in T (Appendix A.2, [`perez_coefficients`]).
//! - Zenith luminance in kcd/m² (Appendix A.2, [`zenith_luminance`]):
//!   Y_z = (4.0453 T − 4.9710) tan χ − 0.2155 T + 2.4192, χ = (4/9 − T/120)(π − 2θ_s).
//! - Zenith chromaticity: x_z = [T² T 1] M_x [θ_s³ θ_s² θ_s 1]ᵀ and likewise y_z with M_y
//!   (Appendix A.2, [`zenith_chromaticity`]).
//! - xyY → CIE XYZ → linear sRGB (Rec. 709 primaries, D65 white) with the matrix of
//!   IEC 61966-2-1:1999 ([`xyz_to_linear_srgb`]).
//!
//! Where the model is not defined this module decides, and every answer is finite:
//!
//! - **View below the horizon** (θ > 90°): with B < 0 (true for every T ≥ [`TURBIDITY_MIN`]),
//!   e^{B / cos θ} → 0 as cos θ → 0⁺ but blows up for cos θ < 0. cos θ is clamped to
//!   [`COS_THETA_MIN`] = 0.01, where the term is at most e^{−11} ≈ 1.4·10⁻⁵ (B_x at T = 1.7),
//!   so F differs from its horizon limit by less than 10⁻⁵ relative. The lower hemisphere
//!   thus repeats the horizon's θ-term while γ keeps its true value: finite and continuous
//!   across the horizon. The water hides that hemisphere in a rendered frame.
//! - **Sun at and below the horizon**: the fit covers 0 ≤ θ_s ≤ 90°. The model is evaluated
//!   at θ_s clamped to 90° and the sky is multiplied by a twilight fade that goes smoothly
//!   (smoothstep in elevation) from 1 at the horizon to [`NIGHT_FLOOR`] when the sun is
//!   [`TWILIGHT_DEPTH`] below it, continuous in the sun direction. γ is still measured from
//!   the true sun, so the circumsolar glow sinks below the horizon with the sun. Preetham does
//!   not model twilight; the fade only keeps the sky finite, continuous and dim at night.
//! - **Turbidity**: accepted in [[`TURBIDITY_MIN`], [`TURBIDITY_MAX`]]; the paper fits
//!   2 ≤ T ≤ 10 well (recommended). Below ~1.65 the factor 1 + A_Y e^{B_Y} at the zenith
//!   reaches 0 and the normalisation divides by zero; above ~11.2, Y_z becomes negative
//!   for a sun near the horizon, so Y_z is clamped at 0 (a black sky rather than a negative
//!   one).
//! - Out-of-gamut colours (negative linear sRGB) are clamped to 0, as renderers using this
//!   model usually do.
//!
//! What the model predicts (and `tests/sky.rs` checks): luminance peaks around the sun and
//! falls with γ; at fixed γ the sky brightens towards the horizon while A_Y < 0, i.e. for
//! T < 1.4630 / 0.1787 ≈ 8.19, and darkens towards it for hazier skies.
//!
//! The sun disc (0.53° across) is point-sampled at pixel centres like everything else: with a
//! 60° field of view it spans ≈ 9 pixels of a 1080-row frame but less than one of a 100-row
//! frame, where it may fall between centres.
//!
//! Radiometric scale: the model gives luminance in kcd/m². The HDR frame is in scene units in
//! which the scene's `[sun] intensity × color` is the solar disc's radiance; the sky is brought
//! to them by [`SkyParams::sky_scale`] (scene units per kcd/m², default
//! [`DEFAULT_SKY_SCALE`]). The real ratio of sun to sky luminance (~10⁵) is not kept: the
//! scene's sun is a specular-highlight strength, not a photometric quantity.

use crate::{Error, Result};

/// Smallest accepted turbidity: below ~1.65 the Perez zenith factor of Y vanishes.
pub const TURBIDITY_MIN: f64 = 1.7;
/// Largest accepted turbidity. Preetham et al. fitted the model for clear to hazy skies;
/// 2..=10 is the recommended range.
pub const TURBIDITY_MAX: f64 = 20.0;
/// Default turbidity: a clear sky (T = 2 is a very clear sky, T ≈ 6 a hazy one).
pub const DEFAULT_TURBIDITY: f64 = 2.5;
/// Lower clamp of cos θ of the view direction (see the module doc): views at or below the
/// horizon see the horizon's θ-term.
pub const COS_THETA_MIN: f64 = 0.01;
/// How far below the horizon the sun must be for the sky to reach [`NIGHT_FLOOR`]: 6°, the
/// end of civil twilight. Radians.
pub const TWILIGHT_DEPTH: f64 = 6.0 * std::f64::consts::PI / 180.0;
/// Fraction of the sunset sky (sun on the horizon) left at night: a dim floor so that the
/// night sky keeps the sunset's colours rather than going to exact black.
pub const NIGHT_FLOOR: f64 = 1e-3;
/// Angular radius of the solar disc: 0.2665°, half the mean apparent diameter of the sun
/// seen from the Earth (≈ 0.533°, i.e. a semi-diameter of 16′). Radians.
pub const SUN_ANGULAR_RADIUS: f64 = 0.2665 * std::f64::consts::PI / 180.0;
/// Width of the disc's anti-aliased rim, as a fraction of [`SUN_ANGULAR_RADIUS`]: the disc's
/// weight falls linearly in sin γ from 1 at r(1 − w/2) to 0 at r(1 + w/2), so half weight is
/// at the true radius.
pub const SUN_RIM_FRACTION: f64 = 0.1;
/// Default sky scale, scene units per kcd/m²: a clear noon zenith (Y_z ≈ 8 kcd/m² at T = 2.5,
/// θ_s = 30°) becomes ≈ 0.4, a mid tone after the tonemap at exposure 1.
pub const DEFAULT_SKY_SCALE: f64 = 0.05;
/// Smallest chromaticity y used in xyY → XYZ (which divides by y). Preetham's y stays near
/// 0.25–0.45 in the accepted turbidity range; the guard only keeps the division finite.
pub const MIN_CHROMATICITY_Y: f64 = 1e-4;

/// Preetham et al. (1999), Appendix A.2: the Perez coefficients of luminance Y as
/// `[slope, intercept]` of `slope · T + intercept`, rows A, B, C, D, E.
const PEREZ_Y: [[f64; 2]; 5] =
    [[0.1787, -1.4630], [-0.3554, 0.4275], [-0.0227, 5.3251], [0.1206, -2.5771], [-0.0670, 0.3703]];
/// As [`PEREZ_Y`], chromaticity x.
const PEREZ_X: [[f64; 2]; 5] = [
    [-0.0193, -0.2592],
    [-0.0665, 0.0008],
    [-0.0004, 0.2125],
    [-0.0641, -0.8989],
    [-0.0033, 0.0452],
];
/// As [`PEREZ_Y`], chromaticity y.
const PEREZ_YY: [[f64; 2]; 5] = [
    [-0.0167, -0.2608],
    [-0.0950, 0.0092],
    [-0.0079, 0.2102],
    [-0.0441, -1.6537],
    [-0.0109, 0.0529],
];

/// Preetham et al. (1999), Appendix A.2: zenith chromaticity x_z = [T² T 1] M [θ³ θ² θ 1]ᵀ.
const ZENITH_X: [[f64; 4]; 3] = [
    [0.00166, -0.00375, 0.00209, 0.0],
    [-0.02903, 0.06377, -0.03202, 0.00394],
    [0.11693, -0.21196, 0.06052, 0.25886],
];
/// As [`ZENITH_X`], for y_z.
const ZENITH_Y: [[f64; 4]; 3] = [
    [0.00275, -0.00610, 0.00317, 0.0],
    [-0.04214, 0.08970, -0.04153, 0.00516],
    [0.15346, -0.26756, 0.06670, 0.26688],
];

/// IEC 61966-2-1:1999 (sRGB), the matrix from CIE XYZ (D65, Y = 1 white) to linear sRGB,
/// rows R, G, B.
pub const XYZ_TO_LINEAR_SRGB: [[f64; 3]; 3] =
    [[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]];

/// The coefficients (A, B, C, D, E) of one channel's Perez function.
pub type PerezCoefficients = [f64; 5];

/// Preetham et al. (1999), Appendix A.2: the Perez coefficients of `[Y, x, y]` at turbidity
/// `turbidity` (no range check: see [`SkyParams::new`]).
pub fn perez_coefficients(turbidity: f64) -> [PerezCoefficients; 3] {
    [PEREZ_Y, PEREZ_X, PEREZ_YY].map(|table| table.map(|[slope, icpt]| slope * turbidity + icpt))
}

/// The Perez et al. (1993) distribution F(θ, γ) (Preetham et al. 1999, eq. 3) from cos θ and
/// γ: (1 + A e^{B / cos θ})(1 + C e^{D γ} + E cos² γ).
///
/// Defined for cos θ > 0; callers clamp it (module doc).
pub fn perez(k: &PerezCoefficients, cos_theta: f64, gamma: f64) -> f64 {
    let [a, b, c, d, e] = *k;
    let cos_gamma = gamma.cos();
    (1.0 + a * (b / cos_theta).exp()) * (1.0 + c * (d * gamma).exp() + e * cos_gamma * cos_gamma)
}

/// Preetham et al. (1999), Appendix A.2: zenith luminance Y_z in kcd/m² for a sun at zenith
/// angle `theta_s` (radians) and turbidity `turbidity`, unclamped.
pub fn zenith_luminance(theta_s: f64, turbidity: f64) -> f64 {
    let chi = (4.0 / 9.0 - turbidity / 120.0) * (std::f64::consts::PI - 2.0 * theta_s);
    (4.0453 * turbidity - 4.9710) * chi.tan() - 0.2155 * turbidity + 2.4192
}

/// Preetham et al. (1999), Appendix A.2: zenith chromaticity `[x_z, y_z]` for a sun at zenith
/// angle `theta_s` (radians) and turbidity `turbidity`.
pub fn zenith_chromaticity(theta_s: f64, turbidity: f64) -> [f64; 2] {
    let t = [turbidity * turbidity, turbidity, 1.0];
    let th = [theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0];
    [ZENITH_X, ZENITH_Y]
        .map(|m| (0..3).map(|i| t[i] * (0..4).map(|j| m[i][j] * th[j]).sum::<f64>()).sum::<f64>())
}

/// CIE xyY (`[Y, x, y]`, the order this module uses) to XYZ; y is clamped to
/// [`MIN_CHROMATICITY_Y`].
pub fn xyy_to_xyz(yxy: [f64; 3]) -> [f64; 3] {
    let [big_y, x, y] = yxy;
    let y = y.max(MIN_CHROMATICITY_Y);
    [x / y * big_y, big_y, (1.0 - x - y) / y * big_y]
}

/// CIE XYZ to linear sRGB, IEC 61966-2-1 ([`XYZ_TO_LINEAR_SRGB`]); no clamping.
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_LINEAR_SRGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

/// The twilight fade (module doc) at solar elevation `elevation` (radians, 0 at the horizon).
pub fn twilight_fade(elevation: f64) -> f64 {
    let t = ((elevation + TWILIGHT_DEPTH) / TWILIGHT_DEPTH).clamp(0.0, 1.0);
    let s = t * t * (3.0 - 2.0 * t);
    NIGHT_FLOOR + (1.0 - NIGHT_FLOOR) * s
}

/// What the sky needs from the scene. Build it with [`SkyParams::new`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyParams {
    /// Unit direction towards the sun (y up).
    pub sun_direction: [f64; 3],
    /// Turbidity T.
    pub turbidity: f64,
    /// Radiance of the solar disc in scene units, linear sRGB: the scene's
    /// `[sun] intensity × color`.
    pub sun_radiance: [f64; 3],
    /// Scene units per kcd/m² of sky luminance.
    pub sky_scale: f64,
}

impl SkyParams {
    /// Sky parameters from the scene's sun (`direction` towards the sun, any length;
    /// `color`, `intensity`) and a turbidity, with the [`DEFAULT_SKY_SCALE`].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a zero or non-finite direction, a turbidity outside
    /// [[`TURBIDITY_MIN`], [`TURBIDITY_MAX`]], or a negative or non-finite colour or intensity.
    pub fn new(
        sun_direction: [f64; 3],
        turbidity: f64,
        sun_color: [f64; 3],
        sun_intensity: f64,
    ) -> Result<Self> {
        let len = length(sun_direction);
        if !(len.is_finite() && len > 0.0) {
            return Err(Error::InvalidParameter {
                name: "sun.direction",
                value: len,
                reason: "the direction towards the sun needs a finite, non-zero length".into(),
            });
        }
        if !(TURBIDITY_MIN..=TURBIDITY_MAX).contains(&turbidity) {
            return Err(Error::InvalidParameter {
                name: "turbidity",
                value: turbidity,
                reason: format!(
                    "Preetham's sky is defined for {TURBIDITY_MIN} <= T <= {TURBIDITY_MAX} \
                     (2 to 10 recommended)"
                ),
            });
        }
        for value in sun_color.into_iter().chain([sun_intensity]) {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::InvalidParameter {
                    name: "sun.color × sun.intensity",
                    value,
                    reason: "the sun's colour and intensity must be finite and >= 0".into(),
                });
            }
        }
        Ok(Self {
            sun_direction: sun_direction.map(|c| c / len),
            turbidity,
            sun_radiance: sun_color.map(|c| c * sun_intensity),
            sky_scale: DEFAULT_SKY_SCALE,
        })
    }

    /// The same parameters with another sky scale (scene units per kcd/m²).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `sky_scale` is finite and ≥ 0.
    pub fn with_sky_scale(self, sky_scale: f64) -> Result<Self> {
        if !(sky_scale.is_finite() && sky_scale >= 0.0) {
            return Err(Error::InvalidParameter {
                name: "sky_scale",
                value: sky_scale,
                reason: "the sky scale must be finite and >= 0".into(),
            });
        }
        Ok(Self { sky_scale, ..self })
    }
}

/// The Preetham sky for one sun position and turbidity: everything per frame precomputed, in
/// f64. [`PreethamSky::radiance`] is the reference the `sky` stage is tested against.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PreethamSky {
    /// The parameters it was built from.
    pub params: SkyParams,
    /// Zenith angle of the sun, radians, in [0, π].
    pub theta_sun: f64,
    /// θ_s at which the model is evaluated: `theta_sun` clamped to π/2 (module doc).
    pub theta_model: f64,
    /// Perez coefficients of `[Y, x, y]`.
    pub coefficients: [PerezCoefficients; 3],
    /// Zenith values `[Y_z (kcd/m², ≥ 0), x_z, y_z]`.
    pub zenith: [f64; 3],
    /// F(0, θ_model) of each channel: the normalisation of eq. 4.
    pub perez_zenith: [f64; 3],
    /// The twilight fade at the sun's elevation (1 with the sun above the horizon).
    pub fade: f64,
}

impl PreethamSky {
    /// Precomputes the sky for `params`.
    pub fn new(params: SkyParams) -> Self {
        let s = params.sun_direction;
        let theta_sun = (s[0] * s[0] + s[2] * s[2]).sqrt().atan2(s[1]);
        let theta_model = theta_sun.min(std::f64::consts::FRAC_PI_2);
        let t = params.turbidity;
        let coefficients = perez_coefficients(t);
        let [x_z, y_z] = zenith_chromaticity(theta_model, t);
        let zenith = [zenith_luminance(theta_model, t).max(0.0), x_z, y_z];
        let perez_zenith = coefficients.map(|k| perez(&k, 1.0, theta_model));
        let fade = twilight_fade(std::f64::consts::FRAC_PI_2 - theta_sun);
        Self { params, theta_sun, theta_model, coefficients, zenith, perez_zenith, fade }
    }

    /// The model's `[Y (kcd/m²), x, y]` in direction `dir` (any length), before the fade and
    /// the scale; cos θ is clamped to [`COS_THETA_MIN`]. A zero or non-finite `dir` gives
    /// zeros.
    pub fn yxy(&self, dir: [f64; 3]) -> [f64; 3] {
        let Some(d) = normalized(dir) else { return [0.0; 3] };
        let cos_theta = d[1].max(COS_THETA_MIN);
        let gamma = angle_between(d, self.params.sun_direction);
        std::array::from_fn(|c| {
            self.zenith[c] * perez(&self.coefficients[c], cos_theta, gamma) / self.perez_zenith[c]
        })
    }

    /// Sky radiance without the sun disc in direction `dir`: linear sRGB, scene units
    /// (negative components clamped to 0, times the fade and the sky scale).
    pub fn sky_radiance(&self, dir: [f64; 3]) -> [f64; 3] {
        let rgb = xyz_to_linear_srgb(xyy_to_xyz(self.yxy(dir)));
        let scale = self.params.sky_scale * self.fade;
        rgb.map(|c| c.max(0.0) * scale)
    }

    /// Weight of the sun disc in direction `dir`, in [0, 1]: 1 inside, a linear rim in sin γ
    /// ([`SUN_RIM_FRACTION`]), 0 outside and 0 below the horizon (y < 0), where the Earth
    /// hides the sun.
    pub fn sun_disc_weight(&self, dir: [f64; 3]) -> f64 {
        let Some(d) = normalized(dir) else { return 0.0 };
        let s = self.params.sun_direction;
        let cos_gamma = dot(d, s);
        let sin_gamma = length(cross(d, s));
        let [sin_inner, sin_outer] = sun_rim_sines();
        let ramp = ((sin_outer - sin_gamma) / (sin_outer - sin_inner)).clamp(0.0, 1.0);
        if cos_gamma > 0.0 && d[1] >= 0.0 { ramp } else { 0.0 }
    }

    /// Radiance of the sun disc in direction `dir`: the scene's sun radiance times
    /// [`PreethamSky::sun_disc_weight`].
    pub fn sun_disc(&self, dir: [f64; 3]) -> [f64; 3] {
        let w = self.sun_disc_weight(dir);
        self.params.sun_radiance.map(|c| c * w)
    }

    /// What the `sky` stage draws in direction `dir`: sky plus sun disc, linear sRGB, scene
    /// units.
    pub fn radiance(&self, dir: [f64; 3]) -> [f64; 3] {
        let sky = self.sky_radiance(dir);
        let sun = self.sun_disc(dir);
        std::array::from_fn(|c| sky[c] + sun[c])
    }

    /// The uniforms of the `sky` stage (f32).
    pub fn uniforms(&self) -> SkyUniforms {
        let channel = |i: usize| -> [f32; 4] {
            let k = &self.coefficients;
            [k[0][i] as f32, k[1][i] as f32, k[2][i] as f32, 0.0]
        };
        let vec3 = |v: [f64; 3]| [v[0] as f32, v[1] as f32, v[2] as f32, 0.0];
        let [sun_sin_inner, sun_sin_outer] = sun_rim_sines();
        SkyUniforms {
            perez_a: channel(0),
            perez_b: channel(1),
            perez_c: channel(2),
            perez_d: channel(3),
            perez_e: channel(4),
            zenith: vec3(self.zenith),
            perez_zenith: vec3(self.perez_zenith),
            sun_direction: vec3(self.params.sun_direction),
            sun_radiance: vec3(self.params.sun_radiance),
            sky_scale: (self.params.sky_scale * self.fade) as f32,
            cos_theta_min: COS_THETA_MIN as f32,
            sun_sin_inner: sun_sin_inner as f32,
            sun_sin_outer: sun_sin_outer as f32,
            cloud_origin: [0.0; 4],
            cloud_color: [0.0; 4],
        }
    }
}

/// sin of the inner and outer radius of the disc's rim ([`SUN_RIM_FRACTION`]).
fn sun_rim_sines() -> [f64; 2] {
    let half = 0.5 * SUN_RIM_FRACTION * SUN_ANGULAR_RADIUS;
    [(SUN_ANGULAR_RADIUS - half).sin(), (SUN_ANGULAR_RADIUS + half).sin()]
}

/// The uniforms of the `sky` stage (`SkyUniforms` in `shaders/shared/preetham.wgsl`), built by
/// [`PreethamSky::uniforms`] (the cloud layer's fields by the frame's inputs). Vectors are `vec4<f32>` with an unused `w` = 0; channels are
/// ordered (Y, x, y).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SkyUniforms {
    /// Perez A of (Y, x, y).
    pub perez_a: [f32; 4],
    /// Perez B of (Y, x, y).
    pub perez_b: [f32; 4],
    /// Perez C of (Y, x, y).
    pub perez_c: [f32; 4],
    /// Perez D of (Y, x, y).
    pub perez_d: [f32; 4],
    /// Perez E of (Y, x, y).
    pub perez_e: [f32; 4],
    /// Zenith values (Y_z in kcd/m², x_z, y_z).
    pub zenith: [f32; 4],
    /// F(0, θ_s) of (Y, x, y): the normalisation of eq. 4.
    pub perez_zenith: [f32; 4],
    /// Unit direction towards the sun.
    pub sun_direction: [f32; 4],
    /// Radiance of the sun disc, linear sRGB, scene units.
    pub sun_radiance: [f32; 4],
    /// Scene units per kcd/m², the twilight fade included.
    pub sky_scale: f32,
    /// [`COS_THETA_MIN`].
    pub cos_theta_min: f32,
    /// sin of the inner radius of the disc's rim.
    pub sun_sin_inner: f32,
    /// sin of the outer radius of the disc's rim.
    pub sun_sin_outer: f32,
    /// Sky technique `preetham_clouds`' layer ([`crate::clouds::cloud_origin`]): the eye's
    /// (x, z) on the noise lattice, the layer's height above the eye in cells, the opacity's
    /// threshold.
    pub cloud_origin: [f32; 4],
    /// The lit cloud's radiance (rgb) and the layer's mean opacity (w).
    pub cloud_color: [f32; 4],
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

fn length(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// `a / |a|`, or `None` for a zero or non-finite vector.
fn normalized(a: [f64; 3]) -> Option<[f64; 3]> {
    let len = length(a);
    (len.is_finite() && len > 0.0).then(|| a.map(|c| c / len))
}

/// The angle between two unit vectors, accurate at 0 and π (atan2 of |a × b| and a · b).
fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    length(cross(a, b)).atan2(dot(a, b))
}
