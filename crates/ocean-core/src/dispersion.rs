//! Dispersion relation ω² = g k tanh(k h), with optional looping. TO BE WRITTEN (helper: spectrum).
