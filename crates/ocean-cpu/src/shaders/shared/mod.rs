//! Mirrors of `shaders/shared/*.wgsl`: functions several stages import.

pub mod camera;
pub mod coastal;
pub mod detail;
pub mod floor;
pub mod foam;
pub mod frame;
pub mod fresnel;
pub mod fullscreen;
pub mod gerstner;
pub mod optics;
pub mod preetham;
pub mod shadow;
pub mod sky_lut;
pub mod trig;
