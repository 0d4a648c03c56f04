//! Every WGSL stage parses and validates with naga (no GPU needed), the `shaders/` folder holds
//! the stages we expect and nothing that is not embedded, and every uniform struct's Rust layout
//! (size, field offsets) is the one naga computes for the WGSL declaration.

use std::mem::{offset_of, size_of};
use std::path::Path;

use naga::valid::{Capabilities, ValidationFlags, Validator};
use ocean_core::camera_uniforms::CameraUniforms;
use ocean_core::frame::{FrameUniforms, FresnelTableUniforms};
use ocean_core::shader_source::{STAGES, embedded_files, stage_source};
use ocean_core::sky::SkyUniforms;
use ocean_core::tonemap::TonemapUniforms;
use ocean_core::waves::uniforms::{FftPassUniforms, WaveModeData, WavesUniforms};

/// The stages written so far; a missing file is a failure, not a pass over fewer files.
const EXPECTED_STAGES: &[&str] =
    &["waves", "fresnel_table", "sky", "objects", "shadow", "water", "tonemap", "present"];

/// Compute stages and their entry points (named after what they do; `main` where a stage has
/// one); the others render (`vs_main`, `fs_main`).
const COMPUTE_STAGES: &[(&str, &[&str])] =
    &[("waves", &["spectrum", "fft_rows", "fft_columns", "pack"]), ("fresnel_table", &["main"])];

/// The stage's source, imports resolved, parsed and validated. Stages stay within WebGPU's
/// baseline: no optional capabilities.
fn module(stage: &str) -> naga::Module {
    let src = stage_source(stage).unwrap_or_else(|e| panic!("{e}"));
    let module = naga::front::wgsl::parse_str(&src)
        .unwrap_or_else(|e| panic!("{stage}.wgsl:\n{}", e.emit_to_string(&src)));
    Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(&module)
        .unwrap_or_else(|e| panic!("{stage}.wgsl does not validate:\n{}", e.emit_to_string(&src)));
    module
}

#[test]
fn every_stage_parses_and_validates() {
    let mut validated = Vec::new();
    for stage in STAGES {
        let m = module(stage);
        // Render and post stages have the two entry points the CPU mirrors are named after;
        // compute stages the entry points listed in COMPUTE_STAGES.
        let wanted: Vec<(&str, naga::ShaderStage)> =
            match COMPUTE_STAGES.iter().find(|(s, _)| s == stage) {
                Some((_, entries)) => {
                    entries.iter().map(|&e| (e, naga::ShaderStage::Compute)).collect()
                }
                None => vec![
                    ("vs_main", naga::ShaderStage::Vertex),
                    ("fs_main", naga::ShaderStage::Fragment),
                ],
            };
        for &(name, kind) in &wanted {
            assert!(
                m.entry_points.iter().any(|e| e.name == name && e.stage == kind),
                "{stage}.wgsl has no {kind:?} entry point `{name}`"
            );
        }
        validated.push(*stage);
    }
    for want in EXPECTED_STAGES {
        assert!(validated.contains(want), "stage {want} was not validated");
    }
}

#[test]
fn shaders_folder_holds_the_expected_stages_and_only_embedded_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
    let mut on_disk = Vec::new();
    for dir in [root.clone(), root.join("shared")] {
        for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "wgsl") {
                let rel = path.strip_prefix(&root).unwrap().to_string_lossy().replace('\\', "/");
                on_disk.push(rel);
            }
        }
    }
    for stage in EXPECTED_STAGES {
        let file = format!("{stage}.wgsl");
        assert!(on_disk.contains(&file), "shaders/{file} is missing");
        assert!(STAGES.contains(stage), "stage {stage} is not in shader_source::STAGES");
    }
    let embedded = embedded_files();
    for file in &on_disk {
        assert!(embedded.contains(file), "shaders/{file} is not embedded in shader_source");
    }
    for file in &embedded {
        assert!(on_disk.contains(file), "shader_source embeds {file}, which is not in shaders/");
        // The embedded text is the file's text (include_str! cannot go stale, but say it).
        if let Some(text) = ocean_core::shader_source::shared_file(file) {
            assert_eq!(text, std::fs::read_to_string(root.join(file)).unwrap(), "{file}");
        }
    }
}

/// Compares the Rust struct `T` with the WGSL struct `name` of `module`: same size as naga's
/// `span`, the same members in the same order, each at naga's offset. `fields` lists the Rust
/// fields as `(name, offset_of!(T, name))`.
fn check_layout<T>(
    module: &naga::Module,
    name: &str,
    fields: &[(&str, usize)],
) -> Result<(), String> {
    let (_, ty) = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(name))
        .ok_or_else(|| format!("no struct `{name}` in the WGSL"))?;
    let naga::TypeInner::Struct { members, span } = &ty.inner else {
        return Err(format!("`{name}` is not a struct in the WGSL"));
    };
    let mut errors = Vec::new();
    if *span as usize != size_of::<T>() {
        errors.push(format!("size: WGSL {span}, Rust {}", size_of::<T>()));
    }
    let wgsl: Vec<(&str, usize)> =
        members.iter().map(|m| (m.name.as_deref().unwrap_or("?"), m.offset as usize)).collect();
    if wgsl.len() != fields.len() {
        errors.push(format!("{} WGSL members, {} Rust fields", wgsl.len(), fields.len()));
    }
    for (i, (w, r)) in wgsl.iter().zip(fields).enumerate() {
        if w != r {
            errors.push(format!("member {i}: WGSL {} at {}, Rust {} at {}", w.0, w.1, r.0, r.1));
        }
    }
    if errors.is_empty() { Ok(()) } else { Err(format!("{name}: {}", errors.join("; "))) }
}

/// `check_layout` that fails the test.
fn assert_layout<T>(module: &naga::Module, name: &str, fields: &[(&str, usize)]) {
    if let Err(e) = check_layout::<T>(module, name, fields) {
        panic!("{e}");
    }
}

/// `(stringify!(field), offset_of!(T, field))` for each field.
macro_rules! fields {
    ($t:ty: $($f:ident),* $(,)?) => { &[$((stringify!($f), offset_of!($t, $f))),*] };
}

#[test]
fn camera_uniforms_layout() {
    assert_layout::<CameraUniforms>(
        &module("sky"),
        "CameraUniforms",
        fields!(CameraUniforms: view_proj, inv_view_proj, eye, viewport),
    );
}

#[test]
fn sky_uniforms_layout() {
    assert_layout::<SkyUniforms>(
        &module("sky"),
        "SkyUniforms",
        fields!(SkyUniforms: perez_a, perez_b, perez_c, perez_d, perez_e, zenith, perez_zenith,
            sun_direction, sun_radiance, sky_scale, cos_theta_min, sun_sin_inner, sun_sin_outer),
    );
}

#[test]
fn tonemap_uniforms_layout() {
    assert_layout::<TonemapUniforms>(
        &module("tonemap"),
        "TonemapUniforms",
        fields!(TonemapUniforms: exposure, pad0, pad1, pad2),
    );
}

/// Negative controls: the checker rejects a struct without its padding, with swapped fields,
/// with a field missing, and a name the WGSL does not have.
#[test]
fn layout_checker_rejects_wrong_structs() {
    #[repr(C)]
    struct NoPadding {
        exposure: f32,
    }
    #[repr(C)]
    struct Swapped {
        pad0: f32,
        exposure: f32,
        pad1: f32,
        pad2: f32,
    }
    #[repr(C)]
    struct VecWhereScalarsAre {
        perez_a: [f32; 4],
        rest: [[f32; 4]; 9],
        sky_scale: [f32; 4],
    }
    let tonemap = module("tonemap");
    let err = check_layout::<NoPadding>(&tonemap, "TonemapUniforms", fields!(NoPadding: exposure))
        .unwrap_err();
    assert!(err.contains("size: WGSL 16, Rust 4") && err.contains("4 WGSL members"), "{err}");
    let err = check_layout::<Swapped>(
        &tonemap,
        "TonemapUniforms",
        fields!(Swapped: pad0, exposure, pad1, pad2),
    )
    .unwrap_err();
    assert!(err.contains("member 0: WGSL exposure at 0, Rust pad0 at 0"), "{err}");
    let err = check_layout::<VecWhereScalarsAre>(
        &module("sky"),
        "SkyUniforms",
        fields!(VecWhereScalarsAre: perez_a, rest, sky_scale),
    )
    .unwrap_err();
    assert!(err.contains("size: WGSL 160, Rust 176"), "{err}");
    let err = check_layout::<NoPadding>(&tonemap, "NoSuchStruct", &[]).unwrap_err();
    assert!(err.contains("no struct `NoSuchStruct`"), "{err}");
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
fn frame_uniforms_layout() {
    for stage in ["objects", "shadow", "water"] {
        assert_layout::<FrameUniforms>(
            &module(stage),
            "FrameUniforms",
            fields!(FrameUniforms: view, sun, tiling, water, hu, passes, ambient),
        );
    }
}

#[test]
fn fresnel_table_uniforms_layout() {
    assert_layout::<FresnelTableUniforms>(
        &module("fresnel_table"),
        "FresnelTableUniforms",
        fields!(FresnelTableUniforms: eta, size, mapping, pad),
    );
}

#[test]
fn waves_uniforms_layout() {
    let waves = module("waves");
    assert_layout::<WavesUniforms>(
        &waves,
        "WavesUniforms",
        fields!(WavesUniforms: size, log2_size, time_ticks, time_remainder, lambda, pad0, pad1),
    );
    assert_layout::<FftPassUniforms>(
        &waves,
        "FftPassUniforms",
        fields!(FftPassUniforms: stage, pad0, pad1, pad2),
    );
    // The storage table's element: its size is the array stride.
    assert_layout::<WaveModeData>(
        &waves,
        "WaveMode",
        fields!(WaveModeData: h0, k, phase_rate, inv_k, frequency),
    );
}
