//! The technique axis (docs/design.md, "Systems and techniques"): a **stage** is one step of the
//! frame, a **technique** one way to do it, a **system** one seed paper's choice of technique
//! per stage. This file is the one table of both; `ocean plan` prints it, the scene's
//! `system` and `[techniques]` keys choose from it, and the planner turns the choice into
//! passes.
//!
//! The stages' techniques are types ([`crate::stage`]); a scene's names become them here, in
//! [`Techniques::with_overrides`], and nowhere after.

use std::fmt;

use crate::frame_format::FrameFormat;
pub use crate::stage::{
    FarField, Foam, Post, Shading, Sky, Spray, Stage, StageTechnique, Surface, TechniqueInfo, Waves,
};
use serde::{Deserialize, Serialize};

/// The technique `name` of `stage`, if the table has it.
pub fn technique(stage: Stage, name: &str) -> Option<&'static TechniqueInfo> {
    stage.techniques().find(|t| t.name == name)
}

/// Every technique of every stage, in stage order (docs/design.md's table).
pub fn all_techniques() -> impl Iterator<Item = &'static TechniqueInfo> {
    Stage::ALL.into_iter().flat_map(Stage::techniques)
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

/// One technique per stage: a system's row, or a frame's choice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Choice {
    /// Stage `waves`.
    pub waves: Waves,
    /// Stage `surface`.
    pub surface: Surface,
    /// Stage `shading`.
    pub shading: Shading,
    /// Stage `sky`.
    pub sky: Sky,
    /// Stage `far_field`.
    pub far_field: FarField,
    /// Stage `foam`.
    pub foam: Foam,
    /// Stage `spray`.
    pub spray: Spray,
    /// Stage `post`.
    pub post: Post,
}

impl Choice {
    /// The row of the technique table chosen for `stage`.
    pub fn of(&self, stage: Stage) -> &'static TechniqueInfo {
        match stage {
            Stage::Waves => self.waves.info(),
            Stage::Surface => self.surface.info(),
            Stage::Shading => self.shading.info(),
            Stage::Sky => self.sky.info(),
            Stage::FarField => self.far_field.info(),
            Stage::Foam => self.foam.info(),
            Stage::Spray => self.spray.info(),
            Stage::Post => self.post.info(),
        }
    }

    /// Sets `stage` to the technique called `name`.
    ///
    /// # Errors
    /// [`TechniqueError::UnknownTechnique`] for a name the stage does not have.
    /// The overrides applied: each stage that has one takes it.
    fn overridden_by(mut self, o: &TechniqueOverrides) -> Self {
        macro_rules! apply {
            ($($stage:ident),+) => { $( if let Some(t) = o.$stage { self.$stage = t; } )+ };
        }
        apply!(waves, surface, shading, sky, far_field, foam, spray, post);
        self
    }
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
    /// Its technique per stage.
    pub techniques: Choice,
    /// The format of its frame's colour buffers where the scene does not choose one.
    pub frame_format: FrameFormat,
}

/// The systems, one per seed paper (docs/design.md). A stage a paper does not name keeps the
/// neutral technique (`none`, `tonemap`).
pub const SYSTEMS: &[SystemInfo] = &[
    SystemInfo {
        system: System::Hu,
        name: "hu",
        paper: "Hu, Velho, Tong, Guo & Shum 2004 (seed 000)",
        techniques: Choice {
            waves: Waves::Fft,
            surface: Surface::HuPatches,
            shading: Shading::Hu,
            sky: Sky::Preetham,
            far_field: FarField::Variance,
            foam: Foam::None,
            spray: Spray::None,
            post: Post::Tonemap,
        },
        frame_format: FrameFormat::Rgba32Float,
    },
    SystemInfo {
        system: System::Chiu,
        name: "chiu",
        paper: "Chiu & Chang (seed 001)",
        techniques: Choice {
            waves: Waves::Fft,
            surface: Surface::ProjectedGrid,
            shading: Shading::Chiu,
            sky: Sky::PreethamClouds,
            // The paper point-samples; its far sea then sparkles, and the mip-mapped slopes
            // are the filtering its shading can take (it has no variance term).
            far_field: FarField::Mip,
            foam: Foam::None,
            spray: Spray::Particles,
            post: Post::Tonemap,
        },
        frame_format: FrameFormat::Rgba32Float,
    },
    SystemInfo {
        system: System::Welch,
        name: "welch",
        paper: "Welch 2019 (seed 002)",
        techniques: Choice {
            waves: Waves::Gerstner,
            surface: Surface::Clipmap,
            shading: Shading::Ggx,
            sky: Sky::Atmosphere,
            // The paper takes the waves' slopes as they are; its far sea then sparkles, and
            // far field `mip` is the Gerstner waves' analytic footprint filter (the maps'
            // `variance` needs chains the Gerstner waves do not have).
            far_field: FarField::Mip,
            foam: Foam::Heuristic,
            spray: Spray::None,
            post: Post::Bloom,
        },
        // "works with 16-bit precision floats in all the frame buffers" (seed 002 §post).
        frame_format: FrameFormat::Rgba16Float,
    },
    SystemInfo {
        system: System::Coastal,
        name: "coastal",
        paper: "the coastal-wave shader (seed 004)",
        techniques: Choice {
            waves: Waves::Coastal,
            surface: Surface::ShoreGrid,
            shading: Shading::Coastal,
            sky: Sky::Preetham,
            // The seed filters nothing; its far sea would sparkle, and far field `mip` is the
            // coastal waves' analytic footprint filter (as the Gerstner waves').
            far_field: FarField::Mip,
            foam: Foam::Heuristic,
            spray: Spray::None,
            post: Post::Tonemap,
        },
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
    #[error("{}", stage.unknown_technique(name))]
    UnknownTechnique {
        /// The stage.
        stage: Stage,
        /// The name asked for.
        name: String,
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

/// "hu, chiu, welch, coastal".
pub fn known_systems() -> String {
    SYSTEMS.iter().map(|s| s.name).collect::<Vec<_>>().join(", ")
}

/// The `[techniques]` table of a scene file: a technique per stage, overriding the system's
/// choice. Each value is parsed where the file is read (an unknown name is refused there, at
/// its line and column).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct TechniqueOverrides {
    /// Stage `waves`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub waves: Option<Waves>,
    /// Stage `surface`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub surface: Option<Surface>,
    /// Stage `shading`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shading: Option<Shading>,
    /// Stage `sky`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sky: Option<Sky>,
    /// Stage `far_field`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub far_field: Option<FarField>,
    /// Stage `foam`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub foam: Option<Foam>,
    /// Stage `spray`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spray: Option<Spray>,
    /// Stage `post`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub post: Option<Post>,
}

impl TechniqueOverrides {
    /// The (stage, name) pairs that are set, in stage order.
    pub fn iter(&self) -> impl Iterator<Item = (Stage, &'static str)> {
        [
            (Stage::Waves, self.waves.map(Waves::name)),
            (Stage::Surface, self.surface.map(Surface::name)),
            (Stage::Shading, self.shading.map(Shading::name)),
            (Stage::Sky, self.sky.map(Sky::name)),
            (Stage::FarField, self.far_field.map(FarField::name)),
            (Stage::Foam, self.foam.map(Foam::name)),
            (Stage::Spray, self.spray.map(Spray::name)),
            (Stage::Post, self.post.map(Post::name)),
        ]
        .into_iter()
        .filter_map(|(s, v)| v.map(|v| (s, v)))
    }

    /// Sets `stage` to the technique called `name`: where a name from the command line
    /// becomes a technique.
    ///
    /// # Errors
    /// [`TechniqueError::UnknownTechnique`] for a name the stage does not have.
    pub fn set(&mut self, stage: Stage, name: &str) -> Result<(), TechniqueError> {
        fn parse<T: StageTechnique>(name: &str) -> Result<Option<T>, TechniqueError> {
            T::from_name(name).map(Some).ok_or_else(|| TechniqueError::UnknownTechnique {
                stage: T::STAGE,
                name: name.into(),
            })
        }
        match stage {
            Stage::Waves => self.waves = parse(name)?,
            Stage::Surface => self.surface = parse(name)?,
            Stage::Shading => self.shading = parse(name)?,
            Stage::Sky => self.sky = parse(name)?,
            Stage::FarField => self.far_field = parse(name)?,
            Stage::Foam => self.foam = parse(name)?,
            Stage::Spray => self.spray = parse(name)?,
            Stage::Post => self.post = parse(name)?,
        }
        Ok(())
    }
}

/// The technique chosen for each stage of a frame: the system's row with the scene's
/// `[techniques]` overrides applied.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Techniques {
    /// The system the choice starts from.
    pub system: System,
    chosen: Choice,
    overridden: [bool; 8],
}

impl Techniques {
    /// The system's own choice.
    pub fn of_system(system: System) -> Self {
        Self { system, chosen: system.info().techniques, overridden: [false; 8] }
    }

    /// The system's choice with a scene's `[techniques]` applied.
    pub fn of_overrides(system: System, overrides: &TechniqueOverrides) -> Self {
        let mut overridden = [false; 8];
        for (stage, _) in overrides.iter() {
            overridden[stage as usize] = true;
        }
        Self { system, chosen: system.info().techniques.overridden_by(overrides), overridden }
    }

    /// The system's choice with `overrides` (stage → technique name) applied: names from
    /// the command line or a test, parsed by [`TechniqueOverrides::set`].
    ///
    /// # Errors
    /// [`TechniqueError::UnknownTechnique`] for a name the stage does not have.
    pub fn with_overrides<'a>(
        system: System,
        overrides: impl IntoIterator<Item = (Stage, &'a str)>,
    ) -> Result<Self, TechniqueError> {
        let mut o = TechniqueOverrides::default();
        for (stage, name) in overrides {
            o.set(stage, name)?;
        }
        Ok(Self::of_overrides(system, &o))
    }

    /// Stage `waves`' technique.
    pub fn waves(&self) -> Waves {
        self.chosen.waves
    }

    /// Stage `surface`'s technique.
    pub fn surface(&self) -> Surface {
        self.chosen.surface
    }

    /// Stage `shading`'s technique.
    pub fn shading(&self) -> Shading {
        self.chosen.shading
    }

    /// Stage `sky`'s technique.
    pub fn sky(&self) -> Sky {
        self.chosen.sky
    }

    /// Stage `far_field`'s technique.
    pub fn far_field(&self) -> FarField {
        self.chosen.far_field
    }

    /// Stage `foam`'s technique.
    pub fn foam(&self) -> Foam {
        self.chosen.foam
    }

    /// Stage `spray`'s technique.
    pub fn spray(&self) -> Spray {
        self.chosen.spray
    }

    /// Stage `post`'s technique.
    pub fn post(&self) -> Post {
        self.chosen.post
    }

    /// The row of the technique table chosen for `stage` (for printing: code that acts on a
    /// technique matches on the typed accessors above).
    pub fn of(&self, stage: Stage) -> &'static TechniqueInfo {
        self.chosen.of(stage)
    }

    /// Whether the scene chose `stage`'s technique (rather than the system).
    pub fn is_overridden(&self, stage: Stage) -> bool {
        self.overridden[stage as usize]
    }

    /// Every (stage, technique), in stage order.
    pub fn iter(&self) -> impl Iterator<Item = (Stage, &'static TechniqueInfo)> + '_ {
        Stage::ALL.into_iter().map(|s| (s, self.of(s)))
    }

    /// Checks that the choice can be rendered: no pair of techniques that cannot work
    /// together.
    ///
    /// # Errors
    /// [`TechniqueError::Incompatible`] naming both techniques of a pair.
    pub fn check(&self) -> Result<(), TechniqueError> {
        if self.waves() == Waves::Gerstner && self.far_field() == FarField::Variance {
            return Err(TechniqueError::Incompatible {
                stage_a: Stage::Waves,
                a: Waves::Gerstner.name(),
                stage_b: Stage::FarField,
                b: FarField::Variance.name(),
                why: "the Gerstner waves' slopes are filtered analytically, with no maps, and \
                      `variance` needs the maps' chains for its filtered Fresnel table; choose \
                      far_field = \"mip\" (the analytic filter) or \"none\"",
            });
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
    fn every_system_has_one_row_and_parses_by_name() {
        for sys in System::ALL {
            assert_eq!(SYSTEMS.iter().filter(|s| s.system == sys).count(), 1, "{sys:?}");
            assert_eq!(System::from_name(sys.name()), Ok(sys));
            Techniques::of_system(sys).check().unwrap();
        }
        let e = System::from_name("no-such-system").unwrap_err().to_string();
        assert!(e.contains("hu") && e.contains("welch") && e.contains("coastal"), "{e}");
        // No technique is lost from the table (25 before sky `overcast`), and no stage names
        // two alike.
        let names: Vec<(Stage, &str)> = all_techniques().map(|t| (t.stage, t.name)).collect();
        assert!(names.len() >= 26, "{} techniques", names.len());
        let unique: std::collections::BTreeSet<_> = names.iter().collect();
        assert_eq!(unique.len(), names.len(), "a stage names two techniques alike");
        assert_eq!(technique(Stage::Surface, "clipmap").map(|t| t.name), Some("clipmap"));
        assert_eq!(technique(Stage::Surface, "fft"), None);
    }

    #[test]
    fn overrides_replace_one_stage_and_are_checked() {
        let t = Techniques::with_overrides(System::Hu, [(Stage::FarField, "mip")]).unwrap();
        assert_eq!(t.far_field(), FarField::Mip);
        assert_eq!(t.of(Stage::FarField).name, "mip");
        assert_eq!(t.waves(), Waves::Fft);
        assert!(t.is_overridden(Stage::FarField) && !t.is_overridden(Stage::Waves));
        assert!(t.check().is_ok());
        let t = Techniques::with_overrides(System::Hu, [(Stage::Foam, "jacobian")]).unwrap();
        assert_eq!(t.foam(), Foam::Jacobian);
        let t = Techniques::with_overrides(System::Hu, [(Stage::Surface, "shore_grid")]).unwrap();
        assert_eq!(t.surface(), Surface::ShoreGrid);
        let t = Techniques::with_overrides(System::Welch, [(Stage::FarField, "variance")]).unwrap();
        let e = t.check().unwrap_err().to_string();
        assert!(e.contains("gerstner") && e.contains("variance"), "{e}");
        let e = Techniques::with_overrides(System::Hu, [(Stage::Sky, "nope")]).unwrap_err();
        assert!(e.to_string().contains("preetham") && e.to_string().contains("`sky`"), "{e}");
        // A name of another stage is no technique of this one.
        assert!(Techniques::with_overrides(System::Hu, [(Stage::Shading, "fft")]).is_err());
    }
}
