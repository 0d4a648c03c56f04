//! CPU mirror of `shaders/waves.wgsl`: h̃(k, t) and the multiplied spectra, the radix-2
//! Stockham inverse FFT pass by pass, and the packing into the three wave textures, in f32
//! with the WGSL's operations in the WGSL's order (wrapping u32 arithmetic where the WGSL's
//! integers wrap), the same twiddle table and the same mode table (ocean-core's
//! `waves::uniforms`, which also documents the phase in integer turns and the FFT stages).
//!
//! Nothing is left to the implementation: the phase's cos and sin are `cis_turns`, a
//! polynomial of + − × only, so that on lavapipe the GPU and the mirror agree bit for bit.
//! ocean-core's `Synthesizer<f64>` is the reference both are held against.
//!
//! [`WavesMirror`] runs a whole frame; [`WavesMirror::run_traced`] hands out the ping-pong
//! buffer after each dispatch, for pass-by-pass comparison with the GPU.

use ocean_core::waves::WaveModes;
use ocean_core::waves::uniforms::{
    FftPassUniforms, WAVE_ARRAYS, WaveModeData, WavesUniforms, check_fft_size, fft_passes,
    fft_twiddles, wave_mode_table,
};

use crate::envelope::{Iv, Jitter, JitterRules, Real};

pub mod shared_memory;
use crate::sampler::Texture2D;
use crate::shaders::shared::trig::cis_reduced_r;

/// `vec2<f32>`: a complex number, x the real part.
pub type Vec2 = [f32; 2];

/// A complex number over any [`Real`], x the real part.
pub type Cx<R> = [R; 2];

/// `TURN_UNIT`: 2⁻²⁴.
pub const TURN_UNIT: f32 = 5.960_464_5e-8;

/// The four packed complex arrays of one frame, N² each (ocean-core's [`WAVE_ARRAYS`]).
pub const ARRAYS: u32 = WAVE_ARRAYS;

/// `mul_hi(a, b)`: the high 32 bits of a·b from 16-bit halves.
#[inline]
pub fn mul_hi(a: u32, b: u32) -> u32 {
    let a0 = a & 0xffff;
    let a1 = a >> 16;
    let b0 = b & 0xffff;
    let b1 = b >> 16;
    let p00 = a0 * b0;
    let p01 = a0 * b1;
    let p10 = a1 * b0;
    let p11 = a1 * b1;
    let mid = (p00 >> 16) + (p01 & 0xffff) + (p10 & 0xffff);
    p11 + (p01 >> 16) + (p10 >> 16) + (mid >> 16)
}

/// The 24-bit turn count of `phase_turns`, read as signed turns: integer arithmetic and an
/// exact scaling, so the same value on every implementation.
#[inline]
pub fn coarse_turns(rate: [u32; 2], params: &WavesUniforms) -> f32 {
    let ticks = params.time_ticks;
    let turns_fixed = mul_hi(rate[0], ticks[0])
        .wrapping_add(rate[1].wrapping_mul(ticks[0]))
        .wrapping_add(rate[0].wrapping_mul(ticks[1]));
    ((turns_fixed.wrapping_add(128) as i32) >> 8) as f32 * TURN_UNIT
}

/// `phase_turns(rate, frequency)`: frac(f·t) in turns, in [−½, ½].
#[inline]
pub fn phase_turns(rate: [u32; 2], frequency: f32, params: &WavesUniforms) -> f32 {
    let c = coarse_turns(rate, params) + frequency * params.time_remainder;
    c - (c + 0.5).floor()
}

/// `cis_turns(phase_turns(rate, frequency))` over any [`Real`].
#[inline]
pub fn phase_cis<R: Real>(rate: [u32; 2], frequency: f32, params: &WavesUniforms) -> Cx<R> {
    let l = R::lit;
    let c = l(coarse_turns(rate, params)) + l(frequency) * l(params.time_remainder);
    cis_reduced_r(c)
}

pub use super::shared::trig::{
    COS_C2, COS_C4, COS_C6, COS_C8, COS_C10, SIN_C3, SIN_C5, SIN_C7, SIN_C9, TAU, cis_turns,
};

/// `complex_mul(a, b)`.
#[inline]
pub fn complex_mul<R: Real>(a: Cx<R>, b: Cx<R>) -> Cx<R> {
    [a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0]]
}

/// `pack_pair(a, b)`: Â + iB̂.
#[inline]
pub fn pack_pair<R: Real>(a: Cx<R>, b: Cx<R>) -> Cx<R> {
    [a[0] - b[1], a[1] + b[0]]
}

#[inline]
fn scale<R: Real>(v: Cx<R>, s: R) -> Cx<R> {
    [v[0] * s, v[1] * s]
}

/// `spectrum_of(i, j)`: the four packed spectra of bin (i, j), in array order.
pub fn spectrum_of<R: Real>(
    i: u32,
    j: u32,
    params: &WavesUniforms,
    modes: &[WaveModeData],
) -> [Cx<R>; 4] {
    let n = params.size;
    let l = R::lit;
    let bin = j * n + i;
    let partner = ((n - j) & (n - 1)) * n + ((n - i) & (n - 1));
    let mode = modes[bin as usize];
    let (h0, h0_minus) = (mode.h0.map(l), modes[partner as usize].h0.map(l));
    let e: Cx<R> = phase_cis(mode.phase_rate, mode.frequency, params);
    let s = [h0[0] + h0_minus[0], h0[1] + h0_minus[1]];
    let d = [h0[0] - h0_minus[0], h0[1] - h0_minus[1]];
    let h = [s[0] * e[0] - s[1] * e[1], d[0] * e[1] + d[1] * e[0]];

    let kx = l(mode.k[0]);
    let kz = l(mode.k[1]);
    let inv_k = l(mode.inv_k);
    let lambda = l(params.lambda);
    let i_h = [-h[1], h[0]];
    let minus_i_h = [h[1], -h[0]];
    let disp_x = scale(minus_i_h, lambda * kx * inv_k);
    let disp_z = scale(minus_i_h, lambda * kz * inv_k);
    let slope_x = scale(i_h, kx);
    let slope_z = scale(i_h, kz);
    let disp_x_dx = scale(h, lambda * kx * kx * inv_k);
    let disp_z_dz = scale(h, lambda * kz * kz * inv_k);
    let disp_x_dz = scale(h, lambda * kx * kz * inv_k);
    [
        pack_pair(h, disp_x),
        pack_pair(disp_z, disp_x_dz),
        pack_pair(slope_x, slope_z),
        pack_pair(disp_x_dx, disp_z_dz),
    ]
}

/// `spectrum(id)`: the four packed spectra of bin (id.x, id.y), written into `dst`.
pub fn spectrum<R: Real>(
    id: [u32; 3],
    params: &WavesUniforms,
    modes: &[WaveModeData],
    dst: &mut [Cx<R>],
) {
    let n = params.size;
    if id[0] >= n || id[1] >= n {
        return;
    }
    let bin = (id[1] * n + id[0]) as usize;
    let plane = (n * n) as usize;
    for (f, value) in spectrum_of(id[0], id[1], params, modes).into_iter().enumerate() {
        dst[f * plane + bin] = value;
    }
}

/// `butterfly(base, stride, j)` of the stage in `fft_pass`.
#[expect(clippy::too_many_arguments, reason = "the WGSL's bindings become parameters")]
#[inline]
pub fn butterfly<R: Real>(
    base: u32,
    stride: u32,
    j: u32,
    params: &WavesUniforms,
    fft_pass: &FftPassUniforms,
    twiddles: &[Vec2],
    src: &[Cx<R>],
    dst: &mut [Cx<R>],
) {
    let half = params.size / 2;
    let s = 1u32 << fft_pass.stage;
    let q = j & (s - 1);
    let a = src[(base + j * stride) as usize];
    let b = src[(base + (j + half) * stride) as usize];
    let w = twiddles[(j - q) as usize].map(R::lit);
    let d = [a[0] - b[0], a[1] - b[1]];
    let out = 2 * j - q;
    dst[(base + out * stride) as usize] = [a[0] + b[0], a[1] + b[1]];
    dst[(base + (out + s) * stride) as usize] = complex_mul(d, w);
}

/// `fft_rows(id)`: id.x butterfly, id.y row, id.z array.
pub fn fft_rows<R: Real>(
    id: [u32; 3],
    params: &WavesUniforms,
    fft_pass: &FftPassUniforms,
    twiddles: &[Vec2],
    src: &[Cx<R>],
    dst: &mut [Cx<R>],
) {
    let n = params.size;
    if id[0] >= n / 2 || id[1] >= n || id[2] >= ARRAYS {
        return;
    }
    butterfly(id[2] * n * n + id[1] * n, 1, id[0], params, fft_pass, twiddles, src, dst);
}

/// `fft_columns(id)`: id.x butterfly, id.y column, id.z array.
pub fn fft_columns<R: Real>(
    id: [u32; 3],
    params: &WavesUniforms,
    fft_pass: &FftPassUniforms,
    twiddles: &[Vec2],
    src: &[Cx<R>],
    dst: &mut [Cx<R>],
) {
    let n = params.size;
    if id[0] >= n / 2 || id[1] >= n || id[2] >= ARRAYS {
        return;
    }
    butterfly(id[2] * n * n + id[1], n, id[0], params, fft_pass, twiddles, src, dst);
}

/// `store_texel`: the three texels (displacement, displacement_slopes, bump) of one bin from
/// its four transformed arrays.
pub fn store_texel<R: Real>(params: &WavesUniforms, arrays: [Cx<R>; 4]) -> [[R; 4]; 3] {
    let l = R::lit;
    let [height_disp_x, disp_z_disp_x_dz, slopes, disp_x_dx_disp_z_dz] = arrays;
    let height = height_disp_x[0];
    let disp_x = if params.lambda == 0.0 { l(0.0) } else { height_disp_x[1] };
    let disp_z = disp_z_disp_x_dz[0];
    let disp_x_dz = disp_z_disp_x_dz[1];
    let jacobian = (l(1.0) + disp_x_dx_disp_z_dz[0]) * (l(1.0) + disp_x_dx_disp_z_dz[1])
        - disp_x_dz * disp_x_dz;
    [
        [disp_x, height, disp_z, jacobian],
        [slopes[0], slopes[1], l(0.0), l(0.0)],
        [slopes[0], slopes[1], height, jacobian],
    ]
}

/// The three texels `pack(id)` stores: (displacement, displacement_slopes, bump), or `None`
/// outside the map.
pub fn pack<R: Real>(id: [u32; 3], params: &WavesUniforms, src: &[Cx<R>]) -> Option<[[R; 4]; 3]> {
    let n = params.size;
    if id[0] >= n || id[1] >= n {
        return None;
    }
    let bin = (id[1] * n + id[0]) as usize;
    let plane = (n * n) as usize;
    Some(store_texel(params, [0, 1, 2, 3].map(|f| src[f * plane + bin])))
}

/// The three textures `pack` writes.
#[derive(Clone, Debug, PartialEq)]
pub struct WaveTextures {
    /// (disp_x, height, disp_z, jacobian).
    pub displacement: Texture2D,
    /// (slope_x, slope_z, 0, 0).
    pub displacement_slopes: Texture2D,
    /// (slope_x, slope_z, height, jacobian).
    pub bump: Texture2D,
}

/// Which dispatch produced a buffer handed to [`WavesMirror::run_traced`]'s callback.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dispatch {
    /// `spectrum` (into ping).
    Spectrum,
    /// `fft_rows` stage `.0`.
    FftRows(u32),
    /// `fft_columns` stage `.0`.
    FftColumns(u32),
}

/// The stage's inputs for one [`WaveModes`] and the dispatches of a frame, as the GPU runs
/// them.
#[derive(Clone, Debug)]
pub struct WavesMirror {
    resolution: u32,
    dispersion: ocean_core::dispersion::Dispersion,
    modes: Vec<WaveModeData>,
    twiddles: Vec<Vec2>,
    passes: Vec<FftPassUniforms>,
}

impl WavesMirror {
    /// The mode table and twiddles of `modes`.
    ///
    /// # Errors
    /// N not a power of two (the radix-2 FFT of the GPU path).
    pub fn new(modes: &WaveModes) -> ocean_core::Result<Self> {
        let n = modes.resolution();
        check_fft_size(n)?;
        Ok(Self {
            resolution: n as u32,
            dispersion: *modes.dispersion(),
            modes: wave_mode_table(modes),
            twiddles: fft_twiddles(n),
            passes: fft_passes(n),
        })
    }

    /// The mode table (what the GPU uploads).
    pub fn modes(&self) -> &[WaveModeData] {
        &self.modes
    }

    /// Writable mode table: for negative controls (a perturbed h0).
    pub fn modes_mut(&mut self) -> &mut [WaveModeData] {
        &mut self.modes
    }

    /// The twiddle table (what the GPU uploads).
    pub fn twiddles(&self) -> &[Vec2] {
        &self.twiddles
    }

    /// Writable twiddle table: for negative controls (a wrong sign).
    pub fn twiddles_mut(&mut self) -> &mut [Vec2] {
        &mut self.twiddles
    }

    /// The uniforms of time `t` and `choppiness`.
    ///
    /// # Errors
    /// See [`WavesUniforms::new`].
    pub fn uniforms(&self, t: f64, choppiness: f64) -> ocean_core::Result<WavesUniforms> {
        WavesUniforms::new(self.resolution as usize, &self.dispersion, t, choppiness)
    }

    /// The textures of time `t` with `choppiness`.
    ///
    /// # Errors
    /// See [`WavesUniforms::new`].
    pub fn run(&self, t: f64, choppiness: f64) -> ocean_core::Result<WaveTextures> {
        Ok(self.run_traced(&self.uniforms(t, choppiness)?, &mut |_, _| {}))
    }

    /// Every dispatch of a frame with `params`; `on_dispatch` sees the buffer each spectrum
    /// and FFT dispatch wrote (4·N² complex values, array f at f·N²).
    pub fn run_traced(
        &self,
        params: &WavesUniforms,
        on_dispatch: &mut dyn FnMut(Dispatch, &[Vec2]),
    ) -> WaveTextures {
        let n = params.size;
        let [displacement, displacement_slopes, bump] =
            self.frame(params, on_dispatch).map(|t| Texture2D::new(n, n, t));
        WaveTextures { displacement, displacement_slopes, bump }
    }

    /// The envelope of the three textures of a frame with `params` (displacement,
    /// displacement_slopes, bump): every value a conformant GPU may store, given the uploaded
    /// mode and twiddle tables (exact: no arithmetic made them on the GPU).
    pub fn envelope(&self, params: &WavesUniforms) -> [Vec<[Iv; 4]>; 3] {
        self.frame(params, &mut |_, _| {})
    }

    /// The three textures as one random conformant GPU (or, at `rules.scale` 2, one twice as
    /// loose) computes them: the envelope's soundness test.
    pub fn jitter(&self, params: &WavesUniforms, rules: JitterRules) -> WaveTextures {
        Jitter::reseed(rules, 0);
        let n = params.size;
        let [displacement, displacement_slopes, bump] = self
            .frame::<Jitter>(params, &mut |_, _| {})
            .map(|t| Texture2D::new(n, n, t.into_iter().map(|v| v.map(|c| c.0)).collect()));
        WaveTextures { displacement, displacement_slopes, bump }
    }

    /// FFT dispatch `p` of a frame (`fft_rows` or `fft_columns`, one stage) from `src` into
    /// `dst`, over any [`Real`].
    fn fft_dispatch<R: Real>(
        &self,
        params: &WavesUniforms,
        p: usize,
        src: &[Cx<R>],
        dst: &mut [Cx<R>],
    ) -> Dispatch {
        let n = params.size;
        let fft_pass = &self.passes[p];
        let rows = (p as u32) < params.log2_size;
        for z in 0..ARRAYS {
            for y in 0..n {
                for x in 0..n / 2 {
                    let id = [x, y, z];
                    if rows {
                        fft_rows(id, params, fft_pass, &self.twiddles, src, dst);
                    } else {
                        fft_columns(id, params, fft_pass, &self.twiddles, src, dst);
                    }
                }
            }
        }
        if rows { Dispatch::FftRows(fft_pass.stage) } else { Dispatch::FftColumns(fft_pass.stage) }
    }

    /// The FFT dispatches of a frame: 2·log2(N), rows then columns.
    pub fn fft_dispatches(&self) -> usize {
        self.passes.len()
    }

    /// The envelope of FFT dispatch `p` given its input `src` (what a GPU read): one stage's
    /// butterflies, so a few ULP wide — the check that each dispatch's rules are not vacuous,
    /// where the whole frame's envelope is their composition.
    pub fn fft_dispatch_envelope(
        &self,
        params: &WavesUniforms,
        p: usize,
        src: &[Vec2],
    ) -> Vec<Cx<Iv>> {
        let src: Vec<Cx<Iv>> = src.iter().map(|v| v.map(Iv::point)).collect();
        let mut dst = vec![[Iv::point(0.0); 2]; src.len()];
        self.fft_dispatch(params, p, &src, &mut dst);
        dst
    }

    /// FFT dispatch `p` from `src` as one random conformant GPU computes it (`rules.scale`
    /// times the rules).
    pub fn fft_dispatch_jitter(
        &self,
        params: &WavesUniforms,
        p: usize,
        src: &[Vec2],
        rules: JitterRules,
    ) -> Vec<Vec2> {
        Jitter::reseed(rules, p as u64);
        let src: Vec<Cx<Jitter>> = src.iter().map(|v| v.map(Jitter)).collect();
        let mut dst = vec![[Jitter(0.0); 2]; src.len()];
        self.fft_dispatch(params, p, &src, &mut dst);
        dst.into_iter().map(|v| v.map(|c| c.0)).collect()
    }

    /// A frame's dispatches over any [`Real`]: the three textures' texels.
    fn frame<R: Real>(
        &self,
        params: &WavesUniforms,
        on_dispatch: &mut dyn FnMut(Dispatch, &[Cx<R>]),
    ) -> [Vec<[R; 4]>; 3] {
        let n = params.size;
        assert_eq!(n, self.resolution, "uniforms of another resolution");
        let len = (ARRAYS * n * n) as usize;
        let zero = [R::lit(0.0); 2];
        let mut ping = vec![zero; len];
        let mut pong = vec![zero; len];
        for j in 0..n {
            for i in 0..n {
                spectrum([i, j, 0], params, &self.modes, &mut ping);
            }
        }
        on_dispatch(Dispatch::Spectrum, &ping);
        for p in 0..self.passes.len() {
            let which = self.fft_dispatch(params, p, &ping, &mut pong);
            std::mem::swap(&mut ping, &mut pong);
            on_dispatch(which, &ping);
        }
        let mut texels = [Vec::new(), Vec::new(), Vec::new()];
        for j in 0..n {
            for i in 0..n {
                let t = pack([i, j, 0], params, &ping).unwrap_or([[R::lit(0.0); 4]; 3]);
                for (out, texel) in texels.iter_mut().zip(t) {
                    out.push(texel);
                }
            }
        }
        texels
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `cis_turns` against f64 cos and sin of 2πp over the whole range, on a fine grid and at
    /// the quadrant boundaries: within 4e-7 (a few f32 ulps of 1; the Taylor truncation on
    /// [−π/4, π/4] is below 2e-9).
    #[test]
    fn cis_turns_is_cos_and_sin_of_a_turn() {
        let mut worst = 0.0f64;
        let mut check = |p: f32| {
            let [c, s] = cis_turns(p);
            let x = std::f64::consts::TAU * f64::from(p);
            worst = worst.max((f64::from(c) - x.cos()).abs()).max((f64::from(s) - x.sin()).abs());
        };
        for i in -100_000..=100_000 {
            check(i as f32 / 200_000.0);
        }
        for q in [-0.5f32, -0.375, -0.25, -0.125, 0.0, 0.125, 0.25, 0.375, 0.5] {
            for d in [-1i32, 0, 1] {
                check(f32::from_bits((q.to_bits() as i32 + d) as u32));
            }
        }
        assert!(worst < 4e-7, "worst {worst:e}");
        // Exact where the quadrant rotation makes it so.
        assert_eq!(cis_turns(0.0), [1.0, 0.0]);
        assert_eq!(cis_turns(0.25), [-0.0, 1.0]);
        assert_eq!(cis_turns(-0.5), [-1.0, -0.0]);
    }
}
