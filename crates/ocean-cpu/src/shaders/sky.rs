//! Mirror of `shaders/sky.wgsl`: the environment behind everything, one compute invocation
//! per pixel; its techniques are the submodules (`shaders/sky/<technique>.wgsl`).

pub mod atmosphere;
pub mod overcast;
pub mod preetham;
pub mod preetham_clouds;

use ocean_core::atmosphere::SkyLut;
use ocean_core::plan::Sky;

use rayon::prelude::*;

use crate::raster::RenderTarget;
use crate::shaders::shared::camera::{CameraUniforms, view_ray};
use crate::shaders::shared::preetham::SkyUniforms;
use crate::shaders::wgsl::{Vec3, vec2};

/// A sky technique's `sky_radiance`: radiance of a world direction (arrays at this boundary
/// to the frame and the water's bindings), given the stage's `sky` and `sky_lut`.
pub type SkyRadiance = fn(&SkyUniforms, &SkyLut, [f32; 3]) -> [f32; 3];

/// A sky technique's interface: `sky_radiance` and `sun_disc`.
#[derive(Clone, Copy, Debug)]
pub struct SkyTechnique {
    /// `sky_radiance(sky, dir)`, with the stage's `sky_lut` that the WGSL reads.
    pub sky_radiance: fn(&SkyUniforms, &SkyLut, Vec3) -> Vec3,
    /// `sun_disc(sky, dir)`.
    pub sun_disc: fn(&SkyUniforms, Vec3) -> Vec3,
}

/// The mirror of sky technique `technique`.
pub fn technique(technique: Sky) -> SkyTechnique {
    match technique {
        Sky::Preetham => SkyTechnique {
            sky_radiance: |sky, _, dir| preetham::sky_radiance(sky, dir),
            sun_disc: preetham::sun_disc,
        },
        Sky::PreethamClouds => SkyTechnique {
            sky_radiance: |sky, _, dir| preetham_clouds::sky_radiance(sky, dir),
            sun_disc: preetham_clouds::sun_disc,
        },
        Sky::Atmosphere => {
            SkyTechnique { sky_radiance: atmosphere::sky_radiance, sun_disc: atmosphere::sun_disc }
        }
        Sky::Overcast => SkyTechnique {
            sky_radiance: |sky, _, dir| overcast::sky_radiance(sky, dir),
            sun_disc: overcast::sun_disc,
        },
    }
}

/// The environment's radiance of a world direction for the frame's sky technique: what
/// `sky_radiance` of the WGSL's `// #import technique/sky` is.
pub fn environment_radiance(technique: Sky) -> SkyRadiance {
    match technique {
        Sky::Preetham => |sky, _, dir| preetham::sky_radiance(sky, dir.into()).into(),
        Sky::PreethamClouds => |sky, _, dir| preetham_clouds::sky_radiance(sky, dir.into()).into(),
        Sky::Atmosphere => |sky, lut, dir| atmosphere::sky_radiance(sky, lut, dir.into()).into(),
        Sky::Overcast => |sky, _, dir| overcast::sky_radiance(sky, dir.into()).into(),
    }
}

/// `cs_main(@builtin(global_invocation_id) id)`: the linear HDR radiance, alpha 1, that it
/// stores at texel `id` (inside the frame: the shader returns early outside), along the ray
/// through the pixel centre `id + 0.5` (exact in f32 for any frame a GPU can hold).
pub fn cs_main(
    id: [u32; 2],
    camera: &CameraUniforms,
    sky: &SkyUniforms,
    lut: &SkyLut,
    t: &SkyTechnique,
) -> [f32; 4] {
    let dir = view_ray(camera, vec2(id[0] as f32 + 0.5, id[1] as f32 + 0.5));
    let radiance = (t.sky_radiance)(sky, lut, dir) + (t.sun_disc)(sky, dir);
    radiance.extend(1.0).into()
}

/// The `sky` pass into `target`: [`cs_main`] at every pixel with sky technique `t`, stored in
/// the target's format, rows in parallel (each pixel is a pure function of its centre). The
/// pass neither tests nor writes depth.
///
/// `camera.viewport` must describe `target` (checked in debug builds).
pub fn render_sky(
    target: &mut RenderTarget,
    camera: &CameraUniforms,
    sky: &SkyUniforms,
    lut: &SkyLut,
    t: &SkyTechnique,
) {
    debug_assert!(
        camera.viewport[0] == target.width as f32 && camera.viewport[1] == target.height as f32,
        "camera viewport {:?} does not match the {}x{} target",
        camera.viewport,
        target.width,
        target.height
    );
    let (width, format) = (target.width as usize, target.format);
    if width == 0 {
        return;
    }
    target.color.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
        for (x, px) in row.iter_mut().enumerate() {
            *px = format.store4(cs_main([x as u32, y as u32], camera, sky, lut, t));
        }
    });
}

/// What the sky pass's envelope reads: its uniforms and, for `atmosphere`, the sky-view table.
#[derive(Clone, Copy, Debug)]
pub struct SkyInputs<'a> {
    /// The camera's uniforms.
    pub camera: &'a CameraUniforms,
    /// The sky's uniforms.
    pub sky: &'a SkyUniforms,
    /// The sky-view table (`atmosphere`).
    pub lut: &'a SkyLut,
}

/// The water's `sky_radiance(sky, dir)` over any [`crate::envelope::Real`] (the sky pass's
/// radiance without its sun disc): every technique's mirror runs over one.
pub fn sky_radiance_r<R: crate::envelope::Real>(
    technique: Sky,
    sky: &SkyUniforms,
    lut: &SkyLut,
    dir: [R; 3],
) -> [R; 3] {
    use crate::shaders::shared::preetham::preetham_radiance_r;
    use crate::shaders::shared::sky_lut::sky_lut_radiance_r;
    match technique {
        Sky::Atmosphere => {
            let s = sky.sun_direction;
            sky_lut_radiance_r(lut, dir, [R::lit(s[0]), R::lit(s[1]), R::lit(s[2])])
        }
        Sky::PreethamClouds => preetham_clouds::sky_radiance_r(sky, dir),
        Sky::Preetham => preetham_radiance_r(sky, dir),
        Sky::Overcast => overcast::sky_radiance_r(sky, dir),
    }
}

/// The sky pass's `sun_disc(sky, dir)` over any [`crate::envelope::Real`].
pub fn sun_disc_r<R: crate::envelope::Real>(
    technique: Sky,
    sky: &SkyUniforms,
    dir: [R; 3],
) -> [R; 3] {
    use crate::shaders::shared::preetham::preetham_sun_disc_r;
    match technique {
        Sky::Preetham | Sky::Atmosphere => preetham_sun_disc_r(sky, dir),
        Sky::PreethamClouds => preetham_clouds::sun_disc_r(sky, dir),
        Sky::Overcast => [R::lit(0.0); 3],
    }
}

/// `cs_main` over any [`crate::envelope::Real`] at every pixel of a `width × height` frame,
/// stored in `format`; `each(i)` runs before pixel i (a [`crate::envelope::Jitter`] reseeds
/// there).
fn sky_frame<R: crate::envelope::Real + Send>(
    technique: Sky,
    inputs: SkyInputs<'_>,
    (width, height): (u32, u32),
    format: ocean_core::frame_format::FrameFormat,
    each: impl Fn(usize) + Sync,
) -> Vec<[R; 3]> {
    use rayon::prelude::*;

    use crate::shaders::shared::camera::view_ray_r;
    let SkyInputs { camera, sky, lut } = inputs;
    let w = width as usize;
    (0..w * height as usize)
        .into_par_iter()
        .with_min_len(w.max(1))
        .map(|i| {
            each(i);
            let p = [R::lit((i % w) as f32 + 0.5), R::lit((i / w) as f32 + 0.5)];
            let dir = view_ray_r(camera, p);
            let s = sky_radiance_r(technique, sky, lut, dir);
            let d = sun_disc_r(technique, sky, dir);
            std::array::from_fn(|c| (s[c] + d[c]).store(format))
        })
        .collect()
}

/// The sky pass's envelope at every pixel (what any conformant GPU writes there before the
/// passes after it).
pub fn envelope(
    technique: Sky,
    inputs: SkyInputs<'_>,
    size: (u32, u32),
    format: ocean_core::frame_format::FrameFormat,
) -> Vec<[crate::envelope::Iv; 3]> {
    sky_frame(technique, inputs, size, format, |_| {})
}

/// The sky pass as one random conformant GPU computes it (`rules`).
pub fn jitter(
    technique: Sky,
    inputs: SkyInputs<'_>,
    size: (u32, u32),
    format: ocean_core::frame_format::FrameFormat,
    rules: crate::envelope::JitterRules,
) -> Vec<[f32; 3]> {
    use crate::envelope::Jitter;
    let v: Vec<[Jitter; 3]> =
        sky_frame(technique, inputs, size, format, |i| Jitter::reseed(rules, i as u64));
    v.into_iter().map(|p| p.map(|c| c.0)).collect()
}

/// The exact sky pass (f32, lavapipe's arithmetic) at every pixel: which pixels of a frame
/// still hold it tells where the sky is judged.
pub fn exact(
    technique: Sky,
    inputs: SkyInputs<'_>,
    size: (u32, u32),
    format: ocean_core::frame_format::FrameFormat,
) -> Vec<[f32; 3]> {
    sky_frame(technique, inputs, size, format, |_| {})
}
