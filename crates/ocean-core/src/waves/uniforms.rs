//! What the `waves` stage (`shaders/waves.wgsl`) receives from the CPU, defined once here for
//! the GPU path (`ocean-gpu`) and its CPU mirror (`ocean-cpu::shaders::waves`): the uniforms,
//! the per-mode table, the FFT twiddles, and the phase representation that keeps h̃(k, t)
//! accurate at any time without f64 on the GPU.
//!
//! # Phase at large t (the GPU has no f64)
//!
//! h̃ needs e^{iωt}, i.e. the phase ωt modulo 2π. At t = 10⁶ s and ω = 10 rad/s, ωt = 10⁷ rad;
//! an f32 holds that to ±0.5 rad, and even a double-f32 product needs error-free
//! multiplications that a GPU compiler may break by fusing them into FMAs. So the phase is
//! formed in **turns** (cycles) with **integer** arithmetic, which every GPU evaluates
//! exactly:
//!
//! - time is counted in ticks of Δ = [`TIME_TICK_S`] = 2⁻⁸ s: t = ticks·Δ + r, `ticks` a signed
//!   64-bit integer (sent as two u32, two's complement) and |r| ≤ Δ/2 an f32
//!   ([`WavesUniforms::new`], in f64 on the CPU; when looping t is first reduced modulo the
//!   loop period T, in f64, as `Dispersion::reduced_time` does);
//! - each mode holds its rate q = frac(f·Δ) turns per tick, f = ω/2π, as a 64-bit binary
//!   fraction Q = q·2⁶⁴ ([`WaveModeData::phase_rate`], from the f64 ω: exact when q ≥ 2⁻¹²,
//!   i.e. f ≥ 1/16 Hz, since q has 53 significant bits; rounded to 2⁻⁶⁴ below that);
//! - the phase in turns is frac(f·t) = frac(q·ticks) + f·r: since `ticks` is an integer the
//!   whole turns of f·Δ drop out, and frac(q·ticks)·2³² is the high word of Q·ticks mod 2⁶⁴,
//!   three 32-bit products (one of them a 32×32→64 high word, built from 16-bit halves).
//!   Wrapping u32 arithmetic *is* the modulo, also for negative ticks;
//! - that 32-bit turn count is rounded to 24 bits, read as a signed turn in [−½, ½), the
//!   small f32 term f·r (|f·r| ≤ f·2⁻⁹ turns) added, the sum brought back to [−½, ½] with
//!   c − floor(c + ½) (exact) and multiplied by 2π in f32 for `cos` / `sin`.
//!
//! Error budget, in turns: the 24-bit rounding 2⁻²⁵; f·r and the additions a few f32 ulps of
//! ≤ ½ turn (for f < 100 Hz: gravity waves of the grids ocean-core accepts have f < 10 Hz
//! unless L is centimetres); 2π·c 6e-8 relative; the rounding of Q (slow modes only)
//! 2⁻⁶⁵·|ticks|, 2⁻³⁷ at t = 10⁶ s and 2⁻²⁷ at 10⁹ s. In all ≲ 1e-6 rad for |t| ≤ 10⁹ s,
//! against the 1e-4 rad asked at t = 10⁶ s (measured ≤ 7e-7 rad on the mirror and on lavapipe,
//! `tests/gpu_waves.rs`, including the f32 rounding of h0·e^{iθ} it reads). The f64 values
//! the CPU holds (ω, t) are the reference, as in ocean-core's `Dispersion::phase`.
//!
//! Looping: t and t + T reduce to the same τ in f64 whenever t + T is exact, and everything
//! after is then bit-identical, so h(t + T) = h(t) bit for bit; otherwise to the f64 rounding
//! of t + T, as on the CPU. Without looping |t| must stay below 2⁵⁵ s (1.1 billion years), or
//! the tick count overflows 64 bits and [`WavesUniforms::new`] returns an error.
//!
//! # FFT conventions
//!
//! The same as ocean-core's synthesis (crate root): unnormalised inverse DFT
//! x_j = Σ_k X_k e^{+2πi jk/N}, bins in order n mod N. Stockham radix-2 autosort, decimation
//! in frequency: stage s = 0 … log₂N − 1, stride S = 2^s, butterfly j ∈ [0, N/2):
//!
//! ```text
//! a = x[j], b = x[j + N/2], q = j mod S, w = W[j − q]   (W[m] = e^{+2πi m/N}, m < N/2)
//! y[2j − q] = a + b,  y[2j − q + S] = (a − b)·w
//! ```
//!
//! after log₂N stages the result is in natural order. Rows (along x) first, then columns.
//! The twiddles W are computed in f64 and rounded to f32 once ([`fft_twiddles`]); the GPU and
//! the mirror read the same table. Power-of-two N only ([`check_fft_size`]).

use std::f64::consts::TAU;

use bytemuck::{Pod, Zeroable};

use super::modes::{WaveModes, check_choppiness, check_time};
use crate::dispersion::Dispersion;
use crate::{Error, Result};

/// Δ, the time tick of the phase (see the module doc): 2⁻⁸ s.
pub const TIME_TICK_S: f64 = 1.0 / 256.0;

/// The largest |t| (seconds, after the loop reduction) the tick count holds: 2⁵⁵ s.
pub const MAX_TIME_S: f64 = (1u64 << 55) as f64;

/// Uniforms of the `waves` stage (WGSL `WavesUniforms`), written once per frame.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct WavesUniforms {
    /// N, a power of two.
    pub size: u32,
    /// log₂ N: the number of FFT stages per axis.
    pub log2_size: u32,
    /// t (reduced modulo the loop period when looping) in ticks of [`TIME_TICK_S`], rounded
    /// to nearest: a signed 64-bit integer as (low, high) u32 words, two's complement.
    pub time_ticks: [u32; 2],
    /// t − ticks·Δ, seconds, |r| ≤ Δ/2.
    pub time_remainder: f32,
    /// λ = −choppiness (ocean-core's sign convention: positive choppiness sharpens crests).
    pub lambda: f32,
    /// Padding to 32 bytes.
    pub pad0: u32,
    /// Padding.
    pub pad1: u32,
}

impl WavesUniforms {
    /// The uniforms for N = `resolution`, time `t` (seconds) and `choppiness`, with the time
    /// reduced and split in f64 as the module doc says.
    ///
    /// # Errors
    /// N not a power of two ≥ 2; t or choppiness not finite; |t| ≥ [`MAX_TIME_S`] without a
    /// loop period.
    pub fn new(
        resolution: usize,
        dispersion: &Dispersion,
        t: f64,
        choppiness: f64,
    ) -> Result<Self> {
        check_fft_size(resolution)?;
        check_time(t)?;
        check_choppiness(choppiness)?;
        let tau = dispersion.reduced_time(t);
        if tau.abs() >= MAX_TIME_S {
            return Err(Error::InvalidParameter {
                name: "time_s",
                value: t,
                reason: format!(
                    "the GPU wave phase holds |t| < 2^55 s ({MAX_TIME_S:e} s) without a loop \
                     period; set loop_period_s or use a smaller time"
                ),
            });
        }
        let (ticks, remainder) = split_time(tau);
        let ticks = ticks as u64; // two's complement
        Ok(Self {
            size: resolution as u32,
            log2_size: resolution.trailing_zeros(),
            time_ticks: [ticks as u32, (ticks >> 32) as u32],
            time_remainder: remainder as f32,
            lambda: (-choppiness) as f32,
            pad0: 0,
            pad1: 0,
        })
    }
}

/// τ = ticks·Δ + r with ticks = round(τ/Δ): both parts exact in f64 (τ/Δ is a power-of-two
/// scaling, ticks·Δ is exact below 2⁵³ ticks, and τ − ticks·Δ is an exact difference of
/// nearby values). |τ| < [`MAX_TIME_S`].
pub fn split_time(tau: f64) -> (i64, f64) {
    let ticks = (tau / TIME_TICK_S).round();
    let remainder = tau - ticks * TIME_TICK_S;
    (ticks as i64, remainder)
}

/// Per-pass uniforms of the FFT entry points (WGSL `FftPassUniforms`): one buffer per
/// stage, written once.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Pod, Zeroable)]
pub struct FftPassUniforms {
    /// The Stockham stage s (stride 2^s), 0 … log₂N − 1.
    pub stage: u32,
    /// Padding to 16 bytes.
    pub pad0: u32,
    /// Padding.
    pub pad1: u32,
    /// Padding.
    pub pad2: u32,
}

/// One mode of the `waves` stage's storage table (WGSL `WaveMode`), indexed by bin as
/// ocean-core stores modes: `(m mod N)·N + (n mod N)`.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct WaveModeData {
    /// h0(k), metres (f64 rounded to f32).
    pub h0: [f32; 2],
    /// (kx, kz), rad/m.
    pub k: [f32; 2],
    /// Q = frac(f·Δ)·2⁶⁴ as (low, high) u32 words: the phase advance per tick in 2⁻⁶⁴ turns.
    pub phase_rate: [u32; 2],
    /// 1/|k|, 0 at k = 0 (where every multiplier is 0 anyway).
    pub inv_k: f32,
    /// f = ω/2π, turns per second (for the sub-tick remainder).
    pub frequency: f32,
}

/// Q = frac(f·Δ)·2⁶⁴ for ω ≥ 0 (rad/s), rounded to nearest (see the module doc).
pub fn phase_rate(omega: f64) -> u64 {
    let q = (omega / TAU * TIME_TICK_S).fract();
    // q < 1 − 2⁻⁵³, so q·2⁶⁴ ≤ 2⁶⁴ − 2¹¹ fits; `as` saturates anyway.
    (q * 18_446_744_073_709_551_616.0).round() as u64
}

/// The table of every bin of `modes` (h0 and ω from ocean-core, rounded to f32 once).
pub fn wave_mode_table(modes: &WaveModes) -> Vec<WaveModeData> {
    let n = modes.resolution();
    let axis_k = modes.axis_wavenumbers();
    let k = modes.wavenumbers();
    let omega = modes.omegas();
    modes
        .h0()
        .iter()
        .enumerate()
        .map(|(bin, h0)| {
            let rate = phase_rate(omega[bin]);
            WaveModeData {
                h0: [h0.re as f32, h0.im as f32],
                k: [axis_k[bin % n] as f32, axis_k[bin / n] as f32],
                phase_rate: [rate as u32, (rate >> 32) as u32],
                // 1/|k| only where |k| > 0, as ocean-core's synthesis does.
                inv_k: if k[bin] > 0.0 { (1.0 / k[bin]) as f32 } else { 0.0 },
                frequency: (omega[bin] / TAU) as f32,
            }
        })
        .collect()
}

/// W\[m\] = e^{+2πi m/N} for m < N/2 (the inverse transform's twiddles), in f64 rounded to f32.
pub fn fft_twiddles(resolution: usize) -> Vec<[f32; 2]> {
    let n = resolution as f64;
    (0..resolution / 2)
        .map(|m| {
            let angle = TAU * m as f64 / n;
            [angle.cos() as f32, angle.sin() as f32]
        })
        .collect()
}

/// The FFT of the `waves` stage takes power-of-two N ≥ 2 only (radix-2 Stockham).
///
/// # Errors
/// [`Error::InvalidParameter`] naming `resolution` otherwise.
pub fn check_fft_size(resolution: usize) -> Result<()> {
    if resolution >= 2 && resolution.is_power_of_two() {
        Ok(())
    } else {
        Err(Error::InvalidParameter {
            name: "resolution",
            value: resolution as f64,
            reason: "the GPU wave synthesis (radix-2 FFT) needs a power of two ≥ 2; use the CPU \
                     backend for other sizes"
                .into(),
        })
    }
}

/// The largest N of the shared-memory FFT (`FFT_SHARED_MAX` in `waves.wgsl`: entry points
/// `spectrum_rows_shared`, `columns_pack_shared`): two lines of N complex f32 in workgroup
/// memory, 16 KiB, the workgroup storage every WebGPU device offers.
pub const FFT_SHARED_MAX: u32 = 1024;
/// Threads per workgroup of the shared-memory FFT (`FFT_SHARED_THREADS`), WebGPU's default
/// limit of invocations per workgroup.
pub const FFT_SHARED_THREADS: u32 = 256;
/// The elements of a line one thread of the shared-memory FFT keeps in registers between the
/// columns' FFT and the packing (`FFT_KEPT_PER_ARRAY`): N / [`FFT_SHARED_THREADS`] at most.
pub const FFT_KEPT_PER_ARRAY: u32 = FFT_SHARED_MAX / FFT_SHARED_THREADS;
/// The complex arrays of a frame's wave synthesis (`WAVE_ARRAYS` in `waves.wgsl`): eight real
/// fields, two per array.
pub const WAVE_ARRAYS: u32 = 4;

/// How many lines of N elements the shared-memory FFT holds in each half of its workgroup
/// memory at once (`shared_lines()` in `waves.wgsl`): all [`WAVE_ARRAYS`] for N ≤ 256, then
/// half as many for each doubling, 1 at [`FFT_SHARED_MAX`].
pub fn fft_shared_lines(resolution: u32) -> u32 {
    WAVE_ARRAYS.min(FFT_SHARED_MAX / resolution.max(1))
}

/// The Stockham pass parameters of every FFT pass of one frame, rows then columns.
pub fn fft_passes(resolution: usize) -> Vec<FftPassUniforms> {
    let stages = resolution.trailing_zeros();
    (0..2 * stages)
        .map(|p| FftPassUniforms { stage: p % stages, pad0: 0, pad1: 0, pad2: 0 })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_split_is_exact_and_rounded() {
        for tau in [0.0, 1e-9, 0.3, -0.3, 1e6, 1e6 + 1.0 / 512.0, -7.5e9, 1e15] {
            let (ticks, r) = split_time(tau);
            assert_eq!(ticks as f64 * TIME_TICK_S + r, tau);
            assert!(r.abs() <= TIME_TICK_S / 2.0, "{tau}: {r}");
        }
    }

    #[test]
    fn uniforms_wrap_negative_ticks_and_reject_bad_input() {
        let d = Dispersion::deep(9.81);
        let u = WavesUniforms::new(64, &d, -1.0, 1.5).unwrap();
        let ticks = u64::from(u.time_ticks[0]) | (u64::from(u.time_ticks[1]) << 32);
        assert_eq!(ticks as i64, -256);
        assert_eq!((u.size, u.log2_size, u.lambda), (64, 6, -1.5));
        assert!(WavesUniforms::new(48, &d, 0.0, 0.0).is_err());
        assert!(WavesUniforms::new(64, &d, f64::NAN, 0.0).is_err());
        assert!(WavesUniforms::new(64, &d, MAX_TIME_S, 0.0).is_err());
        let looping = Dispersion::new(9.81, f64::INFINITY, 20.0).unwrap();
        assert!(WavesUniforms::new(64, &looping, 1e300, 0.0).is_ok());
    }

    #[test]
    fn phase_rate_is_the_fraction_per_tick() {
        // f = 1 Hz: 1/256 turn per tick, 2⁵⁶ in 2⁻⁶⁴ turns.
        assert_eq!(phase_rate(TAU), 1 << 56);
        // f = 256 Hz: whole turns per tick drop out.
        assert_eq!(phase_rate(256.0 * TAU), 0);
        assert_eq!(phase_rate(0.0), 0);
    }

    #[test]
    fn twiddles_and_passes() {
        let w = fft_twiddles(8);
        assert_eq!(w.len(), 4);
        assert_eq!(w[0], [1.0, 0.0]);
        assert!((w[2][0]).abs() < 1e-7 && w[2][1] == 1.0);
        let stages: Vec<u32> = fft_passes(8).iter().map(|p| p.stage).collect();
        assert_eq!(stages, [0, 1, 2, 0, 1, 2]);
    }
}
