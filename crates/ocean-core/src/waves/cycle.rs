//! Cyclic playback (seed 000 §2.1: the samples "are played cyclically"): the maps of one loop
//! period, precomputed at enough instants to sample every wave above its temporal Nyquist
//! limit.
//!
//! With a looping dispersion every ω is a multiple M·ω₀ of ω₀ = 2π/T, so h(x, t) is
//! T-periodic and band-limited in time to the highest harmonic M_max of the modes present
//! (modes whose h̃ can be non-zero). F frames t_i = i·T/F sample it above the Nyquist limit
//! iff F > 2·M_max, i.e. F > ω_max·T/π; the cycle uses the smallest such F, 2·M_max + 1
//! (1 for a flat sea). Playback picks the nearest frame.

use super::modes::{WaveModes, check_time};
use super::synthesis::{MapFloat, Synthesizer, WaveMaps};
use crate::{Error, Result};

/// The most memory a [`FrameCycle`] may hold: 1 GiB of maps (frames × N² × 6 × size of T).
/// A 256² f32 cycle of 1000 frames is 1.5 GiB and is refused: lower the resolution, lengthen
/// the spectrum's cut-off or shorten the loop period.
pub const MAX_FRAME_CYCLE_BYTES: usize = 1 << 30;

/// The maps of one loop period at F evenly spaced instants.
#[derive(Clone, Debug)]
pub struct FrameCycle<T> {
    period_s: f64,
    frames: Vec<WaveMaps<T>>,
}

impl<T: MapFloat> FrameCycle<T> {
    /// The smallest frame count above the temporal Nyquist limit of `modes`: 2·M_max + 1.
    /// Errors if the dispersion does not loop.
    pub fn frame_count_for(modes: &WaveModes) -> Result<usize> {
        let harmonic = modes.max_loop_harmonic().ok_or_else(|| Error::InvalidParameter {
            name: "loop_period_s",
            value: modes.dispersion().loop_period_s,
            reason: "cyclic playback needs a loop period > 0".into(),
        })?;
        usize::try_from(harmonic)
            .ok()
            .and_then(|m| m.checked_mul(2))
            .and_then(|m| m.checked_add(1))
            .ok_or_else(|| Error::InvalidParameter {
                name: "loop_period_s",
                value: modes.dispersion().loop_period_s,
                reason: "the loop period is too long for a frame cycle".into(),
            })
    }

    /// Synthesises the frames of `modes` with choppiness λ. Errors if the dispersion does not
    /// loop, if the synthesizer's resolution differs, or if the frames would exceed
    /// [`MAX_FRAME_CYCLE_BYTES`].
    pub fn new(
        modes: &WaveModes,
        synthesizer: &mut Synthesizer<T>,
        choppiness: f64,
    ) -> Result<Self> {
        let count = Self::frame_count_for(modes)?;
        let n = modes.resolution();
        let bytes =
            count.checked_mul(n * n).and_then(|b| b.checked_mul(6 * std::mem::size_of::<T>()));
        if bytes.is_none_or(|b| b > MAX_FRAME_CYCLE_BYTES) {
            return Err(Error::InvalidParameter {
                name: "loop_period_s",
                value: modes.dispersion().loop_period_s,
                reason: format!(
                    "{count} frames of {n}² maps exceed the frame-cycle memory limit of \
                     {MAX_FRAME_CYCLE_BYTES} bytes"
                ),
            });
        }
        let period_s = modes.dispersion().loop_period_s;
        let frames = (0..count)
            .map(|i| synthesizer.synthesize(modes, frame_time(period_s, count, i), choppiness))
            .collect::<Result<Vec<_>>>()?;
        Ok(Self { period_s, frames })
    }

    /// The loop period T, seconds.
    pub fn period_s(&self) -> f64 {
        self.period_s
    }

    /// F.
    pub fn frame_count(&self) -> usize {
        self.frames.len()
    }

    /// The frames, frame i at t_i = i·T/F.
    pub fn frames(&self) -> &[WaveMaps<T>] {
        &self.frames
    }

    /// The time of frame i, i·T/F.
    pub fn frame_time(&self, i: usize) -> f64 {
        frame_time(self.period_s, self.frames.len(), i)
    }

    /// The frame nearest to t: round(F·(t mod T)/T) mod F, with t reduced modulo T in f64.
    /// A non-finite t gives frame 0.
    pub fn frame_index(&self, t: f64) -> usize {
        if check_time(t).is_err() {
            return 0;
        }
        let count = self.frames.len();
        let phase = t.rem_euclid(self.period_s) / self.period_s; // [0, 1]
        ((phase * count as f64).round() as usize) % count
    }

    /// The frame nearest to t (see [`FrameCycle::frame_index`]).
    pub fn frame_at(&self, t: f64) -> &WaveMaps<T> {
        &self.frames[self.frame_index(t)]
    }
}

fn frame_time(period_s: f64, count: usize, i: usize) -> f64 {
    period_s * i as f64 / count as f64
}
