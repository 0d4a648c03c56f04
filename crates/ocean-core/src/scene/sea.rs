//! The coastal sea a scene makes at a time: here, above the waves model, which then knows no
//! scene.

use super::Scene;

/// Waves technique `coastal`'s sea of `scene` at time `t` (s): its `[coastal]` waves over its
/// `[terrain]` (or the open sea's depth of `[chiu]` without one, as the shaders' floor).
///
/// # Errors
/// The scene's dispersion cannot be built, or a non-finite time.
pub fn coastal_sea(scene: &Scene, t: f64) -> crate::Result<crate::waves::coastal::CoastalSea> {
    finite_time(t)?;
    Ok(crate::waves::coastal::CoastalSea::new(
        &scene.coastal,
        scene.terrain.as_ref(),
        scene.chiu.open_sea_depth_m,
        &scene.ocean.dispersion()?,
        t,
    ))
}

/// `t` if finite: the waves summed per vertex take any finite time (their phases are reduced
/// in f64), and nothing else.
pub(crate) fn finite_time(t: f64) -> crate::Result<f64> {
    if t.is_finite() {
        return Ok(t);
    }
    Err(crate::Error::InvalidParameter {
        name: "time",
        value: t,
        reason: "the waves' time must be finite".into(),
    })
}
