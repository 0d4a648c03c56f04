//! FFT wave synthesis (seed 000 §2.1, Tessendorf 2001): random amplitudes h0(k), the maps of
//! eq. 1 by inverse FFT, the same sums evaluated directly, the height query on the displaced
//! surface, the displacement / bump map pair and cyclic playback.
//!
//! Grid layout, mode storage and the sign and normalisation of eq. 1 are the crate's (see
//! the crate root). Additionally, here:
//! - h0(k) = (ξ_r + iξ_i)·½·sqrt(F(k)Δk² w) and h̃(k, t) = h0(k)e^{iωt} + conj(h0(−k))e^{−iωt},
//!   so that E(h²) = Σ F Δk² w ([`WaveModes`]); ξ from [`crate::rng`], keyed by mode.
//! - k = 0 and the Nyquist row and column hold no wave ([`WaveModes`] says why).
//! - The multipliers of the derived fields and the choppy displacement's sign: [`synthesis`].
//! - Everything up to the FFT is f64; maps are f32 or f64 ([`MapFloat`]).

pub mod coastal;
pub mod cycle;
pub mod gerstner;
pub mod modes;
pub mod query;
pub mod sea;
pub mod surface;
pub mod synthesis;
pub mod uniforms;

pub use cycle::{FrameCycle, MAX_FRAME_CYCLE_BYTES};
pub use modes::{Band, MAX_RESOLUTION, Mode, ModeParams, WaveModes, signed_index};
pub use query::{
    INVERSION_TOLERANCE_REL, Inversion, MAX_INVERSION_ITERATIONS, SurfaceQuery, SurfaceSample,
    eval_direct, invert_displacement,
};
pub use sea::WaveSurface;
pub use surface::{OceanParams, OceanSurface};
pub use synthesis::{MapFloat, Synthesizer, WaveMaps};
