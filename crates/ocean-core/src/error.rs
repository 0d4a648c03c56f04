//! The crate's error type.

/// Errors of `ocean-core`: each names what is wrong so that a user can act on it.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A physical or numerical parameter is outside the range where the model is defined.
    #[error("invalid {name} = {value}: {reason}")]
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
