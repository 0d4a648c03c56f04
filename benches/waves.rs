//! Wave synthesis cost (issue 2): all six maps (height, choppy displacement, slopes,
//! Jacobian: four packed complex 2D inverse FFTs plus h̃(k, t) and the multipliers) at
//! N = 128, 256, 512 in f32, next to a bare rustfft 2D transform of the same size and count
//! (four complex N×N transforms: rows, transpose, rows), so the overhead is a ratio measured
//! in one run. Both use rustfft's scalar planner, as the oracle path must.
//!
//! `cargo bench --bench waves`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use num_complex::Complex;
use ocean_core::scene::Ocean;
use ocean_core::waves::{Synthesizer, WaveMaps};
use rustfft::FftPlannerScalar;

fn transpose(src: &[Complex<f32>], dst: &mut [Complex<f32>], n: usize) {
    for j in 0..n {
        for i in 0..n {
            dst[i * n + j] = src[j * n + i];
        }
    }
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("waves");
    group.sample_size(20);
    for n in [128usize, 256, 512] {
        let ocean = Ocean { resolution: n as u32, ..Ocean::default() };
        let modes = ocean.displacement_modes().expect("default ocean is valid");
        let mut synth = Synthesizer::<f32>::new(n).expect("synthesizer");
        let mut maps = WaveMaps::<f32>::new(n, ocean.patch_size_m);
        group.bench_with_input(BenchmarkId::new("synthesis_all_fields", n), &n, |b, _| {
            let mut t = 0.0;
            b.iter(|| {
                t += 0.016;
                synth.synthesize_into(&modes, t, 1.0, &mut maps).expect("maps");
                black_box(&maps.height);
            })
        });

        let fft = FftPlannerScalar::<f32>::new().plan_fft_inverse(n);
        let mut scratch = vec![Complex::new(0.0, 0.0); fft.get_inplace_scratch_len()];
        let mut a: Vec<Complex<f32>> =
            (0..n * n).map(|i| Complex::new((i % 7) as f32, (i % 5) as f32)).collect();
        let mut b2 = a.clone();
        group.bench_with_input(BenchmarkId::new("bare_rustfft_4x2d", n), &n, |b, _| {
            b.iter(|| {
                for _ in 0..4 {
                    fft.process_with_scratch(&mut a, &mut scratch);
                    transpose(&a, &mut b2, n);
                    fft.process_with_scratch(&mut b2, &mut scratch);
                    transpose(&b2, &mut a, n);
                }
                black_box(&a);
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
