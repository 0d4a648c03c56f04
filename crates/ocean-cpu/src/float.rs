//! Exact f32 helpers of WGSL's builtins that both the scalar mirrors (`shaders::wgsl`) and the
//! envelope's number types (`envelope`) use: a leaf, so neither imports the other for them.

/// WGSL `frexp(x)` for a normal, finite x: (fract ∈ [0.5, 1), exp) with x = fract·2^exp
/// (exact: the exponent field rewritten).
pub fn frexp(x: f32) -> (f32, i32) {
    let bits = x.to_bits();
    let e = ((bits >> 23) & 0xff) as i32;
    (f32::from_bits((bits & 0x807f_ffff) | (126 << 23)), e - 126)
}

/// WGSL `ldexp(x, e)` for exponents with a normal 2^e (|e| < 127): x·2^e, exact.
pub fn ldexp(x: f32, e: i32) -> f32 {
    debug_assert!((-126..=127).contains(&e), "2^{e} is not a normal f32");
    x * f32::from_bits(((127 + e) as u32) << 23)
}
