//! Each judged pass's envelope verdict, given the inputs the GPU itself read.

use anyhow::bail;
use ocean_core::plan::{FramePlan, Pass, ResourceId};
use ocean_core::scene::Scene;

use super::GpuSide;

/// Pass `waves`' three maps, those the frame holds, against the envelope of the spectrum,
/// the FFT and the packing given the uploaded mode and twiddle tables (ocean-cpu
/// `WavesMirror::envelope`). None where the frame's wave maps are not `waves.wgsl`'s (a cycle
/// or a CPU synthesis: uploads).
pub(super) fn waves_verdicts(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
) -> anyhow::Result<Vec<(ResourceId, ocean_verify::envelope::FloatVerdict)>> {
    use ocean_core::plan::WavesKernel;
    if !plan.runs(Pass::Waves) || plan.runs(Pass::Cycle) || plan.waves_kernel != WavesKernel::Shader
    {
        return Ok(Vec::new());
    }
    let surface = scene.ocean.surface()?;
    let sets = [
        (
            &surface.displacement,
            [Some(ResourceId::Displacement), Some(ResourceId::DisplacementSlopes), None],
        ),
        (&surface.bump, [None, None, Some(ResourceId::Bump)]),
    ];
    let mut out = Vec::new();
    for (modes, ids) in sets {
        if ids.iter().flatten().all(|&id| gpu.map(id).is_none()) {
            continue;
        }
        let mirror = ocean_cpu::shaders::waves::WavesMirror::new(modes)?;
        let params = mirror.uniforms(scene.ocean.time_s, scene.ocean.choppiness)?;
        let env = mirror.envelope(&params);
        for (id, env) in ids.into_iter().zip(env) {
            let Some((id, ((w, h), texels))) = id.and_then(|id| Some((id, gpu.map(id)?))) else {
                continue;
            };
            let n = params.size;
            if (w, h) != (n, n) {
                bail!("{}: {w}x{h}, the plan's map {n}x{n}", id.name());
            }
            let env: Vec<Option<[ocean_cpu::envelope::Iv; 4]>> =
                env.into_iter().map(Some).collect();
            out.push((id, ocean_verify::envelope::judge_floats(id.name(), &env, texels, w)));
        }
    }
    Ok(out)
}

/// Pass `foam`'s field after a state's first frame (the warm-up and one step, from an empty
/// field) against its envelope given the GPU's own displacement map (waves `fft`) or the
/// waves' analytic Jacobian (`gerstner`). None where the frame has no field, or its J comes
/// from a displacement map the frame does not hold.
pub(super) fn foam_verdict(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
) -> anyhow::Result<Option<ocean_verify::envelope::FloatVerdict>> {
    use ocean_cpu::sampler::Texture2D;
    let Some(((w, h), field)) = gpu.map(ResourceId::FoamField).filter(|_| plan.runs(Pass::Foam))
    else {
        return Ok(None);
    };
    let state = ocean_core::graph::FrameState::new(0.0);
    let frame = ocean_core::graph::FrameInputs::new(scene, plan, &state)?;
    let eye = [frame.camera.eye.x, frame.camera.eye.z];
    let work = ocean_core::graph::FoamWork::new(scene, plan, &state, eye, frame.mesh.origin);
    let n = work.grid.size;
    if (w, h) != (n, n) {
        bail!("foam_field: {w}x{h}, the plan's field {n}x{n}");
    }
    let reads_map =
        work.steps.iter().any(|u| u.analytic == 0) && frame.uniforms.passes.waves != 0.0;
    let displacement = match gpu.map(ResourceId::Displacement) {
        Some(((dw, dh), t)) => Texture2D::new(dw, dh, t.to_vec()),
        None if !reads_map => Texture2D::new(1, 1, vec![[0.0; 4]]),
        None => return Ok(None),
    };
    let env: Vec<Option<[ocean_cpu::envelope::Iv; 1]>> =
        ocean_cpu::shaders::foam::envelope(&work.steps, &frame.uniforms, &displacement)
            .into_iter()
            .map(|v| Some([v]))
            .collect();
    Ok(Some(ocean_verify::envelope::judge_floats("foam_field", &env, field, w)))
}

/// The rasteriser's envelope of pass `shadow_map` (the objects' triangles, uploaded, seen
/// from the sun): the map's size, each texel's interval and whether its coverage is
/// ambiguous. None where the plan draws no shadow map.
fn shadow_envelope(
    scene: &Scene,
    plan: &FramePlan,
    frame: &ocean_core::graph::FrameInputs<'_>,
    precision: ocean_cpu::envelope::Precision,
) -> Option<([u32; 2], Vec<ocean_cpu::envelope::Iv>, Vec<bool>)> {
    let pass = plan.pass(Pass::ShadowMap).filter(|_| plan.runs(Pass::ShadowMap))?;
    let size = plan.resource(ResourceId::ShadowMap)?.size;
    let tris: Vec<[[f32; 3]; 3]> =
        ocean_core::frame::pass_triangles(scene, &frame.poses, pass, frame.camera.eye)
            .iter()
            .map(|t| t.map(|v| v.position))
            .collect();
    let (env, ambiguous) =
        ocean_cpu::shaders::shadow::envelope(&tris, &frame.uniforms, size, precision);
    Some((size, env, ambiguous))
}

/// The shadow map an objects' pass reads, as intervals: the GPU's own where the frame holds
/// it, else its envelope (a lit point where the plan draws none): its size and texels.
pub(super) fn shadow_occluder(
    scene: &Scene,
    plan: &FramePlan,
    frame: &ocean_core::graph::FrameInputs<'_>,
    gpu: &GpuSide<'_>,
) -> ([u32; 2], Vec<ocean_cpu::envelope::Iv>) {
    use ocean_cpu::envelope::Iv;
    match (gpu.map(ResourceId::ShadowMap), shadow_envelope(scene, plan, frame, gpu.precision.0)) {
        (Some(((sw, sh), t)), _) => ([sw, sh], t.iter().map(|t| Iv::point(t[0])).collect()),
        (None, Some((size, env, _))) => (size, env),
        (None, None) => ([1, 1], vec![Iv::point(1.0)]),
    }
}

/// Pass `shadow_map`'s depth map against [`shadow_envelope`], and the share of texels whose
/// coverage is ambiguous. None where the frame holds no shadow map.
pub(super) fn shadow_verdict(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
) -> anyhow::Result<Option<(ocean_verify::envelope::FloatVerdict, f64)>> {
    let Some(((w, _), texels)) = gpu.map(ResourceId::ShadowMap) else { return Ok(None) };
    let frame =
        ocean_core::graph::FrameInputs::new(scene, plan, &ocean_core::graph::FrameState::new(0.0))?;
    let Some((_, env, ambiguous)) = shadow_envelope(scene, plan, &frame, gpu.precision.0) else {
        return Ok(None);
    };
    if env.len() != texels.len() {
        bail!("shadow_map: {} texels, the plan's map {}", texels.len(), env.len());
    }
    if env.iter().all(|c| c.full) {
        return Ok(None);
    }
    let share = ambiguous.iter().filter(|&&a| a).count() as f64 / ambiguous.len().max(1) as f64;
    let env: Vec<Option<[ocean_cpu::envelope::Iv; 1]>> =
        env.into_iter().map(|v| Some([v])).collect();
    Ok(Some((ocean_verify::envelope::judge_floats("shadow_map", &env, texels, w), share)))
}

/// One of pass `objects`' maps (reflection or refraction) against the rasteriser's envelope
/// of the objects' triangles, each fragment shaded from its varyings' envelope (ocean-cpu
/// `objects::map_envelope`); the shadow map it reads is the GPU's own where the frame holds
/// it, else its envelope. Also the share of texels whose coverage or discard is ambiguous.
/// None where the frame holds no such map, or where shading `chiu` clips at a displacement
/// map the frame does not hold. The floor's relief shadow march is carried step by step
/// (ocean-cpu `floor::ReliefMarch`).
pub(super) fn map_verdict(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
    map: ocean_cpu::shaders::objects::ObjectMap,
) -> anyhow::Result<Option<(ResourceId, ocean_verify::envelope::FloatVerdict, f64)>> {
    use ocean_cpu::envelope::Iv;
    use ocean_cpu::shaders::objects::ObjectMap;
    let (id, pass) = match map {
        ObjectMap::Reflection => (ResourceId::ReflectionMap, Pass::ReflectionMap),
        ObjectMap::Refraction => (ResourceId::RefractionMap, Pass::RefractionMap),
    };
    let (Some(((w, h), texels)), Some(planned), Some(r)) =
        (gpu.map(id), plan.pass(pass).filter(|_| plan.runs(pass)), plan.resource(id))
    else {
        return Ok(None);
    };
    let frame =
        ocean_core::graph::FrameInputs::new(scene, plan, &ocean_core::graph::FrameState::new(0.0))?;
    let tris = ocean_core::frame::pass_triangles(scene, &frame.poses, planned, frame.camera.eye);
    let (dims, shadow) = shadow_occluder(scene, plan, &frame, gpu);
    let occluder = |x: u32, y: u32| shadow[y as usize * dims[0] as usize + x as usize];
    // Shading `chiu` clips at the wave height under the point: the GPU's own displacement map.
    let displacement = match gpu.map(ResourceId::Displacement) {
        Some(((dw, dh), t)) => ocean_cpu::sampler::Texture2D::new(dw, dh, t.to_vec()),
        None if frame.uniforms.chiu.clip_waves == 0.0 => {
            ocean_cpu::sampler::Texture2D::new(1, 1, vec![[0.0; 4]])
        }
        None => return Ok(None),
    };
    let (fw, fh, floor) = ocean_core::terrain::relief_texels(scene.terrain.as_ref());
    let floor_map = ocean_cpu::sampler::Texture2D::new(fw, fh, floor);
    let inputs = ocean_cpu::shaders::objects::MapInputs {
        frame: &frame.uniforms,
        size: [w, h],
        format: r.format.storage(),
        clear: r.clear,
        shadow_dims: dims,
        occluder: &occluder,
        displacement: &displacement,
        floor_map: &floor_map,
        precision: gpu.precision.0,
    };
    let (env, ambiguous) = ocean_cpu::shaders::objects::map_envelope(map, &tris, &inputs);
    if env.len() != texels.len() {
        bail!("{}: {} texels, the map {w}x{h}", id.name(), texels.len());
    }
    // An envelope that is anything everywhere (a vertex the clipper's bounds cannot place)
    // judges nothing: not judged, never passed.
    if env.iter().all(|t| t.iter().all(|c| c.full)) {
        return Ok(None);
    }
    let share = ambiguous.iter().filter(|&&a| a).count() as f64 / ambiguous.len().max(1) as f64;
    let env: Vec<Option<[Iv; 4]>> = env.into_iter().map(Some).collect();
    Ok(Some((id, ocean_verify::envelope::judge_floats(id.name(), &env, texels, w), share)))
}

/// One of pass `wave_mips`' chains against its envelope given the GPU's own slope map and
/// levels (ocean-cpu `wave_mips::envelope`).
pub(super) fn wave_mips_verdict(
    chain: ResourceId,
    (w, h): (u32, u32),
    src: &[[f32; 4]],
    atlas: &[[f32; 4]],
) -> anyhow::Result<ocean_verify::envelope::FloatVerdict> {
    use ocean_cpu::mip::{MipChain, level_count, level_row};
    use ocean_cpu::sampler::Texture2D;
    let levels = level_count(w, h);
    let rows = level_row(h, levels);
    if atlas.len() != w as usize * rows as usize {
        bail!("{}: {} texels, the chain of a {w}x{h} map {w}x{rows}", chain.name(), atlas.len());
    }
    let gpu =
        MipChain { width: w, height: h, levels, atlas: Texture2D::new(w, rows, atlas.to_vec()) };
    let env = ocean_cpu::shaders::wave_mips::envelope(&Texture2D::new(w, h, src.to_vec()), &gpu);
    Ok(ocean_verify::envelope::judge_floats(chain.name(), &env, atlas, w))
}

/// A GPU's bloom chain (its atlas, read back or from a dump) for a `w` × `h` frame, checked
/// against the plan's chain size.
pub(super) fn bloom_chain(
    inputs: &ocean_core::graph::BloomInputs,
    (w, h): (u32, u32),
    name: &str,
    atlas: &[[f32; 4]],
) -> anyhow::Result<ocean_cpu::mip::MipChain> {
    let [bw, bh] = ocean_core::bloom::level_size(w, h, 0);
    let levels = inputs.down.len() as u32;
    let rows = ocean_cpu::mip::level_row(bh, levels);
    if atlas.len() != bw as usize * rows as usize {
        bail!("{name}: {} texels, the plan's chain {bw}x{rows}", atlas.len());
    }
    let atlas = ocean_cpu::sampler::Texture2D::new(bw, rows, atlas.to_vec());
    Ok(ocean_cpu::mip::MipChain { width: bw, height: bh, levels, atlas })
}

/// Pass `bloom`'s chains against its envelope given the GPU's own inputs (each level from the
/// GPU's level before it: ocean-cpu `bloom::envelope`).
pub(super) fn bloom_verdicts(
    scene: &Scene,
    (w, h): (u32, u32),
    hdr: &[[f32; 4]],
    down: &[[f32; 4]],
    up: &[[f32; 4]],
) -> anyhow::Result<Vec<ocean_verify::envelope::FloatVerdict>> {
    use ocean_cpu::sampler::Texture2D;
    let inputs = ocean_core::graph::BloomInputs::new(scene);
    let bw = ocean_core::bloom::level_size(w, h, 0)[0];
    let down = bloom_chain(&inputs, (w, h), "bloom_down", down)?;
    let up = bloom_chain(&inputs, (w, h), "bloom_up", up)?;
    let hdr = Texture2D::new(w, h, hdr.to_vec());
    let (down_env, up_env) = ocean_cpu::shaders::bloom::envelope(&hdr, &down, &up, &inputs);
    Ok(vec![
        ocean_verify::envelope::judge_floats("bloom_down", &down_env, &down.atlas.texels, bw),
        ocean_verify::envelope::judge_floats("bloom_up", &up_env, &up.atlas.texels, bw),
    ])
}
