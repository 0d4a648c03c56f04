//! The stages of a frame and each stage's techniques, as types (docs/design.md, "Systems and
//! techniques"). A technique's name is read once, where the scene file or `--system` names it
//! ([`StageTechnique::from_name`]); everything after matches on the enum, so the compiler
//! lists every place a new technique must be handled.
//!
//! This module imports nothing of the crate: the scene, the plan, the uniforms and the back
//! ends all build on it.

use std::fmt;

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

    /// Its techniques' names, in the table's order: "preetham, preetham_clouds, …".
    pub fn known_techniques(self) -> String {
        self.techniques().map(|t| t.name).collect::<Vec<_>>().join(", ")
    }

    /// The refusal of a name the stage does not have.
    pub fn unknown_technique(self, name: &str) -> String {
        format!(
            "unknown technique `{name}` for stage `{self}` (known: {})",
            self.known_techniques()
        )
    }

    /// The techniques of this stage, in the table's order.
    pub fn techniques(self) -> impl Iterator<Item = &'static TechniqueInfo> {
        match self {
            Stage::Waves => Waves::INFO,
            Stage::Surface => Surface::INFO,
            Stage::Shading => Shading::INFO,
            Stage::Sky => Sky::INFO,
            Stage::FarField => FarField::INFO,
            Stage::Foam => Foam::INFO,
            Stage::Spray => Spray::INFO,
            Stage::Post => Post::INFO,
        }
        .iter()
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One row of the technique table: what `ocean plan` prints and the docs list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TechniqueInfo {
    /// Its stage.
    pub stage: Stage,
    /// Its name: the scene value, and the file name at every layer
    /// (`shaders/<stage>/<name>.wgsl`, `ocean-cpu/src/shaders/<stage>/<name>.rs`).
    pub name: &'static str,
    /// Where it comes from (seed number, paper).
    pub source: &'static str,
}

/// What every stage's technique enum has: its stage, its table rows, and parsing by name.
pub trait StageTechnique: Copy + Eq + fmt::Debug + 'static {
    /// Its stage.
    const STAGE: Stage;
    /// Every technique of the stage, in the table's order.
    const ALL: &'static [Self];
    /// Its row of the table.
    fn info(self) -> &'static TechniqueInfo;
    /// Its name (the scene value).
    fn name(self) -> &'static str {
        self.info().name
    }
    /// The technique called `name`: the one place a name becomes a technique.
    fn from_name(name: &str) -> Option<Self> {
        Self::ALL.iter().copied().find(|t| t.name() == name)
    }
}

/// Declares one stage's enum, its table rows (in declaration order, which `info` indexes by)
/// and its `Display`/`Serialize` by name.
macro_rules! stage_techniques {
    (
        $(#[$doc:meta])*
        $Enum:ident: $stage:ident {
            $( $(#[$vdoc:meta])* $V:ident = $name:literal, $source:literal; )+
        }
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum $Enum {
            $( $(#[$vdoc])* $V, )+
        }

        impl $Enum {
            const INFO: &'static [TechniqueInfo] = &[
                $( TechniqueInfo { stage: Stage::$stage, name: $name, source: $source }, )+
            ];

            /// Its name (the scene value).
            pub const fn name(self) -> &'static str {
                Self::INFO[self as usize].name
            }

            /// Its row of the table (as [`StageTechnique::info`], in constants).
            pub const fn row(self) -> &'static TechniqueInfo {
                &Self::INFO[self as usize]
            }
        }

        impl StageTechnique for $Enum {
            const STAGE: Stage = Stage::$stage;
            const ALL: &'static [Self] = &[ $( $Enum::$V, )+ ];
            fn info(self) -> &'static TechniqueInfo {
                // Variants and rows are declared together, in one order.
                &Self::INFO[self as usize]
            }
        }

        impl fmt::Display for $Enum {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }

        impl Serialize for $Enum {
            fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                s.serialize_str(self.name())
            }
        }

        // A scene file's `[techniques]` value: the one place a name becomes a technique.
        impl<'de> Deserialize<'de> for $Enum {
            fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let name = String::deserialize(d)?;
                <Self as StageTechnique>::from_name(&name).ok_or_else(|| {
                    serde::de::Error::custom(Stage::$stage.unknown_technique(&name))
                })
            }
        }
    };
}

stage_techniques! {
    /// Stage `waves`: where the displacement and slopes come from.
    Waves: Waves {
        /// Tessendorf's spectrum → displacement and bump maps by FFT (seed 000).
        Fft = "fft", "Tessendorf spectrum → displacement + bump maps (seed 000)";
        /// A sum of Gerstner waves, per vertex (seed 002).
        Gerstner = "gerstner", "sum of Gerstner waves, per vertex (seed 002)";
        /// Radial waves running to a shore, per vertex (seed 004).
        Coastal = "coastal", "radial waves running to a shore, per vertex (seed 004)";
    }
}

// What the planner, the uniforms and the frame graph ask of a stage's technique: one
// exhaustive `match` each, so a new technique answers every question where it is declared.

impl Waves {
    /// Whether the waves are summed per vertex and per fragment in the water pass (no wave
    /// maps, no waves pass, the height query from the sum).
    pub fn per_vertex(self) -> bool {
        match self {
            Waves::Fft => false,
            Waves::Gerstner | Waves::Coastal => true,
        }
    }

    /// Whether the waves run up a shore (a wet band on the sand, a sea rebuilt at each time
    /// from the shore's geometry).
    pub fn runs_up_a_shore(self) -> bool {
        match self {
            Waves::Coastal => true,
            Waves::Fft | Waves::Gerstner => false,
        }
    }
}

stage_techniques! {
    /// Stage `surface`: the mesh the waves displace.
    Surface: Surface {
        /// Hu's near LOD tree and far conic patch (seed 000 §3).
        HuPatches = "hu_patches", "near LOD tree + far conic patch (seed 000 §3)";
        /// A grid projected from the screen (seed 001).
        ProjectedGrid = "projected_grid", "projected grid (seed 001)";
        /// GPU clipmaps, morphed, to the horizon (seed 002).
        Clipmap = "clipmap", "GPU clipmaps, morphed, to the horizon (seed 002)";
        /// A camera-aligned grid of rows of equal screen height (seed 004).
        ShoreGrid = "shore_grid", "camera-aligned grid, rows of equal screen height (seed 004)";
    }
}

impl Surface {
    /// Whether the mesh is Hu's near tree with a far patch to the horizon (pass `far_patch`).
    pub fn has_far_patch(self) -> bool {
        match self {
            Surface::HuPatches => true,
            Surface::ProjectedGrid | Surface::Clipmap | Surface::ShoreGrid => false,
        }
    }

    /// Whether the mesh is a clipmap's nested levels around the eye.
    pub fn clipmap_levels(self) -> bool {
        match self {
            Surface::Clipmap => true,
            Surface::HuPatches | Surface::ProjectedGrid | Surface::ShoreGrid => false,
        }
    }

    /// Whether the mesh's vertices are bounded by the waves' height (a grid projected to the
    /// sea plane must reach the highest crest).
    pub fn needs_wave_bound(self) -> bool {
        match self {
            Surface::ProjectedGrid => true,
            Surface::HuPatches | Surface::Clipmap | Surface::ShoreGrid => false,
        }
    }

    /// Whether the mesh is built from the camera each frame (a screen-space grid), so it
    /// reaches the horizon and needs the camera's ray-plane solve.
    pub fn camera_grid(self) -> bool {
        match self {
            Surface::ProjectedGrid | Surface::ShoreGrid => true,
            Surface::HuPatches | Surface::Clipmap => false,
        }
    }

    /// Whether the GPU draws the surface from the vertex index alone (a clipmap's levels, a
    /// camera grid), so the plan's mesh holds no vertex or index list, only its reference
    /// point: [`crate::plan::FramePlan::water_mesh`] makes no list, and
    /// [`crate::graph::DrawMesh::kept`] keeps none.
    pub fn index_drawn(self) -> bool {
        self.clipmap_levels() || self.camera_grid()
    }
}

stage_techniques! {
    /// Stage `shading`: the water's shading.
    Shading: Shading {
        /// Hu's eq. 3: a 2D Fresnel texture and Phong (seed 000).
        Hu = "hu", "eq. 3: 2D Fresnel texture + Phong (seed 000)";
        /// Chiu & Chang's local optics and water colour, eqs. 2–8 (seed 001).
        Chiu = "chiu", "local optics and water colour, eqs. 2–8 (seed 001)";
        /// Cook–Torrance: GGX, Smith G, exact Fresnel (seed 002).
        Ggx = "ggx", "Cook–Torrance: GGX, Smith G, exact Fresnel (seed 002)";
        /// Blinn–Phong, Schlick or exact Fresnel, a dull colour (seed 004).
        Coastal = "coastal", "Blinn–Phong, Schlick or exact Fresnel, dull colour (seed 004)";
    }
}

impl Shading {
    /// Chiu & Chang's optics: the water's colour from its depth (eqs. 5–8), the reflection and
    /// refraction maps clipped at the waves (§3.5.1) and eq. 1's multi-scale sampling.
    pub fn chiu_optics(self) -> bool {
        match self {
            Shading::Chiu => true,
            Shading::Hu | Shading::Ggx | Shading::Coastal => false,
        }
    }

    /// Whether it adds Welch's scrolling detail normal map.
    pub fn detail_map(self) -> bool {
        match self {
            Shading::Ggx => true,
            Shading::Hu | Shading::Chiu | Shading::Coastal => false,
        }
    }
}

stage_techniques! {
    /// Stage `sky`: the environment the water reflects.
    Sky: Sky {
        /// Preetham et al. 1999's daylight.
        Preetham = "preetham", "Preetham et al. 1999 daylight";
        /// Preetham's daylight under clouds (seed 001 eq. 4).
        PreethamClouds = "preetham_clouds", "Preetham + clouds (seed 001 eq. 4)";
        /// Rayleigh and Mie scattering (seed 002).
        Atmosphere = "atmosphere", "Rayleigh/Mie scattering (seed 002)";
        /// The CIE standard overcast sky (Moon & Spencer 1942): grey, no sun disc.
        Overcast = "overcast", "CIE standard overcast sky (Moon & Spencer 1942), no sun disc";
    }
}

impl Sky {
    /// Whether the sky has seed 001's cloud layer (placed over the eye each frame, dimming the
    /// sun).
    pub fn clouds(self) -> bool {
        match self {
            Sky::PreethamClouds => true,
            Sky::Preetham | Sky::Atmosphere | Sky::Overcast => false,
        }
    }

    /// Whether the sky reads the atmosphere's sky-view table.
    pub fn sky_view_table(self) -> bool {
        match self {
            Sky::Atmosphere => true,
            Sky::Preetham | Sky::PreethamClouds | Sky::Overcast => false,
        }
    }
}

stage_techniques! {
    /// Stage `far_field`: what becomes of the wave detail a pixel cannot resolve.
    FarField: FarField {
        /// The wave maps' level 0, bilinear.
        None = "none", "point-sampled wave maps";
        /// Mip chains, trilinear at the footprint's LOD.
        Mip = "mip", "mip-mapped slope maps, trilinear at the footprint";
        /// Mip chains and the unresolved slope variance in the BRDF.
        Variance = "variance", "unresolved slope variance in the BRDF (Bruneton 2010)";
    }
}

impl FarField {
    /// Whether the slope maps carry mip chains (pass `wave_mips`).
    pub fn mip_chains(self) -> bool {
        match self {
            FarField::None => false,
            FarField::Mip | FarField::Variance => true,
        }
    }

    /// Whether the BRDF reads the unresolved slope variance (the filtered Fresnel table).
    pub fn slope_variance(self) -> bool {
        match self {
            FarField::Variance => true,
            FarField::None | FarField::Mip => false,
        }
    }
}

stage_techniques! {
    /// Stage `foam`: white water.
    Foam: Foam {
        /// No foam.
        None = "none", "no foam";
        /// From the normal and the height (seed 002).
        Heuristic = "heuristic", "from normal and height (seed 002)";
        /// Where the Jacobian folds.
        Jacobian = "jacobian", "where the Jacobian folds";
        /// Grows where J is below a threshold and decays over time.
        Accumulated = "accumulated", "grows where J < threshold, decays over time";
    }
}

impl Foam {
    /// Whether the foam keeps a field from frame to frame (pass `foam`).
    pub fn keeps_a_field(self) -> bool {
        match self {
            Foam::Accumulated => true,
            Foam::None | Foam::Heuristic | Foam::Jacobian => false,
        }
    }
}

stage_techniques! {
    /// Stage `spray`: spray particles.
    Spray: Spray {
        /// No spray.
        None = "none", "no spray";
        /// State-preserving GPU particles (seed 001).
        Particles = "particles", "state-preserving GPU particles (seed 001)";
    }
}

impl Spray {
    /// Whether spray particles are simulated and drawn (pass `spray`).
    pub fn particles(self) -> bool {
        match self {
            Spray::Particles => true,
            Spray::None => false,
        }
    }
}

stage_techniques! {
    /// Stage `post`: HDR → display.
    Post: Post {
        /// Exposure, vignette, a filmic curve → 8-bit sRGB.
        Tonemap = "tonemap", "exposure, [post] vignette, ACES or Hable filmic curve → 8-bit sRGB";
        /// A bright pass and blur pyramid added before the tonemap (seed 002, Jimenez 2014).
        Bloom = "bloom", "bright pass + blur pyramid added before the tonemap (seed 002, Jimenez 2014)";
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn round_trips<T: StageTechnique>() {
        let names: Vec<_> = T::ALL.iter().map(|t| t.name()).collect();
        for &t in T::ALL {
            assert_eq!(T::from_name(t.name()), Some(t));
            assert_eq!(t.info().stage, T::STAGE);
            assert_eq!(names.iter().filter(|n| **n == t.name()).count(), 1, "{t:?}");
        }
        assert_eq!(T::STAGE.techniques().count(), T::ALL.len());
        // Negative control: a name of another stage, or none, is not one of these.
        assert_eq!(T::from_name("no-such-technique"), None);
        assert_eq!(T::from_name(""), None);
    }

    #[test]
    fn every_stage_parses_its_names_and_only_its_names() {
        round_trips::<Waves>();
        round_trips::<Surface>();
        round_trips::<Shading>();
        round_trips::<Sky>();
        round_trips::<FarField>();
        round_trips::<Foam>();
        round_trips::<Spray>();
        round_trips::<Post>();
        assert_eq!(Waves::from_name("hu_patches"), None);
        assert_eq!(Shading::from_name("fft"), None);
    }
}
