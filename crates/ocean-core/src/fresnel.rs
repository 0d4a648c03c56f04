//! The exact Fresnel term (Hu et al. 2004, eq. 2). TO BE WRITTEN (helper: fresnel).
