//! CPU mirror of `shaders/fresnel_table.wgsl`: the 2D Fresnel texture computed in f32 texel
//! by texel, as the compute shader does. (ocean-core's `tables::FresnelTexture` builds the
//! same table in f64 and is the reference the tests hold this against.)

use ocean_core::frame::FresnelTableUniforms;

use crate::sampler::Texture2D;
use crate::shaders::wgsl::{Vec3, max, sqrt, vec2, vec3};

pub use super::shared::fresnel::fresnel_exact;

/// `grazing_view_vector(id)`.
pub fn grazing_view_vector(id: [u32; 2], params: &FresnelTableUniforms) -> Vec3 {
    let u = id[0] as f32 * params.step - 1.0;
    let v = id[1] as f32 * params.step - 1.0;
    let d = vec2(u * sqrt(1.0 - 0.5 * v * v), v * sqrt(1.0 - 0.5 * u * u));
    let last = params.size - 1;
    let z = ((id[0] * (last - id[0])) as f32 * params.step2)
        * ((id[1] * (last - id[1])) as f32 * params.step2);
    let k = sqrt(1.0 + z);
    vec3(d.x * k, d.y * k, z)
}

/// `view_vector(s, t)`.
pub fn view_vector(s: f32, t: f32, params: &FresnelTableUniforms) -> Vec3 {
    if params.mapping == 1 {
        let x = s - 0.5;
        let y = t - 0.5;
        return vec3(x, y, sqrt(max(1.0 - x * x - y * y, 0.0)));
    }
    let x = 2.0 * s - 1.0;
    let y = 2.0 * t - 1.0;
    let r2 = x * x + y * y;
    if r2 > 1.0 {
        let r = sqrt(r2);
        return vec3(x / r, y / r, 0.0);
    }
    vec3(x, y, sqrt(max(1.0 - r2, 0.0)))
}

/// `main(id)`: the texel at `id`, or `None` outside the table.
pub fn main(id: [u32; 3], params: &FresnelTableUniforms) -> Option<[f32; 4]> {
    if id[0] >= params.size || id[1] >= params.size {
        return None;
    }
    let v = if params.mapping == 2 {
        grazing_view_vector([id[0], id[1]], params)
    } else {
        let n = params.size as f32;
        let s = (id[0] as f32 + 0.5) / n;
        let t = (id[1] as f32 + 0.5) / n;
        view_vector(s, t, params)
    };
    Some(v.extend(fresnel_exact(v.z, params.eta)).into())
}

/// Runs the stage over the whole table (the dispatch), row-major texels.
pub fn dispatch(params: &FresnelTableUniforms) -> Texture2D {
    let n = params.size;
    let texels = (0..n * n).map(|k| main([k % n, k / n, 0], params).unwrap_or([0.0; 4])).collect();
    Texture2D::new(n, n, texels)
}
