//! The `tonemap` stage's parameters: HDR linear frame → 8-bit sRGB.
//!
//! Per pixel, in this order (`shaders/tonemap.wgsl`, mirrored by `ocean-cpu`'s
//! `shaders::tonemap`):
//!
//! 1. `exposed = hdr · exposure`.
//! 2. Sanitise: `x = min(max(exposed, 0), HDR_MAX)`. NaN → 0 (IEEE `maxNum` returns the
//!    number), −∞ and negatives → 0, +∞ → [`HDR_MAX`] (white after step 3). The bound keeps
//!    x² finite in f32. (WGSL leaves `max` of a NaN undefined; hardware whose `max` follows
//!    IEEE `maxNum`, lavapipe included, gives 0 as the CPU does.)
//! 3. Vignette (`[post] vignette`, strength s ∈ [0, 1], default 0): `x ← x · v` with
//!    v = max(1 − s·r², 0), r² = ((p_x − c_x)² + (p_y − c_y)²) / (c_x² + c_y²), p the pixel
//!    centre, c = (width/2, height/2): r = 0 at the centre, 1 at the image's corner, so the
//!    darkening is smooth (quadratic, like the cos⁴ fall-off of a lens to second order) and
//!    round whatever the aspect ratio. It multiplies the exposed light before the curve, as a
//!    lens's fall-off does; s = 0 leaves every pixel's bits unchanged (x · 1 = x). Only + − ×
//!    on f32, so CPU and GPU agree bit for bit. (docs/design.md lists `vignette` as a post
//!    technique; a per-pixel multiply needs no pass of its own, so it is this key of the
//!    final pass instead.)
//! 4. Operator (`[post] curve`), then clamped to [0, 1]:
//!    - `aces` (the default): the ACES filmic curve as fitted by K. Narkowicz ("ACES Filmic
//!      Tone Mapping Curve", 2016): f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14). A
//!      luminance-only fit to ACES ODT(RRT(x)) for Rec. 709 (max fit error 0.0138 by its
//!      author), applied per channel, so it over-saturates bright colours. f(0) = 0, f is
//!      increasing on x ≥ 0, f(1) ≈ 0.80, and f reaches 1 at x ≈ 7.24. The fit is
//!      pre-exposed; the original ACES curve is f(0.6 x), i.e. `exposure` × 0.6.
//!    - `hable`: J. Hable's filmic curve of Uncharted 2 ("Filmic Tonemapping Operators",
//!      filmicworlds.com, 2010; GDC 2010 "Uncharted 2: HDR Lighting"), with his published
//!      constants A = 0.15 (shoulder strength), B = 0.50 (linear strength), C = 0.10 (linear
//!      angle), D = 0.20 (toe strength), E = 0.02 (toe numerator), F = 0.30 (toe
//!      denominator) and white point W = 11.2: g(x) = (x(Ax + CB) + DE)/(x(Ax + B) + DF) −
//!      E/F, f(x) = g(x)/g(W). Welch (seed 002) tonemaps with Naughty Dog's filmic curve;
//!      this is its published form. The shader evaluates g rearranged over one denominator,
//!      g(x) = x(A(F − E)x + B(CF − E)) / (F(x(Ax + B) + DF)) — the same function, exactly,
//!      but without the cancellation of two E/F terms that leaves g(0) ≠ 0 in f32 — with
//!      the coefficients [`HABLE_P`] … [`HABLE_T`] and the factor [`HABLE_WHITE_SCALE`] =
//!      1/g(W), all computed here in f64 and rounded once to f32. Hable's post also
//!      multiplies by an "exposure bias" of 2 before the curve; here the scene's `exposure`
//!      is that factor. f(0) = 0, f(W) = 1, f is increasing (with g = (Px² + Qx)/(Rx² + Sx +
//!      T), the derivative's numerator (PS − QR)x² + 2PTx + QT has positive coefficients),
//!      f(∞) = (P/R)/g(W) ≈ 1.29, so the clamp makes everything above W white.
//! 5. sRGB OETF, IEC 61966-2-1: 12.92 c for c ≤ 0.0031308, else 1.055 c^{1/2.4} − 0.055.
//! 6. 8-bit quantisation in the shader: `q = round(v · 255) / 255`, WGSL's `round` (ties to
//!    even, exact; Rust's `round_ties_even`), and q is written to an `Rgba8Unorm` target.
//!    Vulkan converts to UNORM by rounding to nearest but leaves ties to the implementation;
//!    q · 255 is already within 2·10⁻⁵ of an integer, so every allowed conversion stores
//!    `round(v · 255)` and the GPU's bytes are the CPU's. (`floor(v · 255 + 0.5)` would not be
//!    exact: for v · 255 one ULP below ½ the f32 sum rounds up to 1.) The OETF is applied in the
//!    shader rather than by an `Rgba8UnormSrgb` target so that both back ends run the same
//!    arithmetic.
//!
//! Alpha is written as 1 (255).

use serde::{Deserialize, Serialize};

use crate::{Error, Result};

/// Upper bound of the exposed HDR value before the operator: the largest finite f16, what an
/// `Rgba16Float` frame can hold. Any value above ≈ 7.24 maps to white anyway.
pub const HDR_MAX: f32 = 65504.0;

/// Default exposure (scene units × exposure go into the operator).
pub const DEFAULT_EXPOSURE: f64 = 1.0;

/// Hable's published constants (Uncharted 2, 2010): shoulder strength A.
pub const HABLE_A: f64 = 0.15;
/// Linear strength B.
pub const HABLE_B: f64 = 0.50;
/// Linear angle C.
pub const HABLE_C: f64 = 0.10;
/// Toe strength D.
pub const HABLE_D: f64 = 0.20;
/// Toe numerator E.
pub const HABLE_E: f64 = 0.02;
/// Toe denominator F.
pub const HABLE_F: f64 = 0.30;
/// Linear white point W: the input that maps to 1.
pub const HABLE_W: f64 = 11.2;

/// g(x) of Hable's curve in its published form, f64 (before the normalisation by g(W)).
pub fn hable_published(x: f64) -> f64 {
    let (a, b, c, d, e, f) = (HABLE_A, HABLE_B, HABLE_C, HABLE_D, HABLE_E, HABLE_F);
    (x * (a * x + c * b) + d * e) / (x * (a * x + b) + d * f) - e / f
}

/// A(F − E): the x² coefficient of the rearranged numerator, as the shader's f32.
pub const HABLE_P: f32 = (HABLE_A * (HABLE_F - HABLE_E)) as f32;
/// B(CF − E): its x coefficient.
pub const HABLE_Q: f32 = (HABLE_B * (HABLE_C * HABLE_F - HABLE_E)) as f32;
/// F·A: the x² coefficient of the rearranged denominator.
pub const HABLE_R: f32 = (HABLE_F * HABLE_A) as f32;
/// F·B: its x coefficient.
pub const HABLE_S: f32 = (HABLE_F * HABLE_B) as f32;
/// F·D·F: its constant.
pub const HABLE_T: f32 = (HABLE_F * HABLE_D * HABLE_F) as f32;
/// 1/g(W), f64 rounded to f32: the normalisation that puts the white point at 1.
pub const HABLE_WHITE_SCALE: f32 = {
    let (a, b, c, d, e, f, w) = (HABLE_A, HABLE_B, HABLE_C, HABLE_D, HABLE_E, HABLE_F, HABLE_W);
    let g = (w * (a * w + c * b) + d * e) / (w * (a * w + b) + d * f) - e / f;
    (1.0 / g) as f32
};

/// The tonemap's curve (`[post] curve`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Curve {
    /// Narkowicz's ACES fit (the default).
    #[default]
    Aces,
    /// Hable's Uncharted 2 filmic curve.
    Hable,
}

impl Curve {
    /// The value of `TonemapUniforms::curve` that selects it in the shader.
    pub fn index(self) -> u32 {
        match self {
            Curve::Aces => 0,
            Curve::Hable => 1,
        }
    }

    /// The scene value (`aces`, `hable`).
    pub fn name(self) -> &'static str {
        match self {
            Curve::Aces => "aces",
            Curve::Hable => "hable",
        }
    }
}

/// The uniforms of the `tonemap` stage (`TonemapUniforms` in `shaders/tonemap.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TonemapUniforms {
    /// Multiplies the HDR radiance before the operator.
    pub exposure: f32,
    /// The operator: [`Curve::index`] (0 ACES, 1 Hable).
    pub curve: u32,
    /// The vignette's strength s ∈ [0, 1] (0: none).
    pub vignette: f32,
    /// 1/(c_x² + c_y²), c the image's centre in pixels: the vignette's r² per squared pixel.
    pub inv_corner2: f32,
    /// (width/2, height/2): the image's centre, pixels.
    pub center: [f32; 2],
    /// Post `bloom`: the bloom chain's level 0 is added × this (strength / levels;
    /// `crate::bloom`), 0 without the pass.
    pub bloom_scale: f32,
    /// Padding (unused, 0).
    pub pad1: f32,
}

impl TonemapUniforms {
    /// Uniforms for `exposure`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] unless `exposure` is > 0 and finite in f32.
    pub fn new(exposure: f64) -> Result<Self> {
        if !((exposure as f32).is_finite() && (exposure as f32) > 0.0) {
            return Err(Error::InvalidParameter {
                name: "exposure",
                value: exposure,
                reason: "the exposure must be a finite number > 0".into(),
            });
        }
        Ok(Self { exposure: exposure as f32, ..Self::DEFAULT })
    }

    /// Uniforms for `exposure`, the scene's `[post]` curve and vignette, and a
    /// `width` × `height` image (the vignette's centre and corner).
    ///
    /// # Errors
    /// As [`Self::new`]; [`Error::InvalidParameter`] for a vignette outside [0, 1].
    pub fn for_image(exposure: f64, post: &Post, width: u32, height: u32) -> Result<Self> {
        if !(0.0..=1.0).contains(&post.vignette) {
            return Err(Error::InvalidParameter {
                name: "vignette",
                value: post.vignette,
                reason: "the vignette's strength must be within [0, 1]".into(),
            });
        }
        let (cx, cy) = (f64::from(width) / 2.0, f64::from(height) / 2.0);
        Ok(Self {
            curve: post.curve.index(),
            vignette: post.vignette as f32,
            inv_corner2: (1.0 / (cx * cx + cy * cy)) as f32,
            center: [cx as f32, cy as f32],
            ..Self::new(exposure)?
        })
    }
}

impl TonemapUniforms {
    /// Uniforms with [`DEFAULT_EXPOSURE`].
    pub const DEFAULT: Self = Self {
        exposure: DEFAULT_EXPOSURE as f32,
        curve: 0,
        vignette: 0.0,
        inv_corner2: 0.0,
        center: [0.0; 2],
        bloom_scale: 0.0,
        pad1: 0.0,
    };
}

/// The `[post]` table: what the final pass does to the HDR frame besides the exposure
/// (`ocean_core::tonemap` says how, in order).
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct Post {
    /// The tonemap's curve: `aces` (Narkowicz's fit, the default) or `hable` (Uncharted 2).
    pub curve: crate::tonemap::Curve,
    /// The vignette's strength s ∈ [0, 1]: each pixel × (1 − s·r²), r = 0 at the centre and
    /// 1 at the corner. 0 (the default): no vignette.
    pub vignette: f64,
    /// Post `bloom`: the bright pass keeps what exceeds this, in exposed units (1 ≈ white).
    pub bloom_threshold: f64,
    /// Post `bloom`: the blurred bright pass is added to the frame × this (0: the pass is
    /// left out).
    pub bloom_strength: f64,
    /// Post `bloom`: levels of the blur pyramid (each twice as wide as the one before), at
    /// most as many as the frame's half size has.
    pub bloom_levels: u32,
    /// The format of the frame's colour buffers (`rgba32float` or `rgba16float`,
    /// `crate::frame_format`); left out, the system's (`welch`: `rgba16float`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub frame_format: Option<crate::frame_format::FrameFormat>,
}

impl Default for Post {
    fn default() -> Self {
        Self {
            curve: crate::tonemap::Curve::Aces,
            vignette: 0.0,
            bloom_threshold: 1.0,
            bloom_strength: 0.1,
            bloom_levels: 5,
            frame_format: None,
        }
    }
}
