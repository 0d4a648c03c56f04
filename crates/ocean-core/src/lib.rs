//! Physics and data of the `ocean` renderer, with no GPU: scene description, wave spectra,
//! dispersion, seeded random amplitudes, FFT wave synthesis (Tessendorf / Hu et al. 2004 eq. 1),
//! the exact Fresnel term (Hu et al. eq. 2) and the tables built from it, the Preetham daylight
//! sky, the view-dependent water mesh (near and far patches, §3), and what the render stages
//! share with the GPU: the embedded WGSL sources and the `#[repr(C)]` uniform structs.
//!
//! Conventions used throughout (one place):
//! - SI units: metres, seconds, radians. y is up, the mean sea plane is y = 0; the horizontal
//!   plane is (x, z).
//! - A wave field on a periodic patch of side `L` sampled on `N × N` points: sample (i, j) is at
//!   x = i·L/N, z = j·L/N. Wave vector of mode (n, m), n, m ∈ (−N/2, N/2): k = 2π(n, m)/L.
//!   Mode (n, m) is stored at FFT bin (n mod N, m mod N), row-major with z (m) the slow index:
//!   `index = (m mod N) · N + (n mod N)`; fields are stored the same way: `index = j · N + i`.
//! - h(x, t) = Σ_k h̃(k, t) exp(i k·x) — no 1/N² factor (it is folded into h̃), so an inverse
//!   FFT without normalisation computes it.

pub mod atmosphere;
pub mod bloom;
pub mod camera;
pub mod camera_uniforms;
pub mod clouds;
pub mod composite;
pub mod detail;
pub mod dispersion;
pub mod error;
pub mod far_field;
pub mod floating;
pub mod foam;
pub mod frame;
pub mod frame_format;
pub mod fresnel;
pub mod fuzz;
pub mod geometry;
pub mod ggx;
pub mod graph;
pub mod heightfield;
pub mod input;
mod kept;
pub mod mutants;
pub mod objects;
pub mod plan;
pub mod registry;
pub mod rng;
pub mod sand;
pub mod scene;
pub mod shader_source;
pub mod shoaling;
pub mod sizes;
pub mod sky;
pub mod solar;
pub mod spectrum;
pub mod spray;
pub mod stage;
pub mod supersample;
pub mod switch;
pub mod tables;
pub mod technique;
pub mod terrain;
pub mod tonemap;
pub mod waves;

pub use error::{Error, Result};

/// Standard gravity, m/s² (the value oceanographic parameterisations assume).
pub const GRAVITY: f64 = 9.81;
