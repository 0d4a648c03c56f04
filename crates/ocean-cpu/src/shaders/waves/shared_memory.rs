//! CPU mirror of the shared-memory FFT of `shaders/waves.wgsl` (`spectrum_rows_shared`,
//! `columns_pack_shared`): a frame in two dispatches, the lines of a row or column held in
//! the workgroup's `fft_line` through every stage. It does the same operations as
//! `spectrum`, the one-stage FFT passes and `pack`, in the same order for each value, so its
//! textures equal [`WavesMirror::run`](super::WavesMirror::run)'s bit for bit; what differs is
//! only which workgroup does what and when, which the tests here pin down.

use ocean_core::waves::uniforms::{
    FFT_KEPT_PER_ARRAY, FFT_SHARED_MAX, FFT_SHARED_THREADS, WAVE_ARRAYS, WaveModeData,
    WavesUniforms, fft_shared_lines,
};

use super::{Vec2, WaveTextures, WavesMirror, complex_mul, spectrum_of, store_texel};
use crate::sampler::Texture2D;

/// The workgroup's `fft_line`: two halves of [`FFT_SHARED_MAX`] elements.
fn workgroup_memory() -> Vec<Vec2> {
    vec![[0.0; 2]; 2 * FFT_SHARED_MAX as usize]
}

fn add(a: Vec2, b: Vec2) -> Vec2 {
    [a[0] + b[0], a[1] + b[1]]
}

fn sub(a: Vec2, b: Vec2) -> Vec2 {
    [a[0] - b[0], a[1] - b[1]]
}

/// `fft_lines_shared(count, local)` of every thread of a workgroup, one pair of stages after
/// another as the barriers order them: the FFT of the `count` lines at [l·N, l·N + N) of the
/// half at 0, returning the offset of the half that holds the result. Within a pair of stages
/// no thread reads what another writes, so the threads' order does not matter.
pub fn fft_lines_shared(
    count: u32,
    fft_line: &mut [Vec2],
    params: &WavesUniforms,
    twiddles: &[Vec2],
) -> u32 {
    let n = params.size;
    let (half, quarter) = (n / 2, n / 4);
    let (mut read_at, mut write_at) = (0u32, FFT_SHARED_MAX);
    let mut stage = 0;
    while stage + 1 < params.log2_size {
        let s = 1u32 << stage;
        let quads_log2 = params.log2_size - 2;
        for t in 0..count << quads_log2 {
            let line = (t >> quads_log2) * n;
            let j = t & (quarter - 1);
            let q = j & (s - 1);
            let from = read_at + line;
            let at = |i: u32| fft_line[(from + i) as usize];
            let (a0, b0) = (at(j), at(j + half));
            let (a1, b1) = (at(j + quarter), at(j + quarter + half));
            let (d0, d1) = (sub(a0, b0), sub(a1, b1));
            let y0 = add(a0, b0);
            let y1 = complex_mul(d0, twiddles[(j - q) as usize]);
            let y2 = add(a1, b1);
            let y3 = complex_mul(d1, twiddles[(j + quarter - q) as usize]);
            let w = twiddles[(2 * (j - q)) as usize];
            let (e0, e1) = (sub(y0, y2), sub(y1, y3));
            let out = (write_at + line + 4 * j - 3 * q) as usize;
            let s = s as usize;
            fft_line[out] = add(y0, y2);
            fft_line[out + s] = add(y1, y3);
            fft_line[out + 2 * s] = complex_mul(e0, w);
            fft_line[out + 3 * s] = complex_mul(e1, w);
        }
        std::mem::swap(&mut read_at, &mut write_at);
        stage += 2;
    }
    if stage < params.log2_size {
        let s = 1u32 << stage;
        let pairs_log2 = params.log2_size - 1;
        for t in 0..count << pairs_log2 {
            let line = (t >> pairs_log2) * n;
            let j = t & (half - 1);
            let q = j & (s - 1);
            let a = fft_line[(read_at + line + j) as usize];
            let b = fft_line[(read_at + line + j + half) as usize];
            let w = twiddles[(j - q) as usize];
            let out = (write_at + line + 2 * j - q) as usize;
            fft_line[out] = add(a, b);
            fft_line[out + s as usize] = complex_mul(sub(a, b), w);
        }
        std::mem::swap(&mut read_at, &mut write_at);
    }
    read_at
}

/// `spectrum_rows_shared(group)`: row `group[0]`'s spectra of arrays `group[1]`·L … (L =
/// [`fft_shared_lines`]), transformed along x, written into `dst` (4·N² values, array f at
/// f·N²).
pub fn spectrum_rows_shared(
    group: [u32; 3],
    params: &WavesUniforms,
    modes: &[WaveModeData],
    twiddles: &[Vec2],
    dst: &mut [Vec2],
) {
    let n = params.size;
    let count = fft_shared_lines(n);
    let first = group[1] * count;
    let mut fft_line = workgroup_memory();
    for i in 0..n {
        let arrays = spectrum_of::<f32>(i, group[0], params, modes);
        for l in 0..count {
            fft_line[(l * n + i) as usize] = arrays[(first + l) as usize];
        }
    }
    let at = fft_lines_shared(count, &mut fft_line, params, twiddles);
    for l in 0..count {
        let base = (first + l) * n * n + group[0] * n;
        for i in 0..n {
            dst[(base + i) as usize] = fft_line[(at + l * n + i) as usize];
        }
    }
}

/// `columns_pack_shared(group)`: column `group[0]` of the four arrays in `src`, transformed
/// along z, [`fft_shared_lines`] at a time; the three texels (displacement,
/// displacement_slopes, bump) of each z of the column, in order.
pub fn columns_pack_shared(
    group: [u32; 3],
    params: &WavesUniforms,
    twiddles: &[Vec2],
    src: &[Vec2],
) -> Vec<[[f32; 4]; 3]> {
    let n = params.size;
    let count = fft_shared_lines(n);
    let mut fft_line = workgroup_memory();
    // Thread `local`'s registers, `kept[(array·FFT_KEPT_PER_ARRAY + k)]` for z = local + k·256,
    // for every thread at once.
    let mut kept =
        vec![[0.0f32; 2]; (FFT_SHARED_THREADS * WAVE_ARRAYS * FFT_KEPT_PER_ARRAY) as usize];
    let slot = |array: u32, z: u32| {
        let (local, k) = (z % FFT_SHARED_THREADS, z / FFT_SHARED_THREADS);
        ((local * WAVE_ARRAYS + array) * FFT_KEPT_PER_ARRAY + k) as usize
    };
    for first in (0..WAVE_ARRAYS).step_by(count as usize) {
        for l in 0..count {
            let base = (first + l) * n * n + group[0];
            for z in 0..n {
                fft_line[(l * n + z) as usize] = src[(base + z * n) as usize];
            }
        }
        let at = fft_lines_shared(count, &mut fft_line, params, twiddles);
        for l in 0..count {
            for z in 0..n {
                kept[slot(first + l, z)] = fft_line[(at + l * n + z) as usize];
            }
        }
    }
    (0..n).map(|z| store_texel(params, [0, 1, 2, 3].map(|a| kept[slot(a, z)]))).collect()
}

/// A whole frame of the shared-memory kernel with `params`: `spectrum_rows_shared` over every
/// row and batch into pong, then `columns_pack_shared` over every column.
pub fn frame(mirror: &WavesMirror, params: &WavesUniforms) -> WaveTextures {
    let n = params.size;
    let lines = fft_shared_lines(n);
    let mut pong = vec![[0.0f32; 2]; (WAVE_ARRAYS * n * n) as usize];
    for batch in 0..WAVE_ARRAYS / lines {
        for row in 0..n {
            spectrum_rows_shared(
                [row, batch, 0],
                params,
                mirror.modes(),
                mirror.twiddles(),
                &mut pong,
            );
        }
    }
    let mut texels = [(); 3].map(|_| vec![[0.0f32; 4]; (n * n) as usize]);
    for column in 0..n {
        for (z, texel) in columns_pack_shared([column, 0, 0], params, mirror.twiddles(), &pong)
            .into_iter()
            .enumerate()
        {
            for (map, value) in texels.iter_mut().zip(texel) {
                map[z * n as usize + column as usize] = value;
            }
        }
    }
    let [displacement, displacement_slopes, bump] = texels.map(|t| Texture2D::new(n, n, t));
    WaveTextures { displacement, displacement_slopes, bump }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean_core::dispersion::Dispersion;
    use ocean_core::waves::{ModeParams, WaveModes};

    /// Texels whose bits differ.
    fn differ(a: &Texture2D, b: &Texture2D) -> usize {
        let bits = |t: &[f32; 4]| t.map(f32::to_bits);
        a.texels.iter().zip(&b.texels).filter(|(x, y)| bits(x) != bits(y)).count()
    }

    /// A spectrum whose halves differ (F(k) ≠ F(−k)), so h̃'s two terms differ too.
    fn density(kx: f64, kz: f64) -> f64 {
        let k2 = kx * kx + kz * kz;
        if k2 == 0.0 { 0.0 } else { (1.0 + 0.6 * kx.signum()) * (-k2 / 4.0).exp() / (1.0 + k2) }
    }

    /// The two-dispatch frame against the one-stage frame (`spectrum`, 2·log₂N FFT passes,
    /// `pack`): the same operations in the same order for every value, so bit for bit, at
    /// every N it runs: log₂N odd (a last radix-2 stage) and even, four lines at once (N ≤
    /// 256), two (512) and one (1024).
    #[test]
    fn the_two_dispatch_frame_is_the_one_stage_frame() {
        for n in [2usize, 4, 8, 64, 128, 256, 512, 1024] {
            let modes =
                WaveModes::new(&ModeParams::new(50.0, n, 11), Dispersion::deep(9.81), density)
                    .unwrap();
            let mirror = WavesMirror::new(&modes).unwrap();
            let params = mirror.uniforms(3.7, 1.3).unwrap();
            let stages = mirror.run_traced(&params, &mut |_, _| {});
            let shared = frame(&mirror, &params);
            for (a, b, name) in [
                (&shared.displacement, &stages.displacement, "displacement"),
                (&shared.displacement_slopes, &stages.displacement_slopes, "displacement_slopes"),
                (&shared.bump, &stages.bump, "bump"),
            ] {
                let differ = differ(a, b);
                assert_eq!(differ, 0, "N = {n}, {name}: {differ} of {} texels differ", n * n);
            }
            // The control: the sea 1 s later differs almost everywhere (N = 2 holds only the
            // mean and Nyquist modes, which are 0: its sea is flat).
            if n == 2 {
                continue;
            }
            let later = frame(&mirror, &mirror.uniforms(4.7, 1.3).unwrap());
            let moved = differ(&later.displacement, &stages.displacement);
            assert!(moved > n * n / 2, "N = {n}: only {moved} texels moved");
        }
    }

    /// A twiddle of the shared kernel alone off by one ULP shows: the comparison above can
    /// fail on a change of the shared kernel's arithmetic.
    #[test]
    fn a_changed_twiddle_is_seen() {
        let modes = WaveModes::new(&ModeParams::new(50.0, 64, 11), Dispersion::deep(9.81), density)
            .unwrap();
        let mut mirror = WavesMirror::new(&modes).unwrap();
        let params = mirror.uniforms(3.7, 1.3).unwrap();
        let stages = mirror.run_traced(&params, &mut |_, _| {});
        let w = &mut mirror.twiddles_mut()[5];
        w[0] = f32::from_bits(w[0].to_bits() + 1);
        let shared = frame(&mirror, &params);
        assert!(differ(&shared.bump, &stages.bump) > 0);
    }
}
