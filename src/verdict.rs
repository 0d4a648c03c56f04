//! The envelope's verdict on a frame a GPU made (docs/tolerances.md), shared by `ocean compare`
//! and `ocean selftest`: each judged pass is held to the envelope of its arithmetic given the
//! inputs the GPU itself read, so a verdict needs no oracle frame and localises a fault to a
//! pass.

use anyhow::bail;
use ocean_core::plan::{FramePlan, Pass, ResourceId};
use ocean_core::scene::Scene;
use ocean_cpu::shaders::objects::ObjectMap;
use ocean_verify::envelope::MAX_AMBIGUOUS_SHARE;
use serde_json::{Value, json};

mod main_view;
mod passes;
pub mod spray;

use main_view::{sky_verdict, water_verdict};
use passes::{
    bloom_chain, bloom_verdicts, foam_verdict, map_verdict, shadow_verdict, wave_mips_verdict,
    waves_verdicts,
};

/// A float frame as read back: (width, height) and its texels.
pub type FrameRef<'a> = ((u32, u32), &'a [[f32; 4]]);

/// What a GPU made of a frame: its float resources as read back (or read from a dump), and
/// its 8-bit picture.
#[derive(Clone, Debug)]
pub struct GpuSide<'a> {
    /// The float resources the frame holds.
    pub maps: Vec<(ResourceId, FrameRef<'a>)>,
    /// The 8-bit picture.
    pub ldr: Option<&'a [u8]>,
    /// The oracle's final HDR frame of the same scene, if at hand: where it still holds the
    /// exact sky pass, the GPU's `hdr` is judged against the sky's envelope.
    pub oracle_hdr: Option<&'a [[f32; 4]]>,
    /// The precision the adapter guarantees (its snap, filter weights and level blend), and
    /// where the figures come from ([`precision_of`]).
    pub precision: (ocean_cpu::envelope::Precision, &'static str),
    /// Whether a failure already found ends the verdict before the water pass's envelope (the
    /// costliest): for a planted bug, where one failure is the answer.
    pub first_failure: bool,
    /// The water pass's envelope on every `water_every`-th pixel along each axis (1: all; 3
    /// for a quick verdict: a ninth of the cost).
    pub water_every: u32,
    /// One more step of the spray, run on the device after the frame ([`spray::probe`]);
    /// `None` where the frame has no spray or the step was not run (a dump).
    pub spray: Option<&'a spray::SprayProbe>,
}

/// The precision of an adapter by its name and PCI vendor id as written in a report or a
/// manifest ("0x10de"): [`ocean_cpu::envelope::Precision::of_adapter`].
pub fn precision_of(name: &str, vendor: &str) -> (ocean_cpu::envelope::Precision, &'static str) {
    let id = u32::from_str_radix(vendor.trim_start_matches("0x"), 16).unwrap_or(0);
    ocean_cpu::envelope::Precision::of_adapter(name, id)
}

impl Default for GpuSide<'_> {
    fn default() -> Self {
        Self {
            maps: Vec::new(),
            ldr: None,
            oracle_hdr: None,
            precision: (ocean_cpu::envelope::Precision::VULKAN_MINIMUM, "Vulkan's minimum limits"),
            first_failure: false,
            water_every: 1,
            spray: None,
        }
    }
}

impl<'a> GpuSide<'a> {
    /// A resource, if the frame holds it.
    pub fn map(&self, id: ResourceId) -> Option<FrameRef<'a>> {
        self.maps.iter().find(|(m, _)| *m == id).map(|(_, f)| *f)
    }

    fn texels(&self, id: ResourceId) -> Option<&'a [[f32; 4]]> {
        self.map(id).map(|(_, t)| t)
    }
}

/// The envelope's verdict on one frame.
#[derive(Clone, Debug, Default)]
pub struct Verdict {
    /// One line per resource, for the terminal.
    pub lines: Vec<String>,
    /// Every resource outside its envelope (or missing), one line each.
    pub failures: Vec<String>,
    /// The JSON entries, one per resource.
    pub json: Vec<Value>,
    /// The resources judged.
    pub judged: Vec<&'static str>,
    /// The resources not judged (their passes have no envelope yet, or an input is missing).
    pub not_judged: Vec<&'static str>,
    /// Of `failures`, those with every value inside but more than [`MAX_AMBIGUOUS_SHARE`] of
    /// the resource ambiguous: too little decided to judge, rather than a value outside.
    pub too_ambiguous: usize,
}

impl Verdict {
    /// Whether something was judged, and everything judged is inside.
    pub fn passed(&self) -> bool {
        self.failures.is_empty() && !self.judged.is_empty()
    }

    /// Whether it failed only for too many ambiguous pixels or texels: no value outside.
    pub fn only_too_ambiguous(&self) -> bool {
        !self.failures.is_empty() && self.failures.len() == self.too_ambiguous
    }

    /// A region's failure (the sky's, the water's, the spray's): too ambiguous where every
    /// judged value is inside.
    fn fail_region(&mut self, f: &ocean_verify::envelope::RegionVerdict, line: String) {
        if !f.passed() {
            self.too_ambiguous += usize::from(f.inner.passed());
            self.failures.push(line);
        }
    }

    /// Records pass `pass`'s verdict on resource `name` (`note` appended to its line).
    fn record(
        &mut self,
        pass: &str,
        name: &'static str,
        f: &ocean_verify::envelope::FloatVerdict,
        note: &str,
    ) {
        self.lines.push(format!("  [{pass:<14}] {}{note}", f.line()));
        if !f.passed() {
            self.failures.push(f.line());
        }
        self.json.push(f.to_json());
        self.judged.push(name);
    }

    /// [`Self::record`] for a map whose coverage may be ambiguous: the share of its texels
    /// that are (`what` says of what) in the line and in the JSON's `ambiguous_share`, held
    /// to [`MAX_AMBIGUOUS_SHARE`] as a screen resource's pixels are.
    fn record_ambiguous(
        &mut self,
        pass: &str,
        name: &'static str,
        f: &ocean_verify::envelope::FloatVerdict,
        share: f64,
        what: &str,
    ) {
        let held = share_held(share);
        let mut note = format!(
            " ({:.2} % of texels' {what} ambiguous, at most {} %)",
            100.0 * share,
            100.0 * MAX_AMBIGUOUS_SHARE
        );
        if !held {
            note.push_str(" — too many ambiguous texels FAIL");
        }
        self.record(pass, name, f, &note);
        if !held && f.passed() {
            self.failures.push(format!("{name}: {}", note.trim_start()));
            self.too_ambiguous += 1;
        }
        if let Some(j) = self.json.last_mut() {
            j["ambiguous_share"] = json!(share);
            j["passed"] = json!(f.passed() && held);
        }
    }
}

/// Whether a map's ambiguous share is within [`MAX_AMBIGUOUS_SHARE`] (NaN is not).
fn share_held(share: f64) -> bool {
    share <= MAX_AMBIGUOUS_SHARE
}

/// The envelope's verdict on a frame as a GPU made it, each pass from the inputs the GPU
/// itself read: `bloom`'s and `wave_mips`' chains (each level from the GPU's level before it),
/// the `waves` pass's maps (from the uploaded modes), the foam field (from the GPU's
/// displacement map), the shadow and reflection maps (the rasteriser's envelope of the
/// objects' triangles),
/// the uploaded `fresnel_filter` (bit for bit), the Fresnel tables, the spray's step (from the
/// pool the GPU held, where `gpu.spray` holds one), the HDR frame's sky pixels
/// (where `oracle_hdr` says the sky shows) and the picture (against the `tonemap` envelope of
/// the GPU's own HDR frame and bloom). The rest of `resources`, whose passes have no envelope
/// yet, are listed as not judged; a frame of which nothing is judged fails.
///
/// # Errors
/// A resource of the wrong size, or uniforms the scene cannot make.
pub fn envelope_verdict(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
    resources: &[ResourceId],
) -> anyhow::Result<Verdict> {
    let mut v = judge_passes(scene, plan, gpu, resources)?;
    // Not judged is never passed: a frame of which nothing could be judged fails.
    if v.judged.is_empty() {
        v.failures.push(
            "nothing judged: no pass of this frame has an envelope, or their inputs are missing"
                .to_owned(),
        );
    }
    Ok(v)
}

/// [`envelope_verdict`]'s passes, one by one.
fn judge_passes(
    scene: &Scene,
    plan: &FramePlan,
    gpu: &GpuSide<'_>,
    resources: &[ResourceId],
) -> anyhow::Result<Verdict> {
    let mut v = Verdict::default();
    v.judge_bloom(scene, plan, gpu)?;
    v.judge_maps(scene, plan, gpu)?;
    v.judge_wave_mips(plan, gpu)?;
    v.judge_fresnel(scene, plan, gpu)?;
    v.judge_spray(plan, gpu)?;
    if let (Some(((w, h), hdr)), Some(oracle)) = (gpu.map(ResourceId::Hdr), gpu.oracle_hdr)
        && let Some(f) = sky_verdict(scene, plan, (w, h), (hdr, oracle), gpu)?
    {
        v.lines.push(format!("  [{:<14}] {}", "sky", f.line()));
        v.fail_region(&f, f.line());
        v.json.push(f.to_json());
        v.judged.push("hdr (sky)");
    }
    // The water's envelope is the costliest: where one failure is the answer, it is spared.
    if gpu.first_failure && !v.failures.is_empty() {
        v.not_judged.push("hdr");
        return Ok(v);
    }
    v.judge_water(scene, plan, gpu)?;
    // Each resource once: judged, not judged with its own reason, or without an envelope.
    let listed: Vec<&str> = v.judged.iter().chain(&v.not_judged).copied().collect();
    for &id in resources.iter().filter(|id| !listed.contains(&id.name())) {
        let pass = id.writer().map_or("", |p| p.name());
        let (why, entry) = ocean_verify::envelope::not_judged(id);
        v.lines.push(format!("  [{pass:<14}] {:<20} not judged: {why}", id.name()));
        v.json.push(entry);
        v.not_judged.push(id.name());
    }
    v.judge_tonemap(scene, plan, gpu)?;
    Ok(v)
}

impl Verdict {
    /// `bloom`'s chains, each level from the GPU's level before it.
    fn judge_bloom(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        gpu: &GpuSide<'_>,
    ) -> anyhow::Result<()> {
        if plan.runs(Pass::Bloom)
            && let (Some(((w, h), hdr)), Some(down), Some(up)) = (
                gpu.map(ResourceId::Hdr),
                gpu.texels(ResourceId::BloomDown),
                gpu.texels(ResourceId::BloomUp),
            )
        {
            for f in bloom_verdicts(scene, (w, h), hdr, down, up)? {
                self.lines.push(format!("  [{:<14}] {}", "bloom", f.line()));
                if !f.passed() {
                    self.failures.push(f.line());
                }
                self.json.push(f.to_json());
            }
            self.judged.extend(["bloom_down", "bloom_up"]);
        }
        Ok(())
    }

    /// The `waves` pass's maps, the foam field, and the shadow, reflection and refraction
    /// maps.
    fn judge_maps(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        gpu: &GpuSide<'_>,
    ) -> anyhow::Result<()> {
        for (id, f) in waves_verdicts(scene, plan, gpu)? {
            self.record("waves", id.name(), &f, "");
        }
        if let Some(f) = foam_verdict(scene, plan, gpu)? {
            self.record("foam", ResourceId::FoamField.name(), &f, "");
        }
        if let Some((f, ambiguous)) = shadow_verdict(scene, plan, gpu)? {
            let name = ResourceId::ShadowMap.name();
            self.record_ambiguous("shadow_map", name, &f, ambiguous, "coverage");
        }
        for map in [ObjectMap::Reflection, ObjectMap::Refraction] {
            if let Some((id, f, ambiguous)) = map_verdict(scene, plan, gpu, map)? {
                let what = "coverage or discard";
                self.record_ambiguous(id.name(), id.name(), &f, ambiguous, what);
            }
        }
        Ok(())
    }

    /// The spray's step from the pool the GPU held ([`spray::verdict`]); where the frame has
    /// a spray but no step was run (a dump), listed as not judged.
    fn judge_spray(&mut self, plan: &FramePlan, gpu: &GpuSide<'_>) -> anyhow::Result<()> {
        if !plan.runs(Pass::Spray) {
            return Ok(());
        }
        let probe = match gpu.spray {
            None => Err("no step of the pool was run on the device (the dump holds no spray step)"),
            // The step read the frame's displacement map: without it, nothing to judge from.
            Some(_) if plan.runs(Pass::Waves) && gpu.map(ResourceId::Displacement).is_none() => {
                Err("its input displacement is not in the frame")
            }
            Some(probe) => Ok(probe),
        };
        let probe = match probe {
            Ok(probe) => probe,
            Err(why) => {
                self.lines.push(format!(
                    "  [{:<14}] {:<20} not judged: {why}",
                    "spray", "spray_particles"
                ));
                self.json.push(json!({"name": "spray_particles", "tolerance": "envelope", "judged": false, "why": why}));
                self.not_judged.push("spray_particles");
                return Ok(());
            }
        };
        let f = spray::verdict(plan, gpu, probe)?;
        // A slot is two of the region's "pixels": its position and its velocity.
        let line = f.line().replacen(" pixels, ", " slot vec4s (two a slot), ", 1);
        self.lines.push(format!("  [{:<14}] {line}", "spray"));
        self.fail_region(&f, line);
        self.json.push(f.to_json());
        self.judged.push("spray_particles");
        Ok(())
    }

    /// `wave_mips`' chains, each level from the GPU's level before it.
    fn judge_wave_mips(&mut self, plan: &FramePlan, gpu: &GpuSide<'_>) -> anyhow::Result<()> {
        if plan.runs(Pass::WaveMips) {
            for (source, chain) in ResourceId::SLOPE_CHAINS {
                if let (Some(((w, h), src)), Some((_, atlas))) = (gpu.map(source), gpu.map(chain)) {
                    let f = wave_mips_verdict(chain, (w, h), src, atlas)?;
                    self.record("wave_mips", chain.name(), &f, "");
                }
            }
        }
        Ok(())
    }

    /// The Fresnel tables, and the far field's uploaded Fresnel filter.
    fn judge_fresnel(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        gpu: &GpuSide<'_>,
    ) -> anyhow::Result<()> {
        if plan.runs(Pass::FresnelTable) {
            let eta = scene.water.ior as f32;
            for (id, eta) in
                [(ResourceId::FresnelAbove, eta), (ResourceId::FresnelBelow, 1.0 / eta)]
            {
                let (Some(((w, _), texels)), Some(r)) = (gpu.map(id), plan.resource(id)) else {
                    continue;
                };
                let params = ocean_core::frame::FresnelTableUniforms::new(
                    eta,
                    r.size[0],
                    plan.fresnel_mapping,
                );
                let env = ocean_cpu::shaders::fresnel_table::envelope(&params);
                if env.len() != texels.len() {
                    bail!("{}: {} texels, the table {}", id.name(), texels.len(), env.len());
                }
                let f = ocean_verify::envelope::judge_floats(id.name(), &env, texels, w);
                self.record("fresnel_table", id.name(), &f, "");
            }
        }
        // The far field's Fresnel filter is computed on the CPU and uploaded: the GPU must
        // hold it bit for bit (an upload has no arithmetic to allow for).
        if let (Some(table), Some(((w, _), texels))) =
            (plan.fresnel_filter(scene), gpu.map(ResourceId::FresnelFilter))
        {
            let env: Vec<Option<[ocean_cpu::envelope::Iv; 4]>> =
                table.texels.iter().map(|t| Some(t.map(ocean_cpu::envelope::Iv::point))).collect();
            let f = if env.len() == texels.len() {
                ocean_verify::envelope::judge_floats("fresnel_filter", &env, texels, w)
            } else {
                bail!("fresnel_filter: {} texels, the table {}", texels.len(), env.len());
            };
            self.record("wave_mips", "fresnel_filter", &f, " (an upload: exact)");
        }
        Ok(())
    }

    /// The HDR frame's water pixels, or why they are not judged.
    fn judge_water(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        gpu: &GpuSide<'_>,
    ) -> anyhow::Result<()> {
        match water_verdict(scene, plan, gpu)? {
            Ok((f, open, took, widths)) => {
                let fmt = |x: Option<f64>| x.map_or("-".to_owned(), |x| format!("{x:.1e}"));
                let sprites = match widths.sprites {
                    Some(n) => format!("; {n} where a sprite may add light"),
                    None if plan.runs(Pass::Spray) => {
                        "; where a sprite may land left out (no pool read back)".to_owned()
                    }
                    None => String::new(),
                };
                let note = format!(
                    " ({} water pixels, rel half-width p50 {} / p99 {}; {} object pixels, p50 \
                     {}; {} where either may show{sprites}; {:.2} % open (the mesh's edges, or \
                     water or object); {} unbounded, not judged; {}; envelope {took:.1?})",
                    widths.pixels,
                    fmt(widths.p50),
                    fmt(widths.p99),
                    widths.objects,
                    fmt(widths.objects_p50),
                    widths.either,
                    100.0 * open,
                    widths.unbounded,
                    gpu.precision.1
                );
                self.lines.push(format!("  [{:<14}] {}{note}", "water", f.line()));
                self.fail_region(&f, f.line());
                let mut j = f.to_json();
                j["water_pixels"] = json!(widths.pixels);
                j["water_rel_half_width_p50"] = json!(widths.p50);
                j["water_rel_half_width_p99"] = json!(widths.p99);
                j["object_pixels"] = json!(widths.objects);
                j["object_rel_half_width_p50"] = json!(widths.objects_p50);
                j["either_pixels"] = json!(widths.either);
                j["unbounded_pixels"] = json!(widths.unbounded);
                j["sprite_pixels"] = json!(widths.sprites);
                j["open_share"] = json!(open);
                j["precision"] = json!(gpu.precision.1);
                self.json.push(j);
                self.judged.push("hdr");
            }
            Err(why) => {
                self.lines
                    .push(format!("  [{:<14}] {:<20} not judged: {why}", "water", "hdr (water)"));
                self.json.push(
                    json!({"name": "hdr (water)", "tolerance": "envelope", "judged": false, "why": why}),
                );
                // The resource's name, as the judged list has it, so that a scene whose water
                // is not judged does not hide another's that is.
                self.not_judged.push("hdr");
            }
        }
        Ok(())
    }

    /// The picture, against the `tonemap` envelope of the GPU's own HDR frame and bloom (not
    /// judged where the plan has no tonemap; a failure where the HDR frame or the picture is
    /// missing).
    fn judge_tonemap(
        &mut self,
        scene: &Scene,
        plan: &FramePlan,
        gpu: &GpuSide<'_>,
    ) -> anyhow::Result<()> {
        let Some(tonemap) = ocean_core::graph::tonemap_uniforms(scene, plan)? else {
            return Ok(());
        };
        let not_judged = |why: &str, v: &mut Verdict| {
            v.lines.push(format!("  [{:<14}] {:<20} not judged: {why}", "tonemap", "ldr"));
            v.json
                .push(json!({"name": "ldr", "tolerance": "envelope", "judged": false, "why": why}));
            v.not_judged.push("ldr");
        };
        let (Some(((w, h), hdr)), Some(ldr)) = (gpu.map(ResourceId::Hdr), gpu.ldr) else {
            not_judged("the GPU's HDR frame or picture is missing", self);
            self.failures.push("ldr: the GPU's HDR frame or picture is missing".to_owned());
            return Ok(());
        };
        let bloom = match (plan.runs(Pass::Bloom), gpu.texels(ResourceId::BloomUp)) {
            (false, _) => None,
            (true, Some(atlas)) => {
                let inputs = ocean_core::graph::BloomInputs::new(scene);
                Some(ocean_cpu::shaders::bloom::level0(&bloom_chain(
                    &inputs,
                    (w, h),
                    "bloom_up",
                    atlas,
                )?))
            }
            (true, None) => {
                not_judged("pass bloom's output (bloom_up) is not in the frame", self);
                return Ok(());
            }
        };
        let envelope =
            ocean_cpu::shaders::tonemap::envelope_of(hdr, bloom.as_ref(), w, h, &tonemap);
        let no_bloom = ocean_cpu::sampler::Texture2D::new(1, 1, vec![[0.0; 4]]);
        let exact = ocean_cpu::shaders::tonemap::tonemap_to_rgba8_with_bloom(
            hdr,
            w,
            h,
            &tonemap,
            bloom.as_ref().unwrap_or(&no_bloom),
        );
        let verdict = ocean_verify::envelope::judge_picture("ldr", &envelope, ldr, &exact, w);
        self.lines.push(format!("  [{:<14}] {}", "tonemap", verdict.line()));
        if !verdict.passed() {
            self.failures.push(verdict.line());
        }
        self.json.push(verdict.to_json());
        self.judged.push("ldr");
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ocean_cpu::envelope::Iv;
    use ocean_verify::envelope::judge_floats;

    /// A map whose every texel lies inside its envelope passes with 1.9 % of its texels
    /// ambiguous and fails with 2.1 % (the line, the failures and the JSON agree), as too
    /// ambiguous rather than outside; NaN fails. A value outside as well: not only too
    /// ambiguous.
    #[test]
    fn a_map_s_ambiguous_share_is_held_to_two_percent() {
        let env = [Some([Iv::new(0.0, 1.0); 4])];
        let f = judge_floats("reflection_map", &env, &[[0.5; 4]], 1);
        assert!(f.passed());
        let verdict = |share: f64| {
            let mut v = Verdict::default();
            v.record_ambiguous("reflection_map", "reflection_map", &f, share, "coverage");
            v
        };
        let held = verdict(0.019);
        assert!(held.passed() && !held.only_too_ambiguous(), "{:?}", held.failures);
        assert_eq!(held.json[0]["passed"], json!(true));
        assert!(held.lines[0].contains("1.90 % of texels' coverage ambiguous, at most 2 %"));
        for share in [0.021, f64::NAN] {
            let over = verdict(share);
            assert!(!over.passed() && over.failures.len() == 1, "{share}: {:?}", over.lines);
            assert!(over.only_too_ambiguous());
            assert_eq!(over.json[0]["passed"], json!(false));
            assert!(over.lines[0].contains("too many ambiguous texels FAIL"), "{}", over.lines[0]);
        }
        let out = judge_floats("reflection_map", &env, &[[1.5; 4]], 1);
        let mut both = Verdict::default();
        both.record_ambiguous("reflection_map", "reflection_map", &out, 0.5, "coverage");
        assert!(!both.passed() && !both.only_too_ambiguous(), "{:?}", both.failures);
    }
}
