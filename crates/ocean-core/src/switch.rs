//! A switch in the uniforms. A WGSL uniform block holds no `bool`, so an on/off choice is an
//! `f32` that is exactly [`SWITCH_ON`] or [`SWITCH_OFF`], and both back ends test it with
//! `==` against the named constant (WGSL `SWITCH_ON`/`SWITCH_OFF` in
//! `shaders/shared/frame.wgsl`, held equal to these by tests/wgsl.rs).

/// The switch is off.
pub const SWITCH_OFF: f32 = 0.0;
/// The switch is on.
pub const SWITCH_ON: f32 = 1.0;

/// `on` as a switch.
pub const fn switch(on: bool) -> f32 {
    if on { SWITCH_ON } else { SWITCH_OFF }
}
