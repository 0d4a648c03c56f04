//! Mirror of `shaders/foam.wgsl` (stage `foam`: one step of foam `accumulated`'s field,
//! [`accumulate`]) and the foam techniques' `foam_coverage` (`shaders/foam/<technique>.wgsl`):
//! the share of a pixel the white water covers, which `water.wgsl` imports as
//! `technique/foam`.

pub mod accumulated;
pub mod heuristic;
pub mod jacobian;
pub mod none;

use ocean_core::foam::{FoamStepUniforms, accumulate_step, texel_is_fresh, texel_offset};
use ocean_core::frame::FrameUniforms;

use super::shared::gerstner::gerstner_jacobian;
use super::water::{Bindings, SurfacePoint, VertexOut};
use super::wgsl::vec2;
use crate::sampler::Texture2D;

/// `accumulate` over every texel: `src` the field before the step (`params.size`² texels),
/// `displacement` the frame's displacement map (waves `fft`); returns the field after it.
pub fn accumulate(
    params: &FoamStepUniforms,
    frame: &FrameUniforms,
    displacement: &Texture2D,
    src: &[[f32; 4]],
) -> Vec<[f32; 4]> {
    let n = params.size;
    let mut out = vec![[0.0; 4]; (n as usize) * (n as usize)];
    for y in 0..n {
        for x in 0..n {
            let fresh = texel_is_fresh(x, 0, params) || texel_is_fresh(y, 1, params);
            let j = if params.analytic == 1 {
                let ox = texel_offset(x, 0, params) as f32;
                let oz = texel_offset(y, 1, params) as f32;
                let pos = vec2(
                    params.start_rel[0] + ox * params.cell_m,
                    params.start_rel[1] + oz * params.cell_m,
                );
                gerstner_jacobian(pos, frame)
            } else {
                let t = displacement
                    .texel(x.min(displacement.width - 1), y.min(displacement.height - 1));
                1.0 + (t[3] - 1.0) * frame.passes.waves
            };
            let i = (y * n + x) as usize;
            out[i] = [accumulate_step(src[i][0], j, fresh, params), 0.0, 0.0, 0.0];
        }
    }
    out
}

/// A foam technique's `foam_coverage(in, p)`.
pub type FoamCoverage = fn(&VertexOut, &SurfacePoint, &Bindings<'_>) -> f32;

/// The CPU mirror of foam technique `technique`'s `foam_coverage`, if it has one.
pub fn foam_coverage(technique: &str) -> Option<FoamCoverage> {
    match technique {
        "none" => Some(none::foam_coverage),
        "heuristic" => Some(heuristic::foam_coverage),
        "jacobian" => Some(jacobian::foam_coverage),
        "accumulated" => Some(accumulated::foam_coverage),
        _ => None,
    }
}

/// The `foam_coverage` of [`ocean_core::foam::FoamBlock::mode`] `mode` (tools that rerun
/// the water pass from a frame's uniforms).
pub fn foam_coverage_of_mode(mode: f32) -> FoamCoverage {
    match mode as u32 {
        1 => heuristic::foam_coverage,
        2 => jacobian::foam_coverage,
        3 => accumulated::foam_coverage,
        _ => none::foam_coverage,
    }
}
