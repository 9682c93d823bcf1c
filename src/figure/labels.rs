//! Every word a figure shows, in English and Romanian, in the lecture's notation (algorithm.md's
//! "Romanian terms worth keeping": rază primară, rază reflectată, rază transmisă, arborele de raze,
//! fereastra vizuală, volum încadrator, subdivizare adaptivă). Labels are markup for
//! `canvas::text` (`n_1` → n₁, `θ_i` → θᵢ); the kinds compose them with numbers, never with words
//! of their own.

use super::source::{Pick, Target, MIN_APART_DEG};
use super::Lang;
use crate::format::{markup_escape, slide_number};

/// A fixed label or caption piece.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Label {
    // Titles.
    /// Title of `uv-map`.
    TitleUvMap,
    /// Title of `projections`.
    TitleProjections,
    /// Title of `rays`.
    TitleRays,
    /// Title of `refraction`.
    TitleRefraction,
    /// Title of `local-model` (followed by the hit's name).
    TitleLocalModel,
    /// Title of `ray-tree`.
    TitleRayTree,
    /// Title of `shadows`.
    TitleShadows,
    /// Title of `slab-test`.
    TitleSlabTest,
    /// Title of `kay-kajiya`.
    TitleKayKajiya,
    /// Title of `bvh`.
    TitleBvh,
    /// Title of `grid-dda`.
    TitleGridDda,
    /// Title of `octree`.
    TitleOctree,
    /// Title of `adaptive`.
    TitleAdaptive,
    /// Title of `heat-map`.
    TitleHeatMap,
    /// Title of `adaptive` for a pixel sampled uniformly (`--aa corners`).
    TitleUniform,

    // Rays and points.
    /// The primary ray P.
    PrimaryRay,
    /// The reflected ray R.
    ReflectedRay,
    /// The transmitted ray T.
    TransmittedRay,
    /// A shadow ray that reaches its light.
    ShadowRay,
    /// A shadow leaf not cast: the light is behind the surface.
    ShadowNotCast,
    /// A shadow ray attenuated by transparent occluders (0 < s < 1).
    BlockedShadowRay,
    /// A shadow ray stopped by an opaque occluder (s = 0).
    OpaqueShadowRay,
    /// A hit point.
    HitPoint,
    /// Where a shadow ray meets an occluder.
    OccluderPoint,
    /// A transparent occluder's outline (shadows).
    TransparentOccluder,
    /// An opaque occluder's outline (shadows).
    OpaqueOccluder,
    /// A light source.
    LightSource,
    /// The observer O.
    Observer,
    /// The normal N.
    Normal,
    /// The view window.
    ViewWindow,
    /// Caption tail of a figure with an inset (followed by its factor, `×3`).
    InsetNote,
    /// The image (viewport).
    Image,
    /// The background (a miss).
    Background,
    /// The chosen pixel.
    ChosenPixel,
    /// The chosen pixel, marked by its centre in a ring (its square too small to see).
    PixelCentreRinged,
    /// The pixel's cell mapped into the window.
    PixelInWindow,
    /// The window–viewport transform.
    WindowViewport,
    /// Orthographic projection.
    Orthographic,
    /// Perspective projection.
    Perspective,
    /// L: towards the light.
    VectorL,
    /// V: towards the viewer.
    VectorV,
    /// H: the bisector of L and V.
    VectorH,
    /// The surface (tangent at I).
    Surface,
    /// The depth limit.
    DepthLimit,
    /// A node stopped by the depth limit.
    StoppedByDepth,
    /// What the level under the depth limit does (after "n = k").
    SpawnsNoRt,
    /// The reflection weight on an R edge of a ray tree (the lecture's Ks).
    WeightKs,
    /// The transmission weight on a T edge of a ray tree (the lecture's Kt).
    WeightKt,
    /// A ray-tree node: its colour.
    NodeColour,
    /// Total internal reflection.
    Tir,
    /// No transmitted ray.
    NoT,
    /// The scene (caption).
    Scene,
    /// A ray given by hand (caption).
    GivenRay,
    /// Nothing in between (s = 1).
    NothingBetween,
    /// Where L leaves the picture towards a light too far to draw (followed by the light's name).
    TowardsLight,
    /// Opaque occluder (s = 0).
    Opaque,
    /// The plane of the camera's u and w axes (3D projection note).
    PlaneUw,
    /// Sections vs projection outlines (3D note).
    SectionsNote,
    /// Plane of incidence (refraction).
    PlaneOfIncidence,
    /// Plane of N and L (shadows).
    PlaneOfNL,
    /// Vectors at their true angles to N (local model, 3D).
    TrueAnglesToN,
    /// Primary rays only (projections caption).
    PrimaryOnly,
    /// Rows counted from the bottom.
    RowsFromBottom,
    /// The level n of a node.
    Level,
    /// "not reached" (depth limit).
    NotReached,
    /// "shadow rays omitted" (crowded tree).
    ShadowLeavesOmitted,
    /// The critical angle.
    CriticalAngle,
    /// "light" (numbered in lists).
    Light,
    /// "picked" (caption).
    Picked,
    /// "row" (caption).
    Row,
    /// "columns" (caption).
    Columns,
    /// Each panel on the plane of its row of rays.
    PlaneOfRow,
    /// The inside of an object.
    Inside,
    /// A light's intensity in the local model's formula.
    Isrc,
    /// A traced sample (legend of `adaptive`).
    SampleTraced,
    /// A sample read again by another subregion (the lecture's subzonă).
    SampleReused,
    /// A leaf square's colour.
    LeafColour,
    /// Legend: a leaf whose corners differ by less than the threshold.
    LeafUnderThreshold,
    /// Legend: a leaf at level K whose corners still differ by the threshold or more.
    LeafAtMaxLevel,
    /// Legend of the uniform figure: the pixel is the mean of its corners.
    UniformMean,
    /// Caption of the uniform figure: the method.
    UniformRule,
    /// The uniform figure's rule: a ray through each corner.
    UniformCorners,
    /// The uniform figure's rule: corners shared, and what an image costs (3D).
    UniformShared,
    /// The uniform figure's rule: corners shared, and what an image costs (2D).
    UniformShared2d,
    /// "split while" (the rule of `adaptive`).
    SplitWhen,
    /// "samples traced".
    SamplesTraced,
    /// The corner reads that traced no new ray (the samples a square read again).
    Reused,
    /// "pixel" (its colour).
    PixelColour,
    /// "primary rays traced" (heat-map caption).
    RaysTraced,
    /// What the heat map's colours count (caption).
    HeatMapCounts,
    /// "samples" after a count in the heat map's legend.
    SamplesUnit,
    /// The heat maps' shared scale (in their legend).
    OneScale,
    /// "mean per pixel".
    MeanPerPixel,
    /// "rays" after a count in the legend.
    RaysPerPixel,
    /// Title of `tradeoff`'s sampling plot.
    TitleTradeoffSampling,
    /// Title of `tradeoff`'s depth plot.
    TitleTradeoffDepth,
    /// The sampling sweep's reference, in a `tradeoff` caption.
    ReferenceSampling,
    /// The depth sweep's reference, in a `tradeoff` caption.
    ReferenceDepth,
    /// After a count of rays per pixel.
    RaysPerPixelShort,
    /// Where a `tradeoff` plot's times are.
    TimesInTable,
    /// What the names of a `tradeoff` sampling plot's points are.
    PointsSampling,
    /// What the names of a `tradeoff` depth plot's points are.
    PointsDepth,
    /// The centre sampling mode.
    SamplingCentre,
    /// The corners sampling mode.
    SamplingCorners,
    /// The adaptive sampling mode.
    SamplingAdaptive,
    /// The Pareto front of rays against error.
    ParetoFront,
    /// The `tradeoff` plot's cost axis.
    AxisRaysPerPixel,
    /// The `tradeoff` plot's error axis.
    AxisRmse,
    /// `tradeoff`'s progress line: after the count of settings rendered.
    ProgressSettings,
    /// `tradeoff`'s progress line: the reference image being rendered.
    ProgressReference,
    /// The adaptive threshold.
    Threshold,
    /// K = 0: the corners, no subdivision.
    CornersOnly,
    /// A slab figure's caption: whose bounding volume is tested, before the object's name.
    VolumeOf,
    /// A ray meets the volume.
    MeetsVolume,
    /// A ray misses the volume.
    MissesVolume,
    /// Drawn in the plane of two axes (followed by their names).
    AxisPlane,
    /// Legend: the ray that meets the volume.
    RayMeets,
    /// Legend: the ray that misses it.
    RayMisses,
    /// Legend: a slab's planes (followed by its name).
    SlabPlanes,
    /// Caption: nodes tested.
    NodesTested,
    /// Caption: nodes entered.
    NodesEntered,
    /// Caption: objects tested.
    ObjectsTested,
    /// Caption: "k of n", out of.
    OutOf,
    /// A note on a ray that passes near an object: "misses" (EN, before the object's name).
    Misses,
    /// The same note: "by" (EN, before the distance).
    MissesBy,
    /// Legend: a node whose box the ray met.
    NodeEntered,
    /// Legend: a node whose box it missed.
    NodeMissed,
    /// Legend: a node met but skipped beyond the nearest hit.
    NodeSkipped,
    /// Legend: a node not reached because an ancestor's box was missed.
    NodeUnderMissed,
    /// Legend: a node not reached because an ancestor was skipped beyond the nearest hit.
    NodeUnderSkipped,
    /// Legend: a node never tested (the walk ended first).
    NodeUntested,
    /// Caption: nodes skipped beyond the nearest hit.
    NodesSkipped,
    /// "grid" (caption, before its cells).
    Grid,
    /// "voxels visited" (the lecture's word for a grid's cell, "voxel", in both languages, as in
    /// the captions and the narration).
    CellsVisited,
    /// Legend: a visited cell.
    CellVisited,
    /// Legend: where the ray leaves a cell.
    CellExit,
    /// Legend: a hit found beyond its cell.
    FoundBeyond,
    /// Legend: an object listed in a visited cell only because its bounding box reaches into it.
    ListedByBox,
    /// Table: the same, after the object's name.
    BoxOnly,
    /// "voxel" (table head).
    Cell,
    /// The pitfall: "found while visiting cell".
    PitfallIn,
    /// The cell's exit t.
    CellExitT,
    /// The pitfall's rule.
    PitfallRule,
    /// Title of `backward`.
    TitleBackward,
    /// Title of `camera-frame`.
    TitleCameraFrame,
    /// Title of `discriminant`.
    TitleDiscriminant,
    /// Title of `jagged-edges`.
    TitleJagged,
    /// Title of `complexity`.
    TitleComplexity,
    /// `backward`'s left panel.
    InReality,
    /// `backward`'s right panel.
    InRayTracing,
    /// `backward`'s legend: what the arrows say.
    ArrowsTravel,
    /// `backward`'s caption: the lecture's words on P.
    PixelTakesI,
    /// `camera-frame`'s legend: u, v, w.
    FrameAxes,
    /// `camera-frame`'s legend: the up vector.
    UpGiven,
    /// `camera-frame`'s legend: from O towards C.
    ViewLine,
    /// `camera-frame`'s caption: how 3D is drawn.
    ObliqueView,
    /// `discriminant`: the ray that misses.
    DeltaMiss,
    /// `discriminant`: the tangent ray.
    DeltaTangent,
    /// `discriminant`: the ray through the sphere.
    DeltaTwo,
    /// `discriminant`'s legend: a root's point.
    Root,
    /// `discriminant`'s caption: the equation.
    Quadratic,
    /// `discriminant`'s caption: which root is the hit.
    NearestRoot,
    /// `discriminant`'s caption: the rays.
    ThreeRays,
    /// `jagged-edges`: the centre-sampled panel.
    OneRayPerPixel,
    /// `jagged-edges`' caption: the crop.
    Crop,
    /// `jagged-edges`' caption: the pixels the two differ in.
    ChangedPixels,
    /// `jagged-edges`' caption: primary rays of the whole image.
    PrimaryForImage,
    /// `complexity`'s left plot.
    ObjectTestsPerRay,
    /// `complexity`'s right plot.
    AllTestsPerRay,
    /// `complexity`'s x axis.
    ObjectsN,
    /// `complexity`: brute force.
    BruteForce,
    /// `complexity`: a bounding volume per object.
    PerObjectVolumes,
    /// `complexity`: the grid.
    RegularGrid,
    /// `complexity`: the octree.
    OctreeName,
    /// `complexity`'s caption: what was rendered.
    CrowdCaption,
    /// `complexity`'s caption: how.
    RayCastingCount,
    /// `jagged-edges`: the panel sampled at the corners.
    CornersPanel,
    /// `jagged-edges`: the panel sampled adaptively (followed by its threshold and K).
    AdaptivePanel,
    /// `complexity`: the BVH.
    BvhName,
    /// The depth limit's name in a formula: the scene field `max_depth`, the lecture's "nivel max".
    MaxDepth,
    /// A square's level in a formula (`4^{−level}`).
    LevelSymbol,
    /// A leaf's colour's subscript in a formula (`C_leaf`).
    LeafSymbol,
    /// The sampling of a heat map, before its kind in Romanian (`--aa` in English).
    SamplingIs,
}

impl Label {
    /// The label in `lang`.
    #[must_use]
    pub fn text(self, lang: Lang) -> &'static str {
        let (en, ro) = self.both();
        match lang {
            Lang::En => en,
            Lang::Ro => ro,
        }
    }

    /// The English and the Romanian text.
    #[must_use]
    pub const fn both(self) -> (&'static str, &'static str) {
        match self {
            Self::TitleUvMap => (
                "From pixel (i, j) to window point (u, v)",
                "De la pixelul (i, j) la punctul (u, v) al ferestrei",
            ),
            Self::TitleProjections => (
                "Primary rays: orthographic and perspective projection",
                "Raze primare: proiecția ortografică și proiecția perspectivă",
            ),
            Self::TitleRays => ("All the rays of one pixel", "Toate razele unui pixel"),
            Self::TitleRefraction => (
                "Reflection and refraction at a hit point",
                "Reflexia și refracția într-un punct de intersecție",
            ),
            Self::TitleLocalModel => ("The local illumination model at", "Modelul de iluminare locală în"),
            Self::TitleRayTree => ("The ray tree", "Arborele de raze"),
            Self::TitleShadows => {
                ("Shadow rays and the shadow factor s", "Raze de umbră și factorul de umbră s")
            }
            Self::TitleSlabTest => {
                ("The slab test of an axis-aligned box", "Testul cu plăci al unui paralelipiped")
            }
            Self::TitleKayKajiya => (
                "Kay–Kajiya slabs: a bounding volume of plane pairs",
                "Volumul încadrator Kay–Kajiya: perechi de plane paralele",
            ),
            Self::TitleBvh => (
                "Bounding volume hierarchy: the nodes a ray visits",
                "Ierarhia de volume încadratoare: nodurile vizitate de rază",
            ),
            Self::TitleGridDda => {
                ("Regular grid: the voxels the DDA visits", "Grila regulată: voxelii parcurși de DDA")
            }
            Self::TitleOctree => {
                ("Octree: adaptive subdivision of the scene", "Arborele octal: divizarea adaptivă a scenei")
            }
            Self::TitleAdaptive => {
                ("Adaptive subdivision of one pixel", "Subdivizarea adaptivă a unui pixel")
            }
            Self::TitleHeatMap => ("Samples read per pixel", "Eșantioane citite pe pixel"),
            Self::HeatMapCounts => (
                "colour: the samples a pixel reads, a shared corner counted in each pixel",
                "culoarea: eșantioanele citite de un pixel, un colț comun numărat la fiecare pixel",
            ),
            Self::TitleUniform => (
                "Uniform supersampling: the corners of one pixel",
                "Mărirea uniformă a numărului de raze: colțurile unui pixel",
            ),
            Self::LeafUnderThreshold => (
                "leaf: corners differ < threshold (their mean)",
                "frunză: colțurile diferă < prag (media lor)",
            ),
            Self::LeafAtMaxLevel => (
                "leaf at level K: still ≥ threshold (their mean)",
                "frunză la nivelul K: încă ≥ prag (media lor)",
            ),
            Self::UniformMean => ("pixel: the mean of its corners", "pixelul: media colțurilor"),
            Self::UniformRule => (
                "uniform: the pixel's corners, shared with its neighbours",
                "uniformă: colțurile pixelului, comune cu vecinii",
            ),
            Self::UniformCorners => (
                "a primary ray through each corner of the pixel",
                "câte o rază primară prin fiecare colț al pixelului",
            ),
            Self::UniformShared => (
                "each corner serves the adjacent pixels too:\nm × n pixels, (m + 1)(n + 1) rays",
                "fiecare colț servește și pixelii adiacenți:\nm × n pixeli, (m + 1)(n + 1) raze",
            ),
            Self::UniformShared2d => (
                "each end serves the adjacent pixel too:\nm pixels, m + 1 rays",
                "fiecare capăt servește și pixelul adiacent:\nm pixeli, m + 1 raze",
            ),

            Self::PrimaryRay => ("primary ray P", "rază primară P"),
            Self::ReflectedRay => ("reflected ray R", "rază reflectată R"),
            Self::TransmittedRay => ("transmitted ray T", "rază transmisă T"),
            Self::ShadowRay => ("shadow ray L, free (s = 1)", "rază de umbră L, liberă (s = 1)"),
            Self::BlockedShadowRay => {
                ("L, transparent occluder (0 < s < 1)", "L, obstacol transparent (0 < s < 1)")
            }
            Self::ShadowNotCast => {
                ("L not cast: light behind (lum = 0)", "L netrasată: sursa în spate (lum = 0)")
            }
            Self::OpaqueShadowRay => ("L, opaque occluder (s = 0)", "L, obstacol opac (s = 0)"),
            Self::HitPoint => ("hit point I", "punct de intersecție I"),
            Self::OccluderPoint => ("L meets an object", "L întâlnește un obiect"),
            Self::TransparentOccluder => ("transparent occluder (kt > 0)", "obstacol transparent (Kt > 0)"),
            Self::OpaqueOccluder => ("opaque occluder (kt = 0)", "obstacol opac (Kt = 0)"),
            Self::LightSource => ("light source S", "sursă de lumină S"),
            Self::Observer => ("observer O", "observatorul O"),
            Self::Normal => ("normal N", "normala N"),
            Self::ViewWindow => ("view window", "fereastra vizuală"),
            Self::InsetNote => (
                "the framed region, drawn again in the inset magnified",
                "regiunea încadrată, redesenată alături în detaliu mărit",
            ),
            Self::Image => ("image", "imaginea"),
            Self::Background => ("background", "fond"),
            Self::ChosenPixel => ("the pixel", "pixelul"),
            Self::PixelCentreRinged => ("the pixel's centre (ringed)", "centrul pixelului (încercuit)"),
            Self::PixelInWindow => ("the pixel in the window", "pixelul în fereastră"),
            Self::WindowViewport => ("window–viewport transform", "transformarea fereastră–poartă"),
            Self::Orthographic => ("orthographic projection", "proiecția ortografică"),
            Self::Perspective => ("perspective projection", "proiecția perspectivă"),
            Self::VectorL => ("L: towards the light", "L: spre sursa de lumină"),
            Self::VectorV => ("V: towards the observer", "V: spre observator"),
            Self::VectorH => ("H: bisector of L and V", "H: bisectoarea lui L și V"),
            Self::Surface => ("surface", "suprafața"),
            Self::DepthLimit => ("depth limit", "adâncimea maximă"),
            Self::StoppedByDepth => ("stopped by the depth limit", "oprit de adâncimea maximă"),
            Self::SpawnsNoRt => ("spawns no R or T", "nu mai generează R sau T"),
            Self::WeightKs => ("ks", "Ks"),
            Self::WeightKt => ("kt", "Kt"),
            Self::NodeColour => ("node: the colour it returns", "nod: culoarea întoarsă"),
            Self::Tir => ("total internal reflection", "reflexie totală internă"),
            Self::NoT => ("no transmitted ray T", "nicio rază transmisă T"),
            Self::Scene => ("scene", "scena"),
            Self::GivenRay => ("a given ray", "o rază dată"),
            Self::NothingBetween => ("nothing in between", "nimic între ele"),
            Self::TowardsLight => ("to the light", "spre sursa"),
            Self::Opaque => ("opaque", "opac"),
            Self::PlaneUw => (
                "3D trace projected onto the camera's (u, w) plane",
                "traseu 3D proiectat pe planul (u, w) al camerei",
            ),
            Self::SectionsNote => (
                "solid outlines: sections by that plane; dashed: outlines of the projections",
                "contur plin: secțiunea cu acest plan; întrerupt: conturul proiecției",
            ),
            Self::PlaneOfIncidence => {
                ("drawn in the plane of incidence (N, D)", "desenat în planul de incidență (N, D)")
            }
            Self::PlaneOfNL => ("drawn in the plane of N and L", "desenat în planul lui N și L"),
            Self::TrueAnglesToN => (
                "each vector drawn at its true angle to N, on the side it leans to",
                "fiecare vector desenat la unghiul său real față de N, de partea spre care se înclină",
            ),
            Self::PrimaryOnly => ("primary rays only", "numai razele primare"),
            Self::RowsFromBottom => ("rows j count from the bottom", "rândurile j se numără de jos"),
            Self::Level => ("level", "nivelul"),
            Self::NotReached => ("not reached", "neatinsă"),
            Self::ShadowLeavesOmitted => {
                ("shadow rays L left out (crowded tree)", "razele de umbră L omise (arbore aglomerat)")
            }
            Self::CriticalAngle => ("critical angle", "unghiul critic"),
            Self::Light => ("light", "sursa"),
            Self::Picked => ("picked", "ales"),
            Self::Row => ("row", "rândul"),
            Self::Columns => ("columns", "coloanele"),
            Self::Inside => ("inside the object", "interiorul obiectului"),
            Self::Isrc => ("Isrc", "Isursa"),
            Self::SampleTraced => ("sample: one primary ray", "eșantion: o rază primară"),
            Self::SampleReused => ("read again by another subregion", "refolosit de altă subzonă"),
            Self::LeafColour => ("leaf: the mean of its corners", "frunză: media colțurilor"),
            Self::SplitWhen => ("a subregion splits while", "o subzonă se divide cât timp"),
            Self::SamplesTraced => ("samples traced", "eșantioane trasate"),
            Self::Reused => ("re-read without a new ray", "recitite fără rază nouă"),
            Self::PixelColour => ("pixel", "pixelul"),
            Self::RaysTraced => ("primary rays traced (shared once)", "raze primare trasate (comune o dată)"),
            Self::MeanPerPixel => ("mean per pixel", "media pe pixel"),
            Self::RaysPerPixel => ("rays", "raze"),
            Self::SamplesUnit => ("samples", "eșantioane"),
            Self::OneScale => ("every map on one logarithmic scale", "toate hărțile pe aceeași scară logaritmică"),
            Self::TitleTradeoffSampling => (
                "What sampling costs: error against rays traced",
                "Cât costă eșantionarea: eroarea față de razele trasate",
            ),
            Self::TitleTradeoffDepth => (
                "What recursion depth costs: error against rays traced",
                "Cât costă adâncimea recursivității: eroarea față de razele trasate",
            ),
            Self::ReferenceSampling => (
                "reference: the same depth limit, sampled at every lattice point",
                "referința: aceeași adâncime maximă, eșantionată în fiecare punct al rețelei",
            ),
            Self::ReferenceDepth => (
                "reference: the same sampling, traced deeper",
                "referința: aceeași eșantionare, trasată mai adânc",
            ),
            Self::RaysPerPixelShort => ("rays/pixel,", "raze/pixel,"),
            Self::TimesInTable => ("times in the table", "timpii în tabel"),
            Self::PointsSampling => (
                "a setting: centre, corners, or adaptive's threshold, K",
                "o variantă: centru, colțuri sau pragul adaptivei, K",
            ),
            Self::PointsDepth => {
                ("a setting: its depth limit by the point", "o variantă: adâncimea maximă lângă punct")
            }
            Self::SamplingCentre => ("centre", "centru"),
            Self::SamplingCorners => ("corners", "colțuri"),
            Self::SamplingAdaptive => ("adaptive", "adaptivă"),
            Self::ParetoFront => (
                "Pareto front: nothing has both fewer rays and less error",
                "frontul Pareto: nimic nu are și mai puține raze, și eroare mai mică",
            ),
            Self::AxisRaysPerPixel => {
                ("rays traced per pixel (all kinds)", "raze trasate pe pixel (toate tipurile)")
            }
            Self::AxisRmse => ("RMSE against the reference", "RMSE față de referință"),
            Self::ProgressSettings => ("settings", "variante"),
            Self::ProgressReference => ("the reference", "referința"),
            Self::Threshold => ("threshold", "pragul"),
            Self::VolumeOf => ("the bounding volume of", "volumul încadrator al obiectului"),
            Self::MeetsVolume => ("meets the volume", "intersectează volumul"),
            Self::MissesVolume => ("misses the volume", "ratează volumul"),
            Self::AxisPlane => ("drawn in the plane", "desenat în planul"),
            Self::RayMeets => ("the ray that meets the volume", "raza care intersectează volumul"),
            Self::RayMisses => ("a ray that misses it", "o rază care îl ratează"),
            Self::SlabPlanes => ("planes", "planele"),
            Self::NodesTested => ("nodes tested", "noduri testate"),
            Self::NodesEntered => ("opened", "deschise"),
            Self::NodesSkipped => ("not opened (beyond the hit)", "nedeschise (dincolo de intersecție)"),
            Self::ObjectsTested => ("objects tested", "obiecte testate"),
            Self::OutOf => ("of", "din"),
            Self::Misses => ("misses", "trece la"),
            Self::MissesBy => ("by", "de"),
            Self::NodeEntered => {
                ("box met: opened (n: order opened)", "volum intersectat: deschis (n: ordinea deschiderii)")
            }
            Self::NodeSkipped => {
                ("box beyond the nearest hit: not opened", "volum dincolo de intersecția găsită: nedeschis")
            }
            Self::NodeMissed => ("box missed: subtree skipped", "volum ratat: subarbore sărit"),
            Self::NodeUnderMissed => ("not reached: an ancestor missed", "neatins: un strămoș ratat"),
            Self::NodeUnderSkipped => {
                ("not reached: an ancestor not opened", "neatins: un strămoș nedeschis")
            }
            Self::NodeUntested => ("never tested", "netestat"),
            Self::Grid => ("grid", "grila"),
            Self::CellsVisited => ("voxels visited", "voxeli parcurși"),
            Self::CellVisited => ("voxel visited (k: order)", "voxel parcurs (k: ordinea)"),
            Self::CellExit => ("ray leaves the voxel (min tMax)", "raza iese din voxel (min tMax)"),
            Self::FoundBeyond => ("hit found beyond its voxel", "intersecție găsită dincolo de voxel"),
            Self::ListedByBox => ("listed via its bounding box only", "listat doar prin volumul încadrator"),
            Self::BoxOnly => ("box only", "doar volumul"),
            Self::Cell => ("voxel", "voxel"),
            Self::PitfallIn => ("the pitfall: hit found in voxel", "capcana: intersecție găsită în voxelul"),
            Self::CellExitT => ("its exit", "ieșirea lui"),
            Self::PitfallRule => (
                "a hit counts only within its voxel:\nthe walk goes on",
                "o intersecție contează numai în voxelul ei:\nparcurgerea continuă",
            ),
            Self::CornersOnly => {
                ("K = 0: the 4 corners, no subdivision", "K = 0: cele 4 colțuri, fără subdivizare")
            }
            Self::MaxDepth => ("max_depth", "nivel max"),
            Self::LevelSymbol => ("level", "nivel"),
            Self::LeafSymbol => ("leaf", "frunză"),
            Self::SamplingIs => ("--aa", "eșantionare:"),
            Self::PlaneOfRow => (
                "each panel drawn in the plane of its row of rays (u to the right, the row's direction up)",
                "fiecare panou desenat în planul rândului său de raze (u spre dreapta, direcția rândului în sus)",
            ),
            Self::TitleBackward => (
                "Rays are traced backwards, against the light",
                "Razele din ray tracing au sensul invers celor din realitate",
            ),
            Self::TitleCameraFrame => (
                "The camera frame built by lookAt(O, C, up)",
                "Sistemul de coordonate al camerei: lookAt(O, C, up)",
            ),
            Self::TitleDiscriminant => (
                "Ray and sphere: the discriminant Δ of the quadratic in t",
                "Rază și sferă: discriminantul Δ al ecuației de grad 2 în t",
            ),
            Self::TitleJagged => (
                "Jagged edges: one ray per pixel against more rays per pixel",
                "Margini zimțate: o rază pe pixel față de mai multe raze pe pixel",
            ),
            Self::TitleComplexity => (
                "Tests per ray against the number of objects n, measured",
                "Teste pe rază în funcție de numărul de obiecte n, măsurate",
            ),
            Self::InReality => (
                "In reality:\nthe light goes S → I → O",
                "În realitate:\nlumina merge S → I → O",
            ),
            Self::InRayTracing => (
                "Ray tracing:\nthe rays go O → I, then I → S",
                "În ray tracing:\nrazele merg O → I, apoi I → S",
            ),
            Self::ArrowsTravel => (
                "arrow: the direction of travel",
                "săgeata: sensul deplasării",
            ),
            Self::PixelTakesI => (
                "the pixel takes the colour of I; P is the direction along which the light of I reaches the observer, traced the other way",
                "pixelul este colorat în culoarea punctului I; P este direcția pe care lumina din I ajunge la observator, parcursă în sens invers",
            ),
            Self::FrameAxes => (
                "camera axes u, v, w (unit vectors)",
                "axele camerei u, v, w (versori)",
            ),
            Self::UpGiven => (
                "up, as given to lookAt",
                "vectorul up, dat lui lookAt",
            ),
            Self::ViewLine => (
                "from O towards C: along −w",
                "de la O spre C: de-a lungul lui −w",
            ),
            Self::ObliqueView => (
                "drawn in an oblique view; the scene's objects are left out",
                "desenat în vedere oblică; obiectele scenei nu sunt desenate",
            ),
            Self::DeltaMiss => (
                "the ray misses the sphere",
                "raza nu intersectează sfera",
            ),
            Self::DeltaTangent => (
                "the ray is tangent to the sphere",
                "raza este tangentă la sferă",
            ),
            Self::DeltaTwo => (
                "two roots t_1 < t_2",
                "două rădăcini t_1 < t_2",
            ),
            Self::Root => (
                "r(t) at a root t",
                "r(t) într-o rădăcină t",
            ),
            Self::Quadratic => (
                "|O + t·D − C|^2 = r^2 gives t^2 + b·t + c = 0 with b = 2D·(O − C), c = |O − C|^2 − r^2, Δ = b^2 − 4c",
                "din |O + t·D − C|^2 = r^2 rezultă t^2 + b·t + c = 0, cu b = 2D·(O − C), c = |O − C|^2 − r^2, Δ = b^2 − 4c",
            ),
            Self::NearestRoot => (
                "the hit is r(min(t_1, t_2)), the least root t > 0",
                "intersecția este r(min(t_1, t_2)), cea mai mică rădăcină t > 0",
            ),
            Self::ThreeRays => (
                "three rays along the camera's −w",
                "trei raze de-a lungul lui −w al camerei",
            ),
            Self::OneRayPerPixel => (
                "1 ray per pixel (its centre)",
                "o rază pe pixel (prin centru)",
            ),
            Self::Crop => (
                "crop",
                "decupajul",
            ),
            Self::ChangedPixels => (
                "pixels changed in the crop",
                "pixeli schimbați în decupaj",
            ),
            Self::PrimaryForImage => (
                "primary rays for the image",
                "raze primare pentru imagine",
            ),
            Self::ObjectTestsPerRay => (
                "object tests per ray",
                "teste rază–obiect pe rază",
            ),
            Self::AllTestsPerRay => (
                "all tests per ray",
                "toate testele pe rază",
            ),
            Self::ObjectsN => (
                "n: objects in the scene",
                "n: obiecte în scenă",
            ),
            Self::BruteForce => (
                "brute force",
                "forța brută",
            ),
            Self::PerObjectVolumes => (
                "a volume per object",
                "un volum pe obiect",
            ),
            Self::RegularGrid => (
                "regular grid",
                "grilă regulată",
            ),
            Self::OctreeName => (
                "octree",
                "arbore octal",
            ),
            Self::CrowdCaption => (
                "in its view: n random spheres",
                "în câmpul vizual al camerei: n sfere aleatoare",
            ),
            Self::RayCastingCount => (
                "ray casting, one ray per pixel, shadow rays counted; one render per point; all tests: objects, bounding volumes, tree nodes, grid voxels",
                "ray casting, o rază pe pixel, razele de umbră numărate; o randare pe punct; toate testele: obiecte, volume încadratoare, noduri, voxeli",
            ),
            Self::CornersPanel => (
                "4 rays per pixel (its corners, shared)",
                "4 raze pe pixel (colțurile, comune cu vecinii)",
            ),
            Self::AdaptivePanel => (
                "adaptive subdivision",
                "subdivizare adaptivă",
            ),
            Self::BvhName => (
                "bounding volume hierarchy (BVH)",
                "ierarhie de volume încadratoare (BVH)",
            ),
        }
    }
}

/// Why the figure picked its pixel, as a caption phrase.
#[must_use]
pub fn pick_reason(pick: Pick, lang: Lang) -> Option<String> {
    let (en, ro) = match pick {
        Pick::Given => return None,
        Pick::Walk => {
            ("its walk through the structure shows the most", "parcurgerea structurii arată cel mai mult")
        }
        Pick::VolumeHit => ("its ray meets the volume", "raza sa intersectează volumul"),
        Pick::VolumeMiss => {
            ("its ray misses the volume by a little", "raza sa ratează volumul la mică distanță")
        }
        Pick::Subdivided => {
            ("its subdivision mixes the most levels", "subdivizarea sa amestecă cele mai multe niveluri")
        }
        Pick::Default => ("the centre pixel", "pixelul din centru"),
        Pick::OffCentre => ("off the centre, in the upper right", "în afara centrului, sus în dreapta"),
        Pick::OffCentreRow => ("right of the centre", "la dreapta centrului"),
        Pick::Refraction => ("its first refraction is the clearest", "are cea mai clară refracție"),
        Pick::Tir => {
            ("its trace has a total internal reflection", "traseul său are o reflexie totală internă")
        }
        Pick::BlockedShadow => {
            ("a shadow ray of its trace meets an object", "o rază de umbră a traseului întâlnește un obiect")
        }
        Pick::Rich => ("its trace has the most kinds of rays", "traseul are cele mai multe tipuri de raze"),
        Pick::LitDirectly => (
            "the light reaches its hit with nothing in between",
            "lumina ajunge în punctul său de intersecție fără obstacole",
        ),
        Pick::Lit => {
            ("its hit is lit, N, L, H, V well apart", "intersecția e luminată, N, L, H, V distincte")
        }
        Pick::LitCrowded => {
            let least = slide_number(MIN_APART_DEG);
            return Some(match lang {
                Lang::En => format!("its hit is lit; no pixel tried keeps N, L, H, V {least}° apart"),
                Lang::Ro => {
                    format!("intersecția e luminată; în niciun pixel încercat N, L, H, V nu sunt la {least}° unul de altul")
                }
            });
        }
    };
    Some(
        match lang {
            Lang::En => en,
            Lang::Ro => ro,
        }
        .to_owned(),
    )
}

/// The traced pixel or ray as a caption phrase: `pixel (3, 2)` (`pixel 5` in 2D).
#[must_use]
pub fn target(target: &Target, dim: usize, lang: Lang) -> String {
    match target {
        Target::Pixel { i, j, .. } => {
            let word = match lang {
                Lang::En => "pixel",
                Lang::Ro => "pixelul",
            };
            if dim == 2 {
                format!("{word} {i}")
            } else {
                format!("{word} ({i}, {j})")
            }
        }
        Target::Ray => Label::GivenRay.text(lang).to_owned(),
    }
}

/// `scene NAME · `, a caption's lead in English; nothing in Romanian, where the scene's file
/// name (`flat`, `mirrors_2d`) would be English on the slide (issue 32 item 4).
#[must_use]
pub fn scene_lead(scene_name: &str, lang: Lang) -> String {
    match lang {
        Lang::En => format!("{} {} · ", Label::Scene.text(lang), markup_escape(scene_name)),
        Lang::Ro => String::new(),
    }
}

/// `objects tested: k of n`: a ray's object tests against the scene's n objects, all of which
/// brute force would test; the cost lesson compares the structures by it.
#[must_use]
pub fn objects_tested(tested: usize, objects: usize, lang: Lang) -> String {
    format!("{}: {tested} {} {objects}", Label::ObjectsTested.text(lang), Label::OutOf.text(lang))
}

/// `scene NAME · pixel (i, j) (picked: …)`: the caption's first part ([`scene_lead`]).
#[must_use]
pub fn traced(scene_name: &str, what: &Target, pick: Pick, dim: usize, lang: Lang) -> String {
    let mut out = format!("{}{}", scene_lead(scene_name, lang), target(what, dim, lang));
    if let Some(why) = pick_reason(pick, lang) {
        out.push_str(&format!(" ({}: {why})", Label::Picked.text(lang)));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::canvas::text::has_glyph;

    /// Every variant, for the checks below (kept in step with the enum by the match in `both`).
    const ALL: &[Label] = &[
        Label::TitleUvMap,
        Label::TitleProjections,
        Label::TitleRays,
        Label::TitleRefraction,
        Label::TitleLocalModel,
        Label::TitleRayTree,
        Label::TitleShadows,
        Label::TitleSlabTest,
        Label::TitleKayKajiya,
        Label::TitleBvh,
        Label::TitleGridDda,
        Label::TitleOctree,
        Label::TitleAdaptive,
        Label::TitleHeatMap,
        Label::TitleTradeoffSampling,
        Label::TitleTradeoffDepth,
        Label::ReferenceSampling,
        Label::ReferenceDepth,
        Label::RaysPerPixelShort,
        Label::TimesInTable,
        Label::PointsSampling,
        Label::PointsDepth,
        Label::SamplingCentre,
        Label::SamplingCorners,
        Label::SamplingAdaptive,
        Label::ParetoFront,
        Label::AxisRaysPerPixel,
        Label::AxisRmse,
        Label::ProgressSettings,
        Label::ProgressReference,
        Label::PrimaryRay,
        Label::ReflectedRay,
        Label::TransmittedRay,
        Label::ShadowRay,
        Label::BlockedShadowRay,
        Label::OpaqueShadowRay,
        Label::ShadowNotCast,
        Label::HitPoint,
        Label::LightSource,
        Label::TowardsLight,
        Label::Observer,
        Label::Normal,
        Label::ViewWindow,
        Label::InsetNote,
        Label::Misses,
        Label::MissesBy,
        Label::Tir,
        Label::SectionsNote,
        Label::TitleUniform,
        Label::HeatMapCounts,
        Label::SamplesUnit,
        Label::OneScale,
        Label::TransparentOccluder,
        Label::OpaqueOccluder,
        Label::LeafUnderThreshold,
        Label::LeafAtMaxLevel,
        Label::UniformMean,
        Label::UniformRule,
        Label::UniformCorners,
        Label::UniformShared,
        Label::UniformShared2d,
        Label::NodeEntered,
        Label::NodeSkipped,
        Label::NodeMissed,
        Label::NodeUnderMissed,
        Label::NodeUnderSkipped,
        Label::NodeUntested,
        Label::NodesSkipped,
        Label::TitleBackward,
        Label::TitleCameraFrame,
        Label::TitleDiscriminant,
        Label::TitleJagged,
        Label::TitleComplexity,
        Label::InReality,
        Label::InRayTracing,
        Label::ArrowsTravel,
        Label::PixelTakesI,
        Label::FrameAxes,
        Label::UpGiven,
        Label::ViewLine,
        Label::ObliqueView,
        Label::DeltaMiss,
        Label::DeltaTangent,
        Label::DeltaTwo,
        Label::Root,
        Label::Quadratic,
        Label::NearestRoot,
        Label::ThreeRays,
        Label::OneRayPerPixel,
        Label::Crop,
        Label::ChangedPixels,
        Label::PrimaryForImage,
        Label::ObjectTestsPerRay,
        Label::AllTestsPerRay,
        Label::ObjectsN,
        Label::BruteForce,
        Label::PerObjectVolumes,
        Label::RegularGrid,
        Label::OctreeName,
        Label::CrowdCaption,
        Label::RayCastingCount,
        Label::CornersPanel,
        Label::AdaptivePanel,
        Label::BvhName,
        Label::MaxDepth,
        Label::LevelSymbol,
        Label::LeafSymbol,
        Label::SamplingIs,
        Label::VolumeOf,
    ];

    #[test]
    fn both_languages_differ_and_every_character_has_a_glyph() {
        for label in ALL {
            let (en, ro) = label.both();
            assert!(!en.is_empty() && !ro.is_empty());
            assert_ne!(en, ro, "{label:?}");
            for c in en.chars().chain(ro.chars()) {
                assert!(has_glyph(c) || c == ' ' || c == '\n', "{label:?}: {c:?}");
            }
        }
    }

    #[test]
    fn romanian_uses_the_lecture_terms() {
        assert_eq!(Label::PrimaryRay.text(Lang::Ro), "rază primară P");
        assert_eq!(Label::TitleRayTree.text(Lang::Ro), "Arborele de raze");
        assert_eq!(Label::ViewWindow.text(Lang::Ro), "fereastra vizuală");
        // "spre sursa" (the figure adds the light's name: "spre sursa S"), not "Isursa" (the
        // source's intensity); the lecture's "nivel max".
        assert_eq!(Label::TowardsLight.text(Lang::Ro), "spre sursa");
        assert_eq!(Label::MaxDepth.text(Lang::Ro), "nivel max");
    }
}
