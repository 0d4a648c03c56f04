//! Tables precomputed from the Fresnel term. TO BE WRITTEN (helper: fresnel).
