//! Building the water mesh of one frame (seed 000 §3): the near patch's bintree, the far
//! patch's precomputation, and the whole stitched mesh, for the default parameters (grid 1 m,
//! near patch 512 m, threshold 0.05 rad, far grid 128 × ~430 rings) at three heights.

use criterion::{Criterion, criterion_group, criterion_main};
use ocean_core::geometry::{FarPatch, NearPatch, PatchParams, WaterMesh};
use std::hint::black_box;

fn geometry(c: &mut Criterion) {
    let params = PatchParams::default();
    let (fov, aspect) = (55f64.to_radians(), 16.0 / 9.0);
    c.bench_function("far_patch_precompute", |b| {
        b.iter(|| FarPatch::precompute(&params, black_box(fov), aspect).expect("valid"))
    });
    let far = FarPatch::precompute(&params, fov, aspect).expect("valid");
    for h in [2.0, 100.0, 10_000.0] {
        let eye = [1.0e6 + 0.3, h, -2.0e5 - 0.2];
        c.bench_function(&format!("near_patch_h{h}"), |b| {
            b.iter(|| NearPatch::build(&params, black_box(eye)).expect("valid"))
        });
        c.bench_function(&format!("water_mesh_h{h}"), |b| {
            b.iter(|| {
                WaterMesh::for_view_with(&params, &far, black_box(eye), [0.3, -0.2, 1.0])
                    .expect("valid")
            })
        });
    }
}

criterion_group!(benches, geometry);
criterion_main!(benches);
