//! The crate's error type.

/// Errors of `ocean-core`: each names what is wrong so that a user can act on it.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A physical or numerical parameter is outside the range where the model is defined.
    #[error("invalid {name} = {}: {reason}", number(*value))]
    InvalidParameter {
        /// The parameter's name as the user knows it (scene key or argument name).
        name: &'static str,
        /// The offending value.
        value: f64,
        /// What the allowed range is and why.
        reason: String,
    },
    /// A stage's WGSL source could not be assembled: unknown stage, unknown or cyclic
    /// `// #import`.
    #[error("WGSL source of stage `{stage}`: {reason}")]
    ShaderSource {
        /// The stage whose source was requested.
        stage: String,
        /// What is wrong.
        reason: String,
    },
}

/// Shorthand for results of this crate.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A number as a person reads it in a message: plain from 1e-4 to 1e7, in exponent notation
/// beyond (`1e300`, not three hundred digits).
pub fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
