//! The envelope's cost against the exact pass it judges (docs/tolerances.md): each judged
//! pass's mirror over `f32` (the exact frame) and over `Iv` (the envelope), on the same inputs
//! — the tonemap of a 640×360 frame, the wave_mips chain of a 256² slope map, a 256² Fresnel
//! table. The budget: the envelope at most 5× the exact pass.
//!
//! `cargo bench --bench envelope`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use ocean_core::frame::FresnelTableUniforms;
use ocean_core::rng::SplitMix64;
use ocean_core::tables::TextureMapping;
use ocean_core::tonemap::TonemapUniforms;
use ocean_cpu::sampler::Texture2D;
use ocean_cpu::shaders::{fresnel_table, tonemap, wave_mips};

fn random(n: usize, scale: f32, seed: u64) -> Vec<[f32; 4]> {
    let mut g = SplitMix64::new(seed);
    (0..n).map(|_| std::array::from_fn(|_| g.next_open_closed() as f32 * scale)).collect()
}

fn envelope(c: &mut Criterion) {
    let (w, h) = (640, 360);
    let hdr = random(w as usize * h as usize, 4.0, 1);
    let t = TonemapUniforms::for_image(1.0, &Default::default(), w, h).expect("uniforms");
    let mut g = c.benchmark_group("envelope");
    g.sample_size(10);
    g.bench_function("tonemap 640x360 exact", |b| {
        b.iter(|| black_box(tonemap::tonemap_to_rgba8(&hdr, w, h, &t)));
    });
    g.bench_function("tonemap 640x360 envelope", |b| {
        b.iter(|| black_box(tonemap::envelope_of(&hdr, None, w, h, &t)));
    });
    let slopes = Texture2D::new(256, 256, random(256 * 256, 0.5, 2));
    g.bench_function("wave_mips 256 exact", |b| b.iter(|| black_box(wave_mips::dispatch(&slopes))));
    let chain = wave_mips::dispatch(&slopes);
    g.bench_function("wave_mips 256 envelope", |b| {
        b.iter(|| black_box(wave_mips::envelope(&slopes, &chain)));
    });
    let params = FresnelTableUniforms::new(1.333, 256, TextureMapping::Grazing);
    g.bench_function("fresnel_table 256 exact", |b| {
        b.iter(|| black_box(fresnel_table::dispatch(&params)));
    });
    g.bench_function("fresnel_table 256 envelope", |b| {
        b.iter(|| black_box(fresnel_table::envelope(&params)));
    });
    g.finish();
}

criterion_group!(benches, envelope);
criterion_main!(benches);
