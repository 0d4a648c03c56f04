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
//! 3. Operator: the ACES filmic curve as fitted by K. Narkowicz ("ACES Filmic Tone Mapping
//!    Curve", 2016): f(x) = x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14), then clamped to
//!    [0, 1]. A luminance-only fit to ACES ODT(RRT(x)) for Rec. 709 (max fit error 0.0138 by
//!    its author), applied per channel, so it over-saturates bright colours. f(0) = 0, f is
//!    increasing on x ≥ 0, f(1) ≈ 0.80, and f reaches 1 at x ≈ 7.24. The fit is pre-exposed;
//!    the original ACES curve is f(0.6 x), i.e. `exposure` × 0.6. Welch (seed 002) uses the
//!    filmic curve of Naughty Dog's Uncharted games instead; another operator would be a new
//!    named function beside this one.
//! 4. sRGB OETF, IEC 61966-2-1: 12.92 c for c ≤ 0.0031308, else 1.055 c^{1/2.4} − 0.055.
//! 5. 8-bit quantisation in the shader: `q = round(v · 255) / 255`, WGSL's `round` (ties to
//!    even, exact; Rust's `round_ties_even`), and q is written to an `Rgba8Unorm` target.
//!    Vulkan converts to UNORM by rounding to nearest but leaves ties to the implementation;
//!    q · 255 is already within 2·10⁻⁵ of an integer, so every allowed conversion stores
//!    `round(v · 255)` and the GPU's bytes are the CPU's. (`floor(v · 255 + 0.5)` would not be
//!    exact: for v · 255 one ULP below ½ the f32 sum rounds up to 1.) The OETF is applied in the
//!    shader rather than by an `Rgba8UnormSrgb` target so that both back ends run the same
//!    arithmetic.
//!
//! Alpha is written as 1 (255).

use crate::{Error, Result};

/// Upper bound of the exposed HDR value before the operator: the largest finite f16, what an
/// `Rgba16Float` frame can hold. Any value above ≈ 7.24 maps to white anyway.
pub const HDR_MAX: f32 = 65504.0;

/// Default exposure (scene units × exposure go into the operator).
pub const DEFAULT_EXPOSURE: f64 = 1.0;

/// The uniforms of the `tonemap` stage (`TonemapUniforms` in `shaders/tonemap.wgsl`).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TonemapUniforms {
    /// Multiplies the HDR radiance before the operator.
    pub exposure: f32,
    /// Padding to 16 bytes (unused, 0).
    pub pad0: f32,
    /// Padding (unused, 0).
    pub pad1: f32,
    /// Padding (unused, 0).
    pub pad2: f32,
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
        Ok(Self { exposure: exposure as f32, pad0: 0.0, pad1: 0.0, pad2: 0.0 })
    }
}

impl TonemapUniforms {
    /// Uniforms with [`DEFAULT_EXPOSURE`].
    pub const DEFAULT: Self =
        Self { exposure: DEFAULT_EXPOSURE as f32, pad0: 0.0, pad1: 0.0, pad2: 0.0 };
}
