//! The technique axis (docs/design.md, "Systems and techniques"): a **stage** is one step of the
//! frame, a **technique** one way to do it, a **system** one seed paper's choice of technique
//! per stage. This file is the one table of both; `ocean plan` prints it, the scene's
//! `system` and `[techniques]` keys choose from it, and the planner turns the choice into
//! passes.
//!
//! A technique that is listed but not built yet is `available: false`: choosing it (or a
//! system that needs it) is an error that names it, never a silent fallback to another.

use std::fmt;

use crate::frame_format::FrameFormat;
use serde::{Deserialize, Serialize};

/// A stage of the technique table, in docs/design.md's order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Stage {
    /// The sea's displacement and slopes.
    Waves,
    /// The mesh the waves displace.
    Surface,
    /// The water's shading.
    Shading,
    /// The sky model (the environment the water reflects).
    Sky,
    /// What becomes of the detail a pixel cannot resolve.
    FarField,
    /// White water.
    Foam,
    /// Spray particles.
    Spray,
    /// HDR → display.
    Post,
}

impl Stage {
    /// Every stage, in order.
    pub const ALL: [Stage; 8] = [
        Stage::Waves,
        Stage::Surface,
        Stage::Shading,
        Stage::Sky,
        Stage::FarField,
        Stage::Foam,
        Stage::Spray,
        Stage::Post,
    ];

    /// The stage's name: the scene key under `[techniques]`.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Waves => "waves",
            Stage::Surface => "surface",
            Stage::Shading => "shading",
            Stage::Sky => "sky",
            Stage::FarField => "far_field",
            Stage::Foam => "foam",
            Stage::Spray => "spray",
            Stage::Post => "post",
        }
    }

    /// The techniques of this stage, in the table's order.
    pub fn techniques(self) -> impl Iterator<Item = &'static TechniqueInfo> {
        TECHNIQUES.iter().filter(move |t| t.stage == self)
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One technique of one stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TechniqueInfo {
    /// Its stage.
    pub stage: Stage,
    /// Its name: the scene value, and the file name at every layer
    /// (`shaders/<stage>/<name>.wgsl`, `ocean-cpu/src/shaders/<stage>/<name>.rs`).
    pub name: &'static str,
    /// Where it comes from (seed number, paper).
    pub source: &'static str,
    /// Whether both back ends implement it.
    pub available: bool,
}

const fn t(
    stage: Stage,
    name: &'static str,
    source: &'static str,
    available: bool,
) -> TechniqueInfo {
    TechniqueInfo { stage, name, source, available }
}

/// Every technique of every stage (docs/design.md's table).
pub const TECHNIQUES: &[TechniqueInfo] = &[
    t(Stage::Waves, "fft", "Tessendorf spectrum → displacement + bump maps (seed 000)", true),
    t(Stage::Waves, "gerstner", "sum of Gerstner waves, per vertex (seed 002)", true),
    t(Stage::Waves, "coastal", "radial waves running to a shore, per vertex (seed 004)", true),
    t(Stage::Surface, "hu_patches", "near LOD tree + far conic patch (seed 000 §3)", true),
    t(Stage::Surface, "projected_grid", "projected grid (seed 001)", true),
    t(Stage::Surface, "clipmap", "GPU clipmaps, morphed, to the horizon (seed 002)", true),
    t(
        Stage::Surface,
        "shore_grid",
        "camera-aligned grid, rows of equal screen height (seed 004)",
        true,
    ),
    t(Stage::Shading, "hu", "eq. 3: 2D Fresnel texture + Phong (seed 000)", true),
    t(Stage::Shading, "chiu", "local optics and water colour, eqs. 2–8 (seed 001)", true),
    t(Stage::Shading, "ggx", "Cook–Torrance: GGX, Smith G, exact Fresnel (seed 002)", true),
    t(
        Stage::Shading,
        "coastal",
        "Blinn–Phong, Schlick or exact Fresnel, dull colour (seed 004)",
        true,
    ),
    t(Stage::Sky, "preetham", "Preetham et al. 1999 daylight", true),
    t(Stage::Sky, "preetham_clouds", "Preetham + clouds (seed 001 eq. 4)", true),
    t(Stage::Sky, "atmosphere", "Rayleigh/Mie scattering (seed 002)", true),
    t(Stage::FarField, "none", "point-sampled wave maps", true),
    t(Stage::FarField, "mip", "mip-mapped slope maps, trilinear at the footprint", true),
    t(Stage::FarField, "variance", "unresolved slope variance in the BRDF (Bruneton 2010)", true),
    t(Stage::Foam, "none", "no foam", true),
    t(Stage::Foam, "heuristic", "from normal and height (seed 002)", true),
    t(Stage::Foam, "jacobian", "where the Jacobian folds", true),
    t(Stage::Foam, "accumulated", "grows where J < threshold, decays over time", true),
    t(Stage::Spray, "none", "no spray", true),
    t(Stage::Spray, "particles", "state-preserving GPU particles (seed 001)", true),
    t(
        Stage::Post,
        "tonemap",
        "exposure, [post] vignette, ACES or Hable filmic curve → 8-bit sRGB",
        true,
    ),
    t(
        Stage::Post,
        "bloom",
        "bright pass + blur pyramid added before the tonemap (seed 002, Jimenez 2014)",
        true,
    ),
    // docs/design.md's third post technique, `vignette`, is the `[post] vignette` key of the final
    // pass instead: a per-pixel multiply needs no pass of its own, and as a key it combines
    // with either technique.
];

/// Whether waves technique `name` is summed per vertex and per fragment in the water pass
/// (`gerstner`, `coastal`): no wave maps, no waves pass, the height query from the sum.
pub fn waves_per_vertex(name: &str) -> bool {
    matches!(name, "gerstner" | "coastal")
}

/// The technique `name` of `stage`, if the table has it.
pub fn technique(stage: Stage, name: &str) -> Option<&'static TechniqueInfo> {
    stage.techniques().find(|t| t.name == name)
}

/// A seed paper's system.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum System {
    /// Hu, Velho, Tong, Guo & Shum 2004 (seed 000), the default.
    #[default]
    Hu,
    /// Chiu & Chang (seed 001).
    Chiu,
    /// Welch 2019 (seed 002).
    Welch,
    /// The coastal-wave shader (seed 004).
    Coastal,
}

/// A system's row of the table.
#[derive(Clone, Copy, Debug)]
pub struct SystemInfo {
    /// Which system.
    pub system: System,
    /// Its name (`--system`, the scene's `system`).
    pub name: &'static str,
    /// The paper.
    pub paper: &'static str,
    /// Its technique per stage, in [`Stage::ALL`] order.
    pub techniques: [&'static str; 8],
    /// The format of its frame's colour buffers where the scene does not choose one.
    pub frame_format: crate::frame_format::FrameFormat,
}

/// The systems, one per seed paper (docs/design.md). A stage a paper does not name keeps the
/// neutral technique (`none`, `tonemap`).
pub const SYSTEMS: &[SystemInfo] = &[
    SystemInfo {
        system: System::Hu,
        name: "hu",
        paper: "Hu, Velho, Tong, Guo & Shum 2004 (seed 000)",
        techniques: ["fft", "hu_patches", "hu", "preetham", "variance", "none", "none", "tonemap"],
        frame_format: FrameFormat::Rgba32Float,
    },
    SystemInfo {
        system: System::Chiu,
        name: "chiu",
        paper: "Chiu & Chang (seed 001)",
        techniques: [
            "fft",
            "projected_grid",
            "chiu",
            "preetham_clouds",
            // The paper point-samples; its far sea then sparkles (issue 12), and the mip-mapped
            // slopes are the filtering its shading can take (it has no variance term).
            "mip",
            "none",
            "particles",
            "tonemap",
        ],
        frame_format: FrameFormat::Rgba32Float,
    },
    SystemInfo {
        system: System::Welch,
        name: "welch",
        paper: "Welch 2019 (seed 002)",
        techniques: [
            "gerstner",
            "clipmap",
            "ggx",
            "atmosphere",
            // The paper takes the waves' slopes as they are; its far sea then sparkles, and
            // far field `mip` is the Gerstner waves' analytic footprint filter (the maps'
            // `variance` needs chains the Gerstner waves do not have).
            "mip",
            "heuristic",
            "none",
            "bloom",
        ],
        // "works with 16-bit precision floats in all the frame buffers" (seed 002 §post).
        frame_format: FrameFormat::Rgba16Float,
    },
    SystemInfo {
        system: System::Coastal,
        name: "coastal",
        paper: "the coastal-wave shader (seed 004)",
        techniques: [
            "coastal",
            "shore_grid",
            "coastal",
            "preetham",
            // The seed filters nothing; its far sea would sparkle, and far field `mip` is the
            // coastal waves' analytic footprint filter (as the Gerstner waves').
            "mip",
            "heuristic",
            "none",
            "tonemap",
        ],
        frame_format: FrameFormat::Rgba32Float,
    },
];

// The rows of `SYSTEMS` are in `System::ALL`'s order, which `System::info` indexes by: checked
// when the crate compiles.
const _: () = {
    let mut i = 0;
    while i < System::ALL.len() {
        assert!(SYSTEMS[i].system as usize == System::ALL[i] as usize, "SYSTEMS out of order");
        i += 1;
    }
};

impl System {
    /// Every system, in the table's order.
    pub const ALL: [System; 4] = [System::Hu, System::Chiu, System::Welch, System::Coastal];

    /// The system's row.
    pub fn info(self) -> &'static SystemInfo {
        // An exhaustive match: a new system fails to compile until it has its row (the rows'
        // order is checked when the crate compiles, below `SYSTEMS`).
        &SYSTEMS[match self {
            System::Hu => 0,
            System::Chiu => 1,
            System::Welch => 2,
            System::Coastal => 3,
        }]
    }

    /// Its name.
    pub fn name(self) -> &'static str {
        self.info().name
    }

    /// The system called `name`, or an error that lists the known ones.
    ///
    /// # Errors
    /// [`TechniqueError::UnknownSystem`].
    pub fn from_name(name: &str) -> Result<System, TechniqueError> {
        SYSTEMS
            .iter()
            .find(|s| s.name == name)
            .map(|s| s.system)
            .ok_or_else(|| TechniqueError::UnknownSystem { name: name.to_owned() })
    }

    /// Whether every technique the system names is available.
    pub fn available(self) -> bool {
        Techniques::of_system(self).missing().is_none()
    }
}

impl fmt::Display for System {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a choice of system or technique cannot be rendered.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum TechniqueError {
    /// No such system.
    #[error("unknown system `{name}` (known: {})", known_systems())]
    UnknownSystem {
        /// The name asked for.
        name: String,
    },
    /// No such technique for the stage.
    #[error("unknown technique `{name}` for stage `{stage}` (known: {})", known_techniques(*stage))]
    UnknownTechnique {
        /// The stage.
        stage: Stage,
        /// The name asked for.
        name: String,
    },
    /// The technique is listed but not built yet.
    #[error(
        "{what} needs {stage} technique `{name}`, which is not yet available (available for \
         {stage}: {}; systems available: {})",
        available_techniques(*stage),
        available_systems()
    )]
    NotAvailable {
        /// The system or key that asked for it.
        what: String,
        /// The stage.
        stage: Stage,
        /// The technique.
        name: &'static str,
    },
    /// Two chosen techniques that cannot work together.
    #[error("{stage_a} technique `{a}` cannot work with {stage_b} technique `{b}`: {why}")]
    Incompatible {
        /// The first stage.
        stage_a: Stage,
        /// Its technique.
        a: &'static str,
        /// The second stage (the one to change).
        stage_b: Stage,
        /// Its technique.
        b: &'static str,
        /// Why, and what to choose instead.
        why: &'static str,
    },
}

/// Pairs of techniques that cannot work together: (stage, technique, stage, technique, why).
const INCOMPATIBLE: &[(Stage, &str, Stage, &str, &str)] = &[(
    Stage::Waves,
    "gerstner",
    Stage::FarField,
    "variance",
    "the Gerstner waves' slopes are filtered analytically, with no maps, and `variance` needs \
     the maps' chains for its filtered Fresnel table; choose far_field = \"mip\" (the analytic \
     filter) or \"none\"",
)];

/// "hu, chiu (not yet available), …".
pub fn known_systems() -> String {
    SYSTEMS
        .iter()
        .map(|s| {
            if s.system.available() {
                s.name.to_owned()
            } else {
                format!("{} (not yet available)", s.name)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

fn available_systems() -> String {
    let names: Vec<_> = SYSTEMS.iter().filter(|s| s.system.available()).map(|s| s.name).collect();
    names.join(", ")
}

fn known_techniques(stage: Stage) -> String {
    let names: Vec<_> = stage
        .techniques()
        .map(|t| {
            if t.available { t.name.to_owned() } else { format!("{} (not yet available)", t.name) }
        })
        .collect();
    names.join(", ")
}

fn available_techniques(stage: Stage) -> String {
    let names: Vec<_> = stage.techniques().filter(|t| t.available).map(|t| t.name).collect();
    names.join(", ")
}

/// The technique chosen for each stage of a frame: the system's row with the scene's
/// `[techniques]` overrides applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Techniques {
    /// The system the choice starts from.
    pub system: System,
    chosen: [&'static TechniqueInfo; 8],
    overridden: [bool; 8],
}

impl Techniques {
    /// The system's own choice.
    pub fn of_system(system: System) -> Self {
        let row = system.info();
        let chosen = std::array::from_fn(|i| {
            // A static table, not input: every name of a row is checked by this module's
            // tests, and a wrong one fails loudly here rather than choosing another technique.
            technique(Stage::ALL[i], row.techniques[i]).unwrap_or_else(|| {
                panic!(
                    "system {}'s {} `{}` is not a technique",
                    row.name,
                    Stage::ALL[i].name(),
                    row.techniques[i]
                )
            })
        });
        Self { system, chosen, overridden: [false; 8] }
    }

    /// The system's choice with `overrides` (stage → technique name) applied.
    ///
    /// # Errors
    /// [`TechniqueError::UnknownTechnique`] for a name the stage does not have.
    pub fn with_overrides<'a>(
        system: System,
        overrides: impl IntoIterator<Item = (Stage, &'a str)>,
    ) -> Result<Self, TechniqueError> {
        let mut t = Self::of_system(system);
        for (stage, name) in overrides {
            let info = technique(stage, name)
                .ok_or_else(|| TechniqueError::UnknownTechnique { stage, name: name.to_owned() })?;
            let i = stage as usize;
            t.chosen[i] = info;
            t.overridden[i] = true;
        }
        Ok(t)
    }

    /// The technique of `stage`.
    pub fn of(&self, stage: Stage) -> &'static TechniqueInfo {
        self.chosen[stage as usize]
    }

    /// Whether the scene chose `stage`'s technique (rather than the system).
    pub fn is_overridden(&self, stage: Stage) -> bool {
        self.overridden[stage as usize]
    }

    /// This choice with `stage` set to a technique that is listed but not built, so tests can
    /// reach the "not yet available" paths now that every listed technique is built.
    #[cfg(test)]
    pub(crate) fn with_unbuilt(mut self, stage: Stage, overridden: bool) -> Self {
        let info = Box::leak(Box::new(t(stage, "unbuilt", "test", false)));
        self.chosen[stage as usize] = info;
        self.overridden[stage as usize] = overridden;
        self
    }

    /// Every (stage, technique), in stage order.
    pub fn iter(&self) -> impl Iterator<Item = (Stage, &'static TechniqueInfo)> + '_ {
        Stage::ALL.into_iter().map(|s| (s, self.of(s)))
    }

    /// The first chosen technique that is not available, as the error that names it.
    pub fn missing(&self) -> Option<TechniqueError> {
        self.iter().find(|(_, t)| !t.available).map(|(stage, t)| TechniqueError::NotAvailable {
            what: if self.is_overridden(stage) {
                format!("techniques.{stage}")
            } else {
                format!("system `{}`", self.system)
            },
            stage,
            name: t.name,
        })
    }

    /// Checks that the choice can be rendered: every technique available, and no pair that
    /// cannot work together.
    ///
    /// # Errors
    /// [`TechniqueError::NotAvailable`] naming the first technique that is not built, or
    /// [`TechniqueError::Incompatible`] naming both techniques of a pair.
    pub fn check(&self) -> Result<(), TechniqueError> {
        if let Some(e) = self.missing() {
            return Err(e);
        }
        for &(stage_a, a, stage_b, b, why) in INCOMPATIBLE {
            if self.of(stage_a).name == a && self.of(stage_b).name == b {
                return Err(TechniqueError::Incompatible { stage_a, a, stage_b, b, why });
            }
        }
        Ok(())
    }
}

impl Serialize for Techniques {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut m = s.serialize_map(Some(Stage::ALL.len()))?;
        for (stage, t) in self.iter() {
            m.serialize_entry(stage.name(), t.name)?;
        }
        m.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_system_row_names_existing_techniques_and_every_variant_has_a_row() {
        for s in SYSTEMS {
            for (i, name) in s.techniques.iter().enumerate() {
                assert!(technique(Stage::ALL[i], name).is_some(), "{}: {name}", s.name);
            }
        }
        for sys in System::ALL {
            assert_eq!(SYSTEMS.iter().filter(|s| s.system == sys).count(), 1, "{sys:?}");
            assert_eq!(System::from_name(sys.name()), Ok(sys));
        }
        for stage in Stage::ALL {
            assert!(stage.techniques().any(|t| t.available), "{stage} has nothing available");
        }
    }

    #[test]
    fn every_system_is_available_and_an_unbuilt_technique_is_named() {
        for sys in [System::Hu, System::Chiu, System::Welch, System::Coastal] {
            assert!(sys.available(), "{sys}");
            Techniques::of_system(sys).check().unwrap();
        }
        // Negative control: a system whose row names a technique that is not built.
        let t = Techniques::of_system(System::Coastal).with_unbuilt(Stage::Shading, false);
        let e = t.check().unwrap_err().to_string();
        assert!(e.contains("system `coastal`") && e.contains("not yet available"), "{e}");
        assert!(e.contains("`unbuilt`") && e.contains("shading"), "{e}");
        let e = System::from_name("no-such-system").unwrap_err().to_string();
        assert!(e.contains("hu") && e.contains("welch") && e.contains("coastal"), "{e}");
    }

    #[test]
    fn overrides_replace_one_stage_and_are_checked() {
        let t = Techniques::with_overrides(System::Hu, [(Stage::FarField, "mip")]).unwrap();
        assert_eq!(t.of(Stage::FarField).name, "mip");
        assert_eq!(t.of(Stage::Waves).name, "fft");
        assert!(t.check().is_ok());
        let t = Techniques::with_overrides(System::Hu, [(Stage::Foam, "jacobian")]).unwrap();
        assert!(t.check().is_ok());
        let t = Techniques::with_overrides(System::Hu, [(Stage::Surface, "shore_grid")]).unwrap();
        assert!(t.check().is_ok());
        // An overridden stage that is not built is named by its scene key, not by the system.
        let e = t.with_unbuilt(Stage::Surface, true).check().unwrap_err().to_string();
        assert!(e.contains("techniques.surface") && e.contains("`unbuilt`"), "{e}");
        let t = Techniques::with_overrides(System::Welch, [(Stage::FarField, "variance")]).unwrap();
        let e = t.check().unwrap_err().to_string();
        assert!(e.contains("gerstner") && e.contains("variance"), "{e}");
        let e = Techniques::with_overrides(System::Hu, [(Stage::Sky, "nope")]).unwrap_err();
        assert!(e.to_string().contains("preetham"), "{e}");
    }
}
