//! The stage registry against the WGSL (no GPU needed): every stage parses and validates with
//! naga; its entry points and bindings are exactly the registry's; every struct Rust shares
//! with WGSL has the same size and the same members (name, offset, type); every WGSL `const`
//! equals its Rust twin; every technique file implements its stage's interface; the
//! `shaders/` folder holds exactly the embedded files; and every piece the registry names
//! (WGSL, CPU mirror, GPU module) exists — with negative controls for each checker.

use std::path::{Path, PathBuf};

use naga::valid::{Capabilities, ValidationFlags, Validator};
use ocean_core::plan::Pass;
use ocean_core::plan::{System, Techniques};
use ocean_core::registry::{
    self, Block, EntryKind, SHARED, STAGES, StageEntry, TECHNIQUE_FILES, WAVE_MODE,
};
use ocean_core::shader_source::{embedded_files, stage_source, stage_source_with};

/// The stages written so far; a missing one is a failure, not a pass over fewer stages.
const EXPECTED_STAGES: &[&str] = &[
    "waves",
    "fresnel_table",
    "sky",
    "objects",
    "shadow",
    "water",
    "tonemap",
    "present",
    "composite",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn parse(name: &str, src: &str) -> naga::Module {
    let module = naga::front::wgsl::parse_str(src)
        .unwrap_or_else(|e| panic!("{name}:\n{}", e.emit_to_string(src)));
    Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{name} does not validate:\n{}", e.emit_to_string(src)));
    module
}

fn module(stage: &str) -> naga::Module {
    let src = stage_source(stage).unwrap_or_else(|e| panic!("{e}"));
    parse(&format!("{stage}.wgsl"), &src)
}

fn kind(k: EntryKind) -> naga::ShaderStage {
    match k {
        EntryKind::Vertex => naga::ShaderStage::Vertex,
        EntryKind::Fragment => naga::ShaderStage::Fragment,
        EntryKind::Compute => naga::ShaderStage::Compute,
    }
}

/// What differs between a stage's registry entry and its WGSL: entry points and bindings, in
/// both directions.
fn entry_and_binding_errors(stage: &StageEntry, m: &naga::Module) -> Vec<String> {
    let mut errors = Vec::new();
    for &(name, k) in stage.entry_points {
        if !m.entry_points.iter().any(|e| e.name == name && e.stage == kind(k)) {
            errors.push(format!("{}: no {k:?} entry point `{name}` in the WGSL", stage.name));
        }
    }
    for e in &m.entry_points {
        if stage.entry(&e.name).is_none() {
            errors.push(format!("{}: entry point `{}` is not in the registry", stage.name, e.name));
        }
    }
    let wgsl: Vec<(u32, u32, String)> = m
        .global_variables
        .iter()
        .filter_map(|(_, g)| {
            g.binding.as_ref().map(|b| (b.group, b.binding, g.name.clone().unwrap_or_default()))
        })
        .collect();
    for b in stage.bindings {
        if !wgsl.iter().any(|(g, n, name)| *g == b.group && *n == b.binding && name == b.name) {
            errors.push(format!(
                "{}: no @group({}) @binding({}) var {} in the WGSL",
                stage.name, b.group, b.binding, b.name
            ));
        }
    }
    for (g, n, name) in &wgsl {
        if !stage.bindings.iter().any(|b| b.group == *g && b.binding == *n && b.name == name) {
            errors.push(format!(
                "{}: @group({g}) @binding({n}) var {name} is not in the registry",
                stage.name
            ));
        }
    }
    errors
}

#[test]
fn every_stage_parses_validates_and_has_exactly_the_registrys_entry_points_and_bindings() {
    let mut errors = Vec::new();
    for stage in STAGES {
        errors.extend(entry_and_binding_errors(stage, &module(stage.name)));
    }
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    for want in EXPECTED_STAGES {
        assert!(registry::stage(want).is_some(), "stage {want} is not in the registry");
    }
}

#[test]
fn entry_and_binding_check_fails_on_a_wrong_registry_entry() {
    // Negative control: the water stage's entry with a renamed entry point and a binding moved.
    let water = *registry::stage("water").unwrap();
    let wrong = StageEntry {
        entry_points: &[("vs_main", EntryKind::Vertex), ("fs_water", EntryKind::Fragment)],
        bindings: &[registry::Binding { group: 0, binding: 0, name: "frames" }],
        ..water
    };
    let errors = entry_and_binding_errors(&wrong, &module("water")).join("\n");
    assert!(errors.contains("no Fragment entry point `fs_water`"), "{errors}");
    assert!(errors.contains("entry point `fs_main` is not in the registry"), "{errors}");
    assert!(errors.contains("var frames in the WGSL"), "{errors}");
    assert!(errors.contains("var displacement is not in the registry"), "{errors}");
}

/// The WGSL name of a naga type.
fn type_name(m: &naga::Module, ty: naga::Handle<naga::Type>) -> String {
    let t = &m.types[ty];
    if let Some(n) = &t.name {
        return n.clone();
    }
    let scalar = |s: naga::Scalar| match (s.kind, s.width) {
        (naga::ScalarKind::Float, 4) => "f32".to_owned(),
        (naga::ScalarKind::Uint, 4) => "u32".to_owned(),
        (naga::ScalarKind::Sint, 4) => "i32".to_owned(),
        other => format!("{other:?}"),
    };
    match &t.inner {
        naga::TypeInner::Scalar(s) => scalar(*s),
        naga::TypeInner::Vector { size, scalar: s } => {
            format!("vec{}<{}>", *size as u8, scalar(*s))
        }
        naga::TypeInner::Matrix { columns, rows, scalar: s } => {
            format!("mat{}x{}<{}>", *columns as u8, *rows as u8, scalar(*s))
        }
        naga::TypeInner::Array { base, size: naga::ArraySize::Constant(n), .. } => {
            format!("array<{}, {n}>", type_name(m, *base))
        }
        other => format!("{other:?}"),
    }
}

/// Compares a shared struct's Rust layout with the WGSL declaration in `m`: size, and each
/// member's name, offset and type.
fn check_block(m: &naga::Module, block: &Block) -> Result<(), String> {
    let name = block.name;
    let (_, ty) = m
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))
        .ok_or_else(|| format!("no struct `{name}` in the WGSL"))?;
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        return Err(format!("`{name}` is not a struct in the WGSL"));
    };
    let mut errors = Vec::new();
    if *span as usize != block.size {
        errors.push(format!("size: WGSL {span}, Rust {}", block.size));
    }
    let rust = (block.members)();
    if members.len() != rust.len() {
        errors.push(format!("{} WGSL members, {} Rust fields", members.len(), rust.len()));
    }
    for (i, (w, r)) in members.iter().zip(&rust).enumerate() {
        let (wn, wo, wt) =
            (w.name.as_deref().unwrap_or("?"), w.offset as usize, type_name(m, w.ty));
        if (wn, wo, wt.as_str()) != (r.name, r.offset, r.wgsl_type) {
            errors.push(format!(
                "member {i}: WGSL {wn}: {wt} at {wo}, Rust {}: {} at {}",
                r.name, r.wgsl_type, r.offset
            ));
        }
    }
    if errors.is_empty() { Ok(()) } else { Err(format!("{name}: {}", errors.join("; "))) }
}

#[test]
fn every_shared_struct_has_the_same_layout_and_member_types_in_rust_and_wgsl() {
    let mut errors = Vec::new();
    let mut checked = 0;
    for stage in STAGES {
        let m = module(stage.name);
        for b in stage.blocks {
            errors.extend(check_block(&m, b).err());
            checked += 1;
        }
    }
    // Shared and technique files are checked where a stage imports them.
    let importers = ["water", "sky"];
    for b in
        SHARED.iter().flat_map(|f| f.blocks).chain(TECHNIQUE_FILES.iter().flat_map(|f| f.blocks))
    {
        let m = importers
            .iter()
            .map(|s| module(s))
            .find(|m| m.types.iter().any(|(_, t)| t.name.as_deref() == Some(b.name)))
            .unwrap_or_else(|| panic!("no stage imports struct `{}`", b.name));
        errors.extend(check_block(&m, b).err());
        checked += 1;
    }
    errors.extend(check_block(&module("waves"), &WAVE_MODE).err());
    checked += 1;
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    // The 15 structs of the registry today: a check over fewer is a failure.
    assert!(checked >= 15, "only {checked} structs checked");
}

/// Negative controls: the checker rejects a struct without its padding, with swapped fields,
/// with a member of the wrong type, and a name the WGSL does not have.
#[test]
fn layout_checker_rejects_wrong_structs() {
    use ocean_core::registry::Member;
    let tonemap = module("tonemap");
    let block =
        |members: fn() -> Vec<Member>, size| Block { name: "TonemapUniforms", size, members };
    let err = check_block(
        &tonemap,
        &block(|| vec![Member { name: "exposure", offset: 0, wgsl_type: "f32" }], 4),
    )
    .unwrap_err();
    assert!(err.contains("size: WGSL 32, Rust 4") && err.contains("7 WGSL members"), "{err}");
    let swapped = || {
        vec![
            Member { name: "vignette", offset: 0, wgsl_type: "f32" },
            Member { name: "curve", offset: 4, wgsl_type: "u32" },
            Member { name: "exposure", offset: 8, wgsl_type: "f32" },
            Member { name: "inv_corner2", offset: 12, wgsl_type: "f32" },
            Member { name: "center", offset: 16, wgsl_type: "vec2<f32>" },
            Member { name: "bloom_scale", offset: 24, wgsl_type: "f32" },
            Member { name: "pad1", offset: 28, wgsl_type: "f32" },
        ]
    };
    let err = check_block(&tonemap, &block(swapped, 32)).unwrap_err();
    assert!(err.contains("member 0: WGSL exposure: f32 at 0, Rust vignette: f32 at 0"), "{err}");
    let wrong_type = || {
        vec![
            Member { name: "exposure", offset: 0, wgsl_type: "u32" },
            Member { name: "curve", offset: 4, wgsl_type: "u32" },
            Member { name: "vignette", offset: 8, wgsl_type: "f32" },
            Member { name: "inv_corner2", offset: 12, wgsl_type: "f32" },
            Member { name: "center", offset: 16, wgsl_type: "vec2<f32>" },
            Member { name: "bloom_scale", offset: 24, wgsl_type: "f32" },
            Member { name: "pad1", offset: 28, wgsl_type: "f32" },
        ]
    };
    let err = check_block(&tonemap, &block(wrong_type, 32)).unwrap_err();
    assert!(err.contains("WGSL exposure: f32 at 0, Rust exposure: u32 at 0"), "{err}");
    let err = check_block(&tonemap, &Block { name: "NoSuchStruct", size: 0, members: Vec::new })
        .unwrap_err();
    assert!(err.contains("no struct `NoSuchStruct`"), "{err}");
    // A nested block of the wrong type is caught by name.
    let frame = module("water");
    let nested_wrong = || {
        let mut v = (registry::SHARED[1].blocks.last().unwrap().members)();
        v[1].wgsl_type = "ViewBlock";
        v
    };
    let fu = Block {
        name: "FrameUniforms",
        size: std::mem::size_of::<ocean_core::frame::FrameUniforms>(),
        members: nested_wrong,
    };
    let err = check_block(&frame, &fu).unwrap_err();
    assert!(err.contains("WGSL sun: SunBlock"), "{err}");
}

/// Every WGSL `const` of every stage and its Rust twin (the CPU mirror's, or ocean-core's).
/// A WGSL constant not listed here fails: each one needs its twin.
fn rust_consts() -> Vec<(&'static str, f64)> {
    use ocean_cpu::shaders::shared::{floor, shadow};
    use ocean_cpu::shaders::{objects, shading::chiu, shared::optics, shared::preetham, tonemap};
    use ocean_cpu::shaders::{water, waves};
    vec![
        ("SHADOW_BIAS", f64::from(shadow::SHADOW_BIAS)),
        ("SWITCH_OFF", f64::from(ocean_core::switch::SWITCH_OFF)),
        ("SWITCH_ON", f64::from(ocean_core::switch::SWITCH_ON)),
        ("FAR_NONE", f64::from(ocean_core::far_field::FAR_NONE)),
        ("FAR_MIP", f64::from(ocean_core::far_field::FAR_MIP)),
        ("FAR_VARIANCE", f64::from(ocean_core::far_field::FAR_VARIANCE)),
        ("FOAM_NONE", f64::from(ocean_core::foam::FOAM_NONE)),
        ("FOAM_HEURISTIC", f64::from(ocean_core::foam::FOAM_HEURISTIC)),
        ("FOAM_JACOBIAN", f64::from(ocean_core::foam::FOAM_JACOBIAN)),
        ("FOAM_ACCUMULATED", f64::from(ocean_core::foam::FOAM_ACCUMULATED)),
        ("RELIEF_SHADOW_BIAS", f64::from(floor::RELIEF_SHADOW_BIAS)),
        ("COASTAL_SEGMENTS", f64::from(ocean_cpu::shaders::shared::coastal::COASTAL_SEGMENTS)),
        ("COASTAL_FILM_M", f64::from(ocean_cpu::shaders::shared::coastal::COASTAL_FILM_M)),
        ("COASTAL_EDGE_M", f64::from(ocean_cpu::shaders::shared::coastal::COASTAL_EDGE_M)),
        ("COASTAL_INV_PI", f64::from(ocean_cpu::shaders::shading::coastal::COASTAL_INV_PI)),
        ("EQ8_LN_R", f64::from(optics::EQ8_LN_R)),
        ("EQ8_LN_G", f64::from(optics::EQ8_LN_G)),
        ("EQ8_LN_B", f64::from(optics::EQ8_LN_B)),
        ("CHIU_MAX_EXPONENT", f64::from(chiu::CHIU_MAX_EXPONENT)),
        ("GGX_PI", f64::from(ocean_cpu::shaders::shading::ggx::GGX_PI)),
        ("FOAM_NOISE_PERIOD", f64::from(ocean_core::foam::FOAM_NOISE_PERIOD)),
        ("FOAM_INV_PI", f64::from(ocean_core::foam::FOAM_INV_PI)),
        ("FOAM_MIN_JACOBIAN", f64::from(ocean_core::foam::FOAM_MIN_JACOBIAN)),
        ("SKY_LUT_WIDTH", ocean_core::atmosphere::LUT_WIDTH as f64),
        ("SKY_LUT_HEIGHT", ocean_core::atmosphere::LUT_HEIGHT as f64),
        ("RAYLEIGH_PHASE_K", f64::from(ocean_cpu::shaders::shared::sky_lut::RAYLEIGH_PHASE_K)),
        ("MIE_G", f64::from(ocean_cpu::shaders::shared::sky_lut::MIE_G)),
        ("MIE_PHASE_K", f64::from(ocean_cpu::shaders::shared::sky_lut::MIE_PHASE_K)),
        ("CLOUD_PERIOD", f64::from(ocean_core::clouds::CLOUD_PERIOD)),
        ("CLOUD_OCTAVES", f64::from(ocean_core::clouds::CLOUD_OCTAVES)),
        ("CLOUD_HORIZON_GAIN", f64::from(ocean_core::clouds::CLOUD_HORIZON_GAIN)),
        ("SQRT2", f64::from(water::SQRT2)),
        ("VISIBLE_A_MIN", f64::from(water::VISIBLE_A_MIN)),
        ("VISIBLE_A_MAX", f64::from(water::VISIBLE_A_MAX)),
        ("EXP_MIN", f64::from(water::EXP_MIN)),
        ("HDR_MAX", f64::from(tonemap::HDR_MAX)),
        ("SRGB_INV_GAMMA", f64::from(tonemap::SRGB_INV_GAMMA)),
        ("BLOOM_HDR_MAX", f64::from(ocean_cpu::shaders::bloom::BLOOM_HDR_MAX)),
        ("HABLE_P", f64::from(tonemap::HABLE_P)),
        ("HABLE_Q", f64::from(tonemap::HABLE_Q)),
        ("HABLE_R", f64::from(tonemap::HABLE_R)),
        ("HABLE_S", f64::from(tonemap::HABLE_S)),
        ("HABLE_T", f64::from(tonemap::HABLE_T)),
        ("HABLE_WHITE_SCALE", f64::from(tonemap::HABLE_WHITE_SCALE)),
        ("TAU", f64::from(waves::TAU)),
        ("TURN_UNIT", f64::from(waves::TURN_UNIT)),
        ("FFT_SHARED_MAX", f64::from(ocean_core::waves::uniforms::FFT_SHARED_MAX)),
        ("FFT_SHARED_THREADS", f64::from(ocean_core::waves::uniforms::FFT_SHARED_THREADS)),
        ("FFT_KEPT_PER_ARRAY", f64::from(ocean_core::waves::uniforms::FFT_KEPT_PER_ARRAY)),
        ("WAVE_ARRAYS", f64::from(ocean_core::waves::uniforms::WAVE_ARRAYS)),
        ("MIN_CHROMATICITY_Y", f64::from(preetham::MIN_CHROMATICITY_Y)),
        ("INV_PI", f64::from(objects::INV_PI)),
        ("SIN_C3", f64::from(waves::SIN_C3)),
        ("SIN_C5", f64::from(waves::SIN_C5)),
        ("SIN_C7", f64::from(waves::SIN_C7)),
        ("SIN_C9", f64::from(waves::SIN_C9)),
        ("COS_C2", f64::from(waves::COS_C2)),
        ("COS_C4", f64::from(waves::COS_C4)),
        ("COS_C6", f64::from(waves::COS_C6)),
        ("COS_C8", f64::from(waves::COS_C8)),
        ("COS_C10", f64::from(waves::COS_C10)),
    ]
}

/// The named constants of `m` as f32 values.
fn wgsl_consts(m: &naga::Module) -> Vec<(String, f64)> {
    m.constants
        .iter()
        .filter_map(|(_, c)| {
            let name = c.name.clone()?;
            let v = match m.global_expressions[c.init] {
                naga::Expression::Literal(naga::Literal::F32(v)) => f64::from(v),
                naga::Expression::Literal(naga::Literal::U32(v)) => f64::from(v),
                naga::Expression::Literal(naga::Literal::I32(v)) => f64::from(v),
                naga::Expression::Literal(naga::Literal::AbstractFloat(v)) => v as f32 as f64,
                _ => f64::NAN,
            };
            Some((name, v))
        })
        .collect()
}

/// Every stage's module with the default techniques, and each composing stage once more for
/// every other available technique of the stages it imports.
fn composed_modules() -> Vec<(String, naga::Module)> {
    let mut out: Vec<_> = STAGES.iter().map(|s| (s.name.to_owned(), module(s.name))).collect();
    for t in TECHNIQUE_FILES {
        for (name, m) in modules_with(t) {
            out.push((format!("{name} with {}/{}", t.technique.stage, t.technique.name), m));
        }
    }
    out
}

/// The stages that import `technique/<t.stage>`, assembled with technique `t`.
fn modules_with(t: &registry::TechniqueFile) -> Vec<(String, naga::Module)> {
    let chosen = Techniques::with_overrides(System::Hu, [(t.technique.stage, t.technique.name)])
        .unwrap_or_else(|e| {
            panic!("{}: {e}", t.file);
        });
    let import = format!("// #import technique/{}", t.technique.stage);
    STAGES
        .iter()
        .filter(|s| s.source.contains(&import))
        .map(|s| {
            let src = stage_source_with(s.name, &chosen).unwrap_or_else(|e| panic!("{e}"));
            (s.name.to_owned(), parse(&format!("{} with {}", s.file, t.file), &src))
        })
        .collect()
}

fn const_errors(rust: &[(&str, f64)]) -> Vec<String> {
    let mut errors = Vec::new();
    for (stage, m) in composed_modules() {
        for (name, v) in wgsl_consts(&m) {
            match rust.iter().find(|(n, _)| *n == name) {
                // Both are f32 values: equal bits, not a tolerance.
                Some((_, r)) if (*r as f32).to_bits() == (v as f32).to_bits() => {}
                Some((_, r)) => errors.push(format!("{stage}: {name} = {v} in WGSL, {r} in Rust")),
                None => errors.push(format!("{stage}: const {name} has no Rust twin")),
            }
        }
    }
    errors
}

#[test]
fn every_wgsl_const_equals_its_rust_twin() {
    let errors = const_errors(&rust_consts());
    assert!(errors.is_empty(), "{}", errors.join("\n"));
    // Negative controls: one ULP off, and a constant left out.
    let mut off = rust_consts();
    off[0].1 = f64::from(f32::from_bits((off[0].1 as f32).to_bits() + 1));
    let e = const_errors(&off).join("\n");
    assert!(e.contains("SHADOW_BIAS = 0.002"), "{e}");
    let e = const_errors(&rust_consts()[1..]).join("\n");
    assert!(e.contains("const SHADOW_BIAS has no Rust twin"), "{e}");
}

#[test]
fn every_technique_file_implements_its_stages_interface() {
    for t in TECHNIQUE_FILES {
        // Each stage that imports the technique's stage, assembled with it, validates; the
        // interface is defined by the technique's own file.
        let stages = modules_with(t);
        assert!(!stages.is_empty(), "{}: no stage imports technique/{}", t.file, t.technique.stage);
        for name in t.interface {
            let own = t.source.contains(&format!("fn {name}("))
                || t.source.contains(&format!("struct {name} "));
            assert!(own, "{}: the {} interface needs `{name}`", t.file, t.technique.stage);
            for (stage, m) in &stages {
                let found = m.functions.iter().any(|(_, f)| f.name.as_deref() == Some(name))
                    || m.types.iter().any(|(_, ty)| ty.name.as_deref() == Some(name));
                assert!(found, "{stage} with {}: `{name}` is missing", t.file);
            }
        }
    }
    // Negative control: a stage assembled with a technique file that lacks the interface's
    // function has none.
    let src = stage_source_with("sky", &Techniques::of_system(System::Hu)).unwrap();
    assert!(src.contains("fn sky_radiance("));
    let stripped = src.replace("sky_radiance(", "sky_renamed(");
    let m = parse("stripped", &stripped);
    assert!(!m.functions.iter().any(|(_, f)| f.name.as_deref() == Some("sky_radiance")));
}

#[test]
fn the_registry_names_no_missing_piece_and_a_fake_entry_is_caught() {
    let missing = registry::missing_pieces(&root(), STAGES, SHARED, TECHNIQUE_FILES);
    assert!(missing.is_empty(), "{}", missing.join("\n"));
    // Negative control: a stage added to the registry without its WGSL, CPU mirror or GPU
    // module; a technique file without its mirror.
    let fake = StageEntry {
        name: "no_such_stage",
        file: "no_such_stage.wgsl",
        source: "",
        entry_points: &[],
        bindings: &[],
        blocks: &[],
        cpu_mirror: "crates/ocean-cpu/src/shaders/no_such_stage.rs",
        gpu_module: "crates/ocean-gpu/src/no_such_stage.rs",
    };
    let mut stages = STAGES.to_vec();
    stages.push(fake);
    let fake_tech = registry::TechniqueFile {
        technique: &ocean_core::plan::TechniqueInfo {
            stage: ocean_core::plan::Stage::Sky,
            name: "no_such_sky",
            source: "a technique added to the registry without its files",
        },
        file: "sky/no_such_sky.wgsl",
        cpu_mirror: "crates/ocean-cpu/src/shaders/sky/no_such_sky.rs",
        ..TECHNIQUE_FILES[0]
    };
    let mut techs = TECHNIQUE_FILES.to_vec();
    techs.push(fake_tech);
    let missing = registry::missing_pieces(&root(), &stages, SHARED, &techs).join("\n");
    for want in [
        "stage `no_such_stage`: its WGSL: shaders/no_such_stage.wgsl is missing",
        "stage `no_such_stage`: its CPU mirror: crates/ocean-cpu/src/shaders/no_such_stage.rs is \
         missing",
        "stage `no_such_stage`: its GPU module: crates/ocean-gpu/src/no_such_stage.rs is missing",
        "technique sky/no_such_sky: its WGSL: shaders/sky/no_such_sky.wgsl is missing",
        "technique sky/no_such_sky: its CPU mirror",
    ] {
        assert!(missing.contains(want), "wanted `{want}` in:\n{missing}");
    }
    // A sky technique of the table with no file is caught too.
    let missing = registry::missing_pieces(&root(), STAGES, SHARED, &[]).join("\n");
    assert!(
        missing.contains("technique sky/preetham: in the table but not in the registry"),
        "{missing}"
    );
}

#[test]
fn every_pass_of_the_plan_runs_a_registered_stage() {
    for pass in Pass::ALL {
        if let Some(shader) = pass.shader() {
            assert!(
                registry::stage(shader).is_some(),
                "{pass}: stage `{shader}` is not registered"
            );
        }
    }
}

fn wgsl_files(dir: &Path, root: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.expect("a readable entry").path();
        if path.is_dir() {
            wgsl_files(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            out.push(
                path.strip_prefix(root)
                    .expect("below shaders/")
                    .to_string_lossy()
                    .replace('\\', "/"),
            );
        }
    }
}

#[test]
fn shaders_folder_holds_exactly_the_embedded_files() {
    let dir = root().join("shaders");
    let mut on_disk = Vec::new();
    wgsl_files(&dir, &dir, &mut on_disk);
    let embedded = embedded_files();
    for file in &on_disk {
        assert!(embedded.contains(file), "shaders/{file} is not in the registry");
    }
    for file in &embedded {
        assert!(on_disk.contains(file), "the registry embeds {file}, which is not in shaders/");
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let stored = STAGES
            .iter()
            .find(|s| s.file == file)
            .map(|s| s.source)
            .or_else(|| ocean_core::shader_source::shared_file(file))
            .unwrap();
        assert_eq!(stored, text, "{file}: the embedded text is stale");
    }
}

/// A broken source fails validation: the validator is not a rubber stamp.
#[test]
fn validator_rejects_a_broken_shader() {
    let src = stage_source("tonemap")
        .unwrap()
        .replace("let encoded = srgb_oetf(mapped);", "let encoded = srgb_oetf(1.0);");
    let module = naga::front::wgsl::parse_str(&src);
    let rejected = match module {
        Err(_) => true,
        Ok(m) => {
            Validator::new(ValidationFlags::all(), Capabilities::empty()).validate(&m).is_err()
        }
    };
    assert!(rejected, "a type error in tonemap.wgsl was accepted");
}

#[test]
fn the_water_shader_reads_the_sky_through_the_technique_interface() {
    let water = registry::stage("water").unwrap().source;
    assert!(!water.to_lowercase().contains("import shared/preetham"), "water imports a sky model");
    assert!(water.contains("// #import technique/sky"));
    // Assembled for hu, the technique's file is in.
    assert!(stage_source("water").unwrap().contains("// ---- begin sky/preetham.wgsl"));
}
