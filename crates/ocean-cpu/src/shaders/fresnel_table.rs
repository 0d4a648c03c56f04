//! CPU mirror of `shaders/fresnel_table.wgsl`: the 2D Fresnel texture computed in f32 texel
//! by texel, as the compute shader does. (ocean-core's `tables::FresnelTexture` builds the
//! same table in f64 and is the reference the tests hold this against.)

use ocean_core::frame::FresnelTableUniforms;

use crate::envelope::{Iv, Jitter, JitterRules, Real, choose_n};
use crate::sampler::Texture2D;
use crate::shaders::wgsl::Vec3;

pub use super::shared::fresnel::fresnel_exact;
use super::shared::fresnel::fresnel_exact_r;

/// `grazing_view_vector(id)`.
pub fn grazing_view_vector(id: [u32; 2], params: &FresnelTableUniforms) -> Vec3 {
    Vec3::from(grazing_view_vector_r::<f32>(id, params))
}

/// [`grazing_view_vector`] over any [`Real`].
pub fn grazing_view_vector_r<R: Real>(id: [u32; 2], params: &FresnelTableUniforms) -> [R; 3] {
    let l = R::lit;
    let (step, one) = (l(params.step), l(1.0));
    let u = l(id[0] as f32) * step - one;
    let v = l(id[1] as f32) * step - one;
    let d = [u * (one - l(0.5) * v * v).sqrt(), v * (one - l(0.5) * u * u).sqrt()];
    let last = params.size - 1;
    let step2 = l(params.step2);
    let z =
        (l((id[0] * (last - id[0])) as f32) * step2) * (l((id[1] * (last - id[1])) as f32) * step2);
    let k = (one + z).sqrt();
    [d[0] * k, d[1] * k, z]
}

/// `view_vector(s, t)`.
pub fn view_vector(s: f32, t: f32, params: &FresnelTableUniforms) -> Vec3 {
    Vec3::from(view_vector_r(s, t, params))
}

/// [`view_vector`] over any [`Real`].
pub fn view_vector_r<R: Real>(s: R, t: R, params: &FresnelTableUniforms) -> [R; 3] {
    let l = R::lit;
    let (zero, one) = (l(0.0), l(1.0));
    if params.mapping == 1 {
        let x = s - l(0.5);
        let y = t - l(0.5);
        return [x, y, (one - x * x - y * y).max(zero).sqrt()];
    }
    let x = l(2.0) * s - one;
    let y = l(2.0) * t - one;
    let r2 = x * x + y * y;
    choose_n(
        one.lt(r2),
        || {
            let r = r2.sqrt();
            [x / r, y / r, zero]
        },
        || [x, y, (one - r2).max(zero).sqrt()],
    )
}

/// `main(id)`: the texel at `id`, or `None` outside the table.
pub fn main(id: [u32; 3], params: &FresnelTableUniforms) -> Option<[f32; 4]> {
    main_r(id, params)
}

/// [`main`] over any [`Real`].
pub fn main_r<R: Real>(id: [u32; 3], params: &FresnelTableUniforms) -> Option<[R; 4]> {
    if id[0] >= params.size || id[1] >= params.size {
        return None;
    }
    let v = if params.mapping == 2 {
        grazing_view_vector_r([id[0], id[1]], params)
    } else {
        let n = R::lit(params.size as f32);
        let s = (R::lit(id[0] as f32) + R::lit(0.5)) / n;
        let t = (R::lit(id[1] as f32) + R::lit(0.5)) / n;
        view_vector_r(s, t, params)
    };
    Some([v[0], v[1], v[2], fresnel_exact_r(v[2], R::lit(params.eta))])
}

/// Runs the stage over the whole table (the dispatch), row-major texels.
pub fn dispatch(params: &FresnelTableUniforms) -> Texture2D {
    let n = params.size;
    let texels = (0..n * n).map(|k| main([k % n, k / n, 0], params).unwrap_or([0.0; 4])).collect();
    Texture2D::new(n, n, texels)
}

/// The table's envelope: every texel of any conformant GPU.
pub fn envelope(params: &FresnelTableUniforms) -> Vec<Option<[Iv; 4]>> {
    let n = params.size;
    (0..n * n).map(|k| main_r([k % n, k / n, 0], params)).collect()
}

/// The table as one random conformant GPU computes it (`rules`).
pub fn jitter(params: &FresnelTableUniforms, rules: JitterRules) -> Texture2D {
    let n = params.size;
    let texels = (0..n * n)
        .map(|k| {
            Jitter::reseed(rules, u64::from(k));
            main_r::<Jitter>([k % n, k / n, 0], params).map_or([0.0; 4], |v| v.map(|c| c.0))
        })
        .collect();
    Texture2D::new(n, n, texels)
}
