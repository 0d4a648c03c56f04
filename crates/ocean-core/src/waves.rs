//! FFT wave synthesis. TO BE WRITTEN (helper: waves).
