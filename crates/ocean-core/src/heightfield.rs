//! The maps of a scene's sea at its time on the N × N grid of its patch, as `ocean
//! heightfield` writes them and the Python module returns them (docs/design.md's heightfield
//! contract).

use crate::scene::Scene;

/// (name, row-major samples) per channel.
pub type Channels = Vec<(&'static str, Vec<f32>)>;

/// The channels of `ocean heightfield` (and the Python `heightfield`): the N × N maps of a
/// scene's sea at `scene.ocean.time_s`, N the ocean's `resolution`, texel (i, j) at
/// x = i·L/N, z = j·L/N, as (name, row-major samples) in [`crate::waves::WaveMaps`]'
/// `FIELD_NAMES` order (`height`, `disp_x`, `disp_z`, `slope_x`, `slope_z`, `jacobian`).
/// Under waves `fft` the maps the FFT makes; under waves summed per vertex (`gerstner`,
/// `coastal`) the height query at the same points.
///
/// # Errors
/// As [`crate::frame::surface_query`], or modes that cannot be synthesised.
pub fn channels(scene: &Scene) -> crate::Result<(usize, Channels)> {
    use crate::waves::{SurfaceSample, Synthesizer, WaveMaps};
    let ocean = &scene.ocean;
    let plan = crate::plan::FramePlan::new(scene, crate::plan::OutputKind::Hdr);
    if plan.techniques.waves().per_vertex() {
        let n = ocean.resolution as usize;
        let sea = crate::frame::surface_query(scene, &plan, ocean.time_s)?;
        let step = ocean.patch_size_m / n as f64;
        let samples: Vec<SurfaceSample> =
            (0..n * n).map(|p| sea.sample((p % n) as f64 * step, (p / n) as f64 * step)).collect();
        let field = |f: fn(&SurfaceSample) -> f64| samples.iter().map(|s| f(s) as f32).collect();
        let data: [Vec<f32>; 6] = [
            field(|s| s.height),
            field(|s| s.disp_x),
            field(|s| s.disp_z),
            field(|s| s.slope_x),
            field(|s| s.slope_z),
            field(|s| s.jacobian),
        ];
        Ok((n, WaveMaps::<f32>::FIELD_NAMES.iter().copied().zip(data).collect()))
    } else {
        let modes = ocean.displacement_modes()?;
        let n = modes.resolution();
        let maps =
            Synthesizer::<f32>::new(n)?.synthesize(&modes, ocean.time_s, ocean.choppiness)?;
        Ok((n, maps.fields().iter().map(|(name, data)| (*name, data.to_vec())).collect()))
    }
}
