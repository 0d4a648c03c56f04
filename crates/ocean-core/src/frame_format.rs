//! The frame's colour buffers: `rgba32float` or, as seed 002 has them ("works with 16-bit
//! precision floats in all the frame buffers"), `rgba16float`.
//!
//! The format is `[post] frame_format`, or the system's when the scene leaves it out (`welch`:
//! `rgba16float`; the others `rgba32float`). It is the format of every colour buffer a pass
//! renders or blurs into: the HDR frame, the reflection and refraction maps, and post
//! `bloom`'s two chains. The wave maps, the Fresnel tables, the shadow map and the foam field
//! stay `Rgba32Float`: they hold positions, slopes and depths, which f16's 11 bits would
//! quantise visibly (a height of 3 m to 2 mm steps, a distance of 500 m to 0.25 m).
//!
//! ## What a store does
//!
//! Each value written to an `rgba16float` buffer (a fragment's colour after blending, a
//! clear colour, a compute write) is rounded **toward zero** to a binary16 value: the f32's
//! low 13 mantissa bits dropped (below 2⁻¹⁴, truncated to a multiple of 2⁻²⁴). So a finite
//! value never becomes an infinity: magnitudes from 65504 up store as 65504 with their sign,
//! and a bilinear tap with weight 0 on a blown-out texel (the sun) still gives 0, not
//! inf · 0 = NaN. NaN and ±inf stay what they are. Reading gives the stored value back
//! exactly as f32.
//!
//! Vulkan leaves both the rounding and the overflow of a conversion to f16 to the
//! implementation ("rounded to one or the other"; "either to the closest representable
//! finite value or to the appropriately signed infinity"). Toward zero is what lavapipe does,
//! measured for fragment outputs and storage writes alike (`tests/gpu_precision.rs`: of
//! 16384 values spread over the binary16 range, round-to-nearest-even disagreed with it on
//! 8198, truncation on none), and the oracle mirrors the driver it checks (docs/design.md,
//! "where lavapipe approximates, mirror the approximation"). A GPU that rounds to nearest
//! (Vulkan allows it; no hardware GPU was measured here) stores at most one step from this.
//!
//! ## What the cross-check allows
//!
//! Two f32 values a few ulp apart (a `sin` on each back end) can lie on either side of a
//! binary16 value and store one step apart, and a GPU that rounds to nearest stores up to one
//! step from the oracle: [`half_step`] is that step, and the cross-check allows one of them on
//! a buffer of this format besides its f32 tolerance.

use serde::{Deserialize, Serialize};

/// The largest finite binary16 value.
pub const HALF_MAX: f32 = 65504.0;

/// The smallest positive normal binary16 value, 2⁻¹⁴.
pub const HALF_MIN_NORMAL: f32 = 6.103_515_6e-5;

/// The texel format of the frame's colour buffers (`[post] frame_format`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize, Serialize)]
pub enum FrameFormat {
    /// Four f32 channels (the default of every system but `welch`).
    #[default]
    #[serde(rename = "rgba32float")]
    Rgba32Float,
    /// Four binary16 channels (seed 002's frame buffers; system `welch`).
    #[serde(rename = "rgba16float")]
    Rgba16Float,
}

impl FrameFormat {
    /// Every format, for documentation and sweeps.
    pub const ALL: [FrameFormat; 2] = [FrameFormat::Rgba32Float, FrameFormat::Rgba16Float];

    /// The scene value (`rgba32float`, `rgba16float`), also the wgpu and WGSL name.
    pub fn name(self) -> &'static str {
        match self {
            FrameFormat::Rgba32Float => "rgba32float",
            FrameFormat::Rgba16Float => "rgba16float",
        }
    }

    /// Bytes per texel.
    pub fn texel_bytes(self) -> u64 {
        match self {
            FrameFormat::Rgba32Float => 16,
            FrameFormat::Rgba16Float => 8,
        }
    }

    /// The value a buffer of this format holds after `x` is written to it (module docs).
    #[inline]
    pub fn store(self, x: f32) -> f32 {
        match self {
            FrameFormat::Rgba32Float => x,
            FrameFormat::Rgba16Float => round_to_half(x),
        }
    }

    /// [`Self::store`] on the four channels of a texel.
    #[inline]
    pub fn store4(self, c: [f32; 4]) -> [f32; 4] {
        match self {
            FrameFormat::Rgba32Float => c,
            FrameFormat::Rgba16Float => c.map(round_to_half),
        }
    }

    /// The spacing of the format's values at the magnitude of `x` (f32: 0, nothing beyond
    /// the f32 tolerance; f16: [`half_step`]).
    pub fn step(self, x: f32) -> f32 {
        match self {
            FrameFormat::Rgba32Float => 0.0,
            FrameFormat::Rgba16Float => half_step(x),
        }
    }
}

impl std::fmt::Display for FrameFormat {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// `x` rounded toward zero to binary16, as f32 (module docs): finite magnitudes from
/// [`HALF_MAX`] up give [`HALF_MAX`]; NaN and ±inf pass.
#[inline]
pub fn round_to_half(x: f32) -> f32 {
    let a = x.abs();
    let r = if !a.is_finite() {
        return x;
    } else if a >= HALF_MAX {
        HALF_MAX
    } else if a < HALF_MIN_NORMAL {
        // Subnormal binary16: multiples of 2⁻²⁴. Scaling by a power of two is exact, so
        // this truncates the exact quotient.
        const SUB: f32 = 5.960_464_5e-8; // 2⁻²⁴
        (a / SUB).trunc() * SUB
    } else {
        // Normal binary16 keeps 10 of f32's 23 mantissa bits: drop the other 13.
        f32::from_bits(a.to_bits() & !0x1fff)
    };
    r.copysign(x)
}

/// The distance between consecutive binary16 values at the magnitude of `x`: 2⁻²⁴ below
/// [`HALF_MIN_NORMAL`] (the subnormals' spacing), 2^(e − 10) for 2^e ≤ |x| < 2^(e+1), and 32
/// from 32768 up (the spacing at [`HALF_MAX`]). NaN: 32.
pub fn half_step(x: f32) -> f32 {
    let a = x.abs();
    if a < HALF_MIN_NORMAL {
        return f32::powi(2.0, -24);
    }
    // The f32 exponent of a: floor(log2 a), exact from the bits (no log rounding).
    let e = (((a.to_bits() >> 23) & 0xff) as i32 - 127).min(15);
    f32::powi(2.0, e - 10)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_is_toward_zero_and_clamps_to_the_largest_finite() {
        let p = |e: i32| f32::powi(2.0, e);
        // Anything in [1, 1 + 2⁻¹⁰) stores as 1, on both sides of the midpoint.
        assert_eq!(round_to_half(1.0 + p(-11)), 1.0);
        assert_eq!(round_to_half(1.0 + p(-10) - p(-23)), 1.0);
        assert_eq!(round_to_half(1.0 + p(-10)), 1.0 + p(-10));
        assert_eq!(round_to_half(-(1.0 + p(-10) - p(-23))), -1.0);
        assert_eq!(round_to_half(1e6), HALF_MAX);
        assert_eq!(round_to_half(65535.0), HALF_MAX);
        assert_eq!(round_to_half(-1e30), -HALF_MAX);
        assert_eq!(round_to_half(f32::INFINITY), f32::INFINITY);
        assert!(round_to_half(f32::NAN).is_nan());
        // Subnormals: multiples of 2⁻²⁴, truncated.
        assert_eq!(round_to_half(p(-24)), p(-24));
        assert_eq!(round_to_half(1.9 * p(-24)), p(-24));
        assert_eq!(round_to_half(p(-25)), 0.0);
        assert_eq!(round_to_half(p(-14) - p(-30)), 1023.0 * p(-24));
        // Every result is a binary16 value (the `half` crate's exact conversion keeps it).
        for x in [0.1_f32, 1.0 / 3.0, 2.0 / 3.0, 12345.678, 3e-6, 6.1e-5] {
            let r = round_to_half(x);
            assert_eq!(half::f16::from_f32(r).to_f32(), r, "{x}");
            assert!(r <= x && x - r < half_step(x), "{x} → {r}");
        }
        // f32 stores are the identity.
        assert_eq!(FrameFormat::Rgba32Float.store(1.000_49), 1.000_49);
    }

    #[test]
    fn the_step_is_the_gap_to_the_next_half_value() {
        for x in [1e-7_f32, 3e-5, 6.2e-5, 0.1, 1.0, 1.5, 2.0, 700.0, 40000.0, 65504.0] {
            let h = half::f16::from_f32(x);
            let next = half::f16::from_bits(h.to_bits() + 1).to_f32();
            let gap = if h.to_f32() == HALF_MAX { 32.0 } else { next - h.to_f32() };
            // Where x is itself the last value below a power of two its rounding may land on
            // the power; the gap below x is the step then.
            let below = h.to_f32() - half::f16::from_bits(h.to_bits().max(1) - 1).to_f32();
            assert!(
                half_step(x) == gap || half_step(x) == below,
                "x = {x}: step {} against gaps {below} and {gap}",
                half_step(x)
            );
        }
        assert_eq!(half_step(1.0), f32::powi(2.0, -10));
        assert_eq!(half_step(-1.0), f32::powi(2.0, -10));
        assert_eq!(half_step(0.0), f32::powi(2.0, -24));
        assert_eq!(half_step(f32::INFINITY), 32.0);
        assert_eq!(FrameFormat::Rgba32Float.step(1.0), 0.0);
    }

    #[test]
    fn names_round_trip_through_the_scene_format() {
        #[derive(Deserialize)]
        struct T {
            f: FrameFormat,
        }
        for f in FrameFormat::ALL {
            let t: T = toml::from_str(&format!("f = \"{}\"", f.name())).expect("parses");
            assert_eq!(t.f, f);
        }
        assert!(toml::from_str::<T>("f = \"rgba8unorm\"").is_err());
    }
}
