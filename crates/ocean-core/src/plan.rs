//! The frame plan: which passes a scene needs, in order, and why each is in or out. Both back
//! ends run a [`FramePlan`] and never decide on their own (DESIGN.md, "Data flow").
//!
//! Every rule leaves out a pass whose contribution to the picture is exactly zero, so the
//! pruned frame is bit-identical to the full one:
//! - `waves`: no wind → a flat sea; the displacement and bump maps are all zero (and J = 1),
//!   which the water pass reads as such without sampling.
//! - `shadow_map`: it only darkens the sun's specular highlight (eq. 3's A_shadow); without a
//!   sun above the horizon there is no highlight, and without an object above the water
//!   nothing casts a shadow.
//! - `reflection_map`: holds the objects above the water, mirrored, with coverage in alpha;
//!   the sky is reflected analytically in the water pass. No object above the water → alpha
//!   is 0 everywhere → the map changes nothing.
//! - `refraction_map`: holds the objects under the water with eq. 4's fog, coverage in alpha;
//!   the water volume colour fills the rest. No object under the water → nothing to show.
//! - `objects`: no objects, no pass.
//! - `sky`: with the camera under the water the background is the water volume's colour (the
//!   frame is cleared to it); the sky is still seen through the surface (Snell's window), which
//!   the water pass evaluates analytically.
//! - `tonemap`: an EXR output keeps linear HDR.

use std::fmt;

use serde::Serialize;

use crate::scene::{Object, Scene, Shape};

/// A pass of the frame, named as in DESIGN.md (the name of its stage, or of the map an
/// object pass fills).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Pass {
    /// Displacement and bump maps of the sea at time t (stage `waves`).
    Waves,
    /// The 2D Fresnel texture (stage `fresnel_table`).
    FresnelTable,
    /// Depth of the objects seen from the sun (stage `shadow`).
    ShadowMap,
    /// Objects above the water, mirrored (stage `objects`, entry `vs_reflect`).
    ReflectionMap,
    /// Objects under the water, scaled and fogged (stage `objects`, entry `vs_refract`).
    RefractionMap,
    /// The sky behind everything (stage `sky`).
    Sky,
    /// The objects in the main view (stage `objects`).
    Objects,
    /// The water surface, eq. 3 (stage `water`).
    Water,
    /// HDR → 8-bit sRGB (stage `tonemap`).
    Tonemap,
}

impl Pass {
    /// Every pass, in execution order.
    pub const ALL: [Pass; 9] = [
        Pass::Waves,
        Pass::FresnelTable,
        Pass::ShadowMap,
        Pass::ReflectionMap,
        Pass::RefractionMap,
        Pass::Sky,
        Pass::Objects,
        Pass::Water,
        Pass::Tonemap,
    ];

    /// The pass's name in plans, labels and reports.
    pub fn name(self) -> &'static str {
        match self {
            Pass::Waves => "waves",
            Pass::FresnelTable => "fresnel_table",
            Pass::ShadowMap => "shadow_map",
            Pass::ReflectionMap => "reflection_map",
            Pass::RefractionMap => "refraction_map",
            Pass::Sky => "sky",
            Pass::Objects => "objects",
            Pass::Water => "water",
            Pass::Tonemap => "tonemap",
        }
    }
}

impl fmt::Display for Pass {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What the frame is written to: the tonemap pass runs only for 8-bit output.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputKind {
    /// 8-bit sRGB (PNG).
    Ldr,
    /// Linear HDR (EXR).
    Hdr,
}

/// A pass with the reason it is in or out of the plan.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct PlannedPass {
    /// Which pass.
    pub name: Pass,
    /// Why it runs or is skipped.
    pub reason: String,
}

/// The ordered passes of a frame and the ones left out.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct FramePlan {
    /// The passes to run, in order.
    pub passes: Vec<PlannedPass>,
    /// The passes left out, with why.
    pub skipped: Vec<PlannedPass>,
}

/// The vertical extent of an object, m.
fn y_range(o: &Object) -> (f64, f64) {
    let half = match o.shape() {
        Some(Shape::Sphere { radius }) => radius,
        Some(Shape::Box { size }) => 0.5 * size[1],
        None => 0.0,
    };
    (o.center[1] - half, o.center[1] + half)
}

impl FramePlan {
    /// The plan of a validated scene.
    pub fn new(scene: &Scene, output: OutputKind) -> Self {
        let above = scene.objects.iter().filter(|o| y_range(o).1 > 0.0).count();
        let below = scene.objects.iter().filter(|o| y_range(o).0 < 0.0).count();
        let sun_up = scene.sun.as_ref().is_some_and(|s| s.direction[1] > 0.0 && s.intensity > 0.0);
        let mut plan = FramePlan { passes: Vec::new(), skipped: Vec::new() };
        for pass in Pass::ALL {
            let (run, reason) = match pass {
                Pass::Waves => {
                    if scene.ocean.wind_speed > 0.0 {
                        (true, format!("wind {} m/s", scene.ocean.wind_speed))
                    } else {
                        (false, "no wind: the sea is flat".to_string())
                    }
                }
                Pass::FresnelTable => (true, "the water pass looks F up in it".into()),
                Pass::ShadowMap => match (sun_up, above) {
                    (false, _) => (false, "no sun above the horizon: no specular to shadow".into()),
                    (true, 0) => (false, "no object above the water casts a shadow".into()),
                    (true, n) => (true, format!("{n} object(s) above the water under the sun")),
                },
                Pass::ReflectionMap => match above {
                    0 => (false, "no object above the water: the sky alone is reflected".into()),
                    n => (true, format!("{n} object(s) above the water")),
                },
                Pass::RefractionMap => match below {
                    0 => (false, "nothing under the water: the water volume colour alone".into()),
                    n => (true, format!("{n} object(s) under the water")),
                },
                Pass::Sky => {
                    if scene.camera.position[1] < 0.0 {
                        (
                            false,
                            "camera under the water: the water volume fills the background".into(),
                        )
                    } else {
                        (true, "the background".into())
                    }
                }
                Pass::Objects => match scene.objects.len() {
                    0 => (false, "the scene has no objects".into()),
                    n => (true, format!("{n} object(s)")),
                },
                Pass::Water => (true, "the sea surface, eq. 3".into()),
                Pass::Tonemap => match output {
                    OutputKind::Ldr => (true, "8-bit sRGB output".into()),
                    OutputKind::Hdr => (false, "EXR output keeps linear HDR".into()),
                },
            };
            let planned = PlannedPass { name: pass, reason };
            if run { plan.passes.push(planned) } else { plan.skipped.push(planned) }
        }
        plan
    }

    /// Whether the plan runs a pass.
    pub fn runs(&self, pass: Pass) -> bool {
        self.passes.iter().any(|p| p.name == pass)
    }
}

impl fmt::Display for FramePlan {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for p in &self.passes {
            writeln!(f, "  run   {:<15} {}", p.name.name(), p.reason)?;
        }
        for p in &self.skipped {
            writeln!(f, "  skip  {:<15} {}", p.name.name(), p.reason)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{ObjectKind, Sun};

    fn sphere(y: f64) -> Object {
        Object {
            kind: ObjectKind::Sphere,
            center: [0.0, y, -10.0],
            radius: Some(1.0),
            size: None,
            color: [0.5; 3],
        }
    }

    #[test]
    fn builtin_scene_runs_every_pass_but_the_tonemap_for_exr() {
        let s = Scene::builtin();
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(p.skipped.is_empty(), "{p}");
        let names: Vec<_> = p.passes.iter().map(|p| p.name).collect();
        assert_eq!(names, Pass::ALL);
        let p = FramePlan::new(&s, OutputKind::Hdr);
        assert_eq!(p.skipped.len(), 1);
        assert!(!p.runs(Pass::Tonemap));
    }

    #[test]
    fn each_rule_fires() {
        let mut s = Scene::default();
        let p = FramePlan::new(&s, OutputKind::Ldr);
        for pass in [Pass::ShadowMap, Pass::ReflectionMap, Pass::RefractionMap, Pass::Objects] {
            assert!(!p.runs(pass), "{pass}");
        }
        s.objects = vec![sphere(5.0)];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(p.runs(Pass::ReflectionMap) && !p.runs(Pass::RefractionMap));
        assert!(!p.runs(Pass::ShadowMap), "no sun");
        s.sun = Some(Sun::default());
        assert!(FramePlan::new(&s, OutputKind::Ldr).runs(Pass::ShadowMap));
        s.sun = Some(Sun { direction: [0.0, -0.1, 1.0], ..Sun::default() });
        assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::ShadowMap), "sun below");
        s.objects = vec![sphere(-5.0)];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(!p.runs(Pass::ReflectionMap) && p.runs(Pass::RefractionMap));
        s.objects = vec![sphere(0.5)];
        let p = FramePlan::new(&s, OutputKind::Ldr);
        assert!(p.runs(Pass::ReflectionMap) && p.runs(Pass::RefractionMap), "straddles");
        s.ocean.wind_speed = 0.0;
        assert!(!FramePlan::new(&s, OutputKind::Ldr).runs(Pass::Waves));
    }
}
