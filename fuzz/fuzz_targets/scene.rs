//! Any bytes as a scene file: `ocean_core::fuzz::check_scene_text` must not panic (it panics
//! where an accepted scene breaks a property: plan, memory estimate, derived quantities,
//! TOML round trip).
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        let _ = ocean_core::fuzz::check_scene_text(text);
    }
});
