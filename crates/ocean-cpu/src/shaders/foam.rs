//! Mirror of `shaders/foam.wgsl` (stage `foam`: one step of foam `accumulated`'s field,
//! [`accumulate`]) and the foam techniques' `foam_coverage` (`shaders/foam/<technique>.wgsl`):
//! the share of a pixel the white water covers, which `water.wgsl` imports as
//! `technique/foam`.

pub mod accumulated;
pub mod heuristic;
pub mod jacobian;
pub mod none;

use ocean_core::foam::{FoamStepUniforms, texel_is_fresh, texel_offset};
use ocean_core::frame::FrameUniforms;

use super::shared::gerstner::gerstner_jacobian_r;
pub use super::water::FoamCoverage;
use crate::envelope::{Iv, Jitter, JitterRules, Real};
use crate::sampler::Texture2D;

/// `accumulate` over every texel: `src` the field before the step (`params.size`² texels),
/// `displacement` the frame's displacement map (waves `fft`); returns the field after it.
pub fn accumulate(
    params: &FoamStepUniforms,
    frame: &FrameUniforms,
    displacement: &Texture2D,
    src: &[[f32; 4]],
) -> Vec<[f32; 4]> {
    let j = jacobian_field(params, frame, displacement);
    let src: Vec<f32> = src.iter().map(|t| t[0]).collect();
    step_field(params, &j, &src).into_iter().map(|f| [f, 0.0, 0.0, 0.0]).collect()
}

/// The J `accumulate` reads at every texel, over any [`Real`]: the waves' analytic Jacobian at
/// the texel's lattice point (`gerstner`), or the displacement map's (`fft`, exact: a texel
/// read, and J = 1 where the waves pass was skipped).
pub fn jacobian_field<R: Real>(
    params: &FoamStepUniforms,
    frame: &FrameUniforms,
    displacement: &Texture2D,
) -> Vec<R> {
    let (n, l) = (params.size, R::lit);
    let mut out = Vec::with_capacity((n as usize) * (n as usize));
    for y in 0..n {
        for x in 0..n {
            out.push(if params.analytic == 1 {
                let ox = l(texel_offset(x, 0, params) as f32);
                let oz = l(texel_offset(y, 1, params) as f32);
                let cell = l(params.cell_m);
                let pos = [l(params.start_rel[0]) + ox * cell, l(params.start_rel[1]) + oz * cell];
                gerstner_jacobian_r(pos, frame)
            } else {
                let t = displacement
                    .texel(x.min(displacement.width - 1), y.min(displacement.height - 1));
                l(1.0) + (l(t[3]) - l(1.0)) * l(frame.passes.waves)
            });
        }
    }
    out
}

/// One step of the field (its `x` channel) given J per texel, over any [`Real`]:
/// f ← min(kept·decay + growth·clamp((threshold − J)·inv_softness, 0, 1), 1), the WGSL's order
/// (ocean-core's `accumulate_step`).
pub fn step_field<R: Real>(params: &FoamStepUniforms, j: &[R], src: &[R]) -> Vec<R> {
    let (n, l) = (params.size, R::lit);
    let mut out = Vec::with_capacity(src.len());
    for y in 0..n {
        for x in 0..n {
            let fresh = texel_is_fresh(x, 0, params) || texel_is_fresh(y, 1, params);
            let i = (y * n + x) as usize;
            let kept = if fresh { l(0.0) } else { src[i] };
            let source =
                ((l(params.threshold) - j[i]) * l(params.inv_softness)).clamp(l(0.0), l(1.0));
            out.push((kept * l(params.decay) + l(params.growth) * source).min(l(1.0)));
        }
    }
    out
}

/// The field after a frame's `steps` from an empty one (a state's first frame: the warm-up
/// and one step) over any [`Real`]; J is computed once while the window stays put.
pub fn run_steps<R: Real>(
    steps: &[FoamStepUniforms],
    frame: &FrameUniforms,
    displacement: &Texture2D,
) -> Vec<R> {
    let Some(first) = steps.first() else { return Vec::new() };
    let mut field = vec![R::lit(0.0); (first.size as usize) * (first.size as usize)];
    let mut j: Option<(FoamStepUniforms, Vec<R>)> = None;
    let same_window = |a: &FoamStepUniforms, b: &FoamStepUniforms| {
        (a.analytic, a.start, a.start_rel, a.cell_m) == (b.analytic, b.start, b.start_rel, b.cell_m)
    };
    for u in steps {
        if j.as_ref().is_none_or(|(v, _)| !same_window(u, v)) {
            j = Some((*u, jacobian_field(u, frame, displacement)));
        }
        let (_, jf) = j.as_ref().expect("just set");
        field = step_field(u, jf, &field);
    }
    field
}

/// The envelope of pass `foam`'s field after a state's first frame, given the GPU's own
/// displacement map: every value a conformant GPU may hold.
pub fn envelope(
    steps: &[FoamStepUniforms],
    frame: &FrameUniforms,
    displacement: &Texture2D,
) -> Vec<Iv> {
    run_steps(steps, frame, displacement)
}

/// The field as one random conformant GPU (`rules.scale` times the rules) computes it.
pub fn jitter(
    steps: &[FoamStepUniforms],
    frame: &FrameUniforms,
    displacement: &Texture2D,
    rules: JitterRules,
) -> Vec<f32> {
    Jitter::reseed(rules, 0);
    run_steps::<Jitter>(steps, frame, displacement).into_iter().map(|v| v.0).collect()
}

/// The CPU mirror of foam technique `technique`'s `foam_coverage`.
pub fn foam_coverage(technique: ocean_core::plan::Foam) -> FoamCoverage {
    use ocean_core::plan::Foam;
    match technique {
        Foam::None => none::foam_coverage,
        Foam::Heuristic => heuristic::foam_coverage,
        Foam::Jacobian => jacobian::foam_coverage,
        Foam::Accumulated => accumulated::foam_coverage,
    }
}
