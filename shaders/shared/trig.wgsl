// (cos 2πp, sin 2πp) by + − × only, so that every device that does not fuse rounds it alike
// and the CPU mirror gives the same bits as lavapipe: shared by `waves` (the FFT's twiddles and
// phases) and `water` (the Gerstner waves' phases). CPU mirror:
// ocean-cpu/src/shaders/shared/trig.rs.

// f32(2π).
const TAU: f32 = 6.2831855;

// Taylor coefficients of sin and cos on [−π/4, π/4] (truncation below 2e-9 there), so that
// (cos 2πp, sin 2πp) is + − × only: every device that does not fuse rounds it alike, and the
// CPU mirror gives the same bits as lavapipe (the drivers' cos and sin differ by ulps).
const SIN_C3: f32 = -0.16666667;
const SIN_C5: f32 = 0.008333334;
const SIN_C7: f32 = -0.0001984127;
const SIN_C9: f32 = 0.0000027557319;
const COS_C2: f32 = -0.5;
const COS_C4: f32 = 0.041666668;
const COS_C6: f32 = -0.0013888889;
const COS_C8: f32 = 0.0000248015873;
const COS_C10: f32 = -2.755732e-7;

// (cos 2πp, sin 2πp) for p in turns, |p| ≤ ½: the quarter turn q nearest p, the rest
// r = p − q/4 ∈ [−⅛, ⅛] as x = 2πr, then sin x and cos x rotated by q quarter turns.
fn cis_turns(p: f32) -> vec2<f32> {
    let q = floor(p * 4.0 + 0.5);
    let x = (p - q * 0.25) * TAU;
    let x2 = x * x;
    let s = x + x * x2 * (SIN_C3 + x2 * (SIN_C5 + x2 * (SIN_C7 + x2 * SIN_C9)));
    let c = 1.0 + x2 * (COS_C2 + x2 * (COS_C4 + x2 * (COS_C6 + x2 * (COS_C8 + x2 * COS_C10))));
    let k = (i32(q) + 4) & 3;
    if (k == 0) {
        return vec2<f32>(c, s);
    }
    if (k == 1) {
        return vec2<f32>(-s, c);
    }
    if (k == 2) {
        return vec2<f32>(-c, -s);
    }
    return vec2<f32>(s, -c);
}
