//! The variant set: named optimization variants (`--variant a,b,…`) and what a
//! combination of them chooses ([`VariantConfig`]).
//! `baseline` is the thesis's software reference: brute force over all primitives, std
//! sqrt, perspective camera, Lambert diffuse, every sample traced. Each other variant
//! changes one of those choices; variants that change the same choice cannot combine.

use crate::camera::Projection;
use crate::variants::diffuse::DiffuseForm;
use std::fmt;

/// One named variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Variant {
    Baseline,
    FastSqrt,
    FastSqrtTuned,
    FastSqrtNewton,
    Bounded,
    Ortho,
    NoRsqrtShading,
    PixelAvg,
    Simd,
    Bvh,
    Embree,
    EmbreeNative,
    EmbreePackets,
    Packets,
}

/// The square root every `sqrt` and `normalize` uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SqrtMethod {
    #[default]
    Std,
    BitTrick,
    TunedBitTrick,
    NewtonBitTrick,
}

/// The structure that answers intersection queries.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Accelerator {
    #[default]
    BruteForce,
    Simd,
    Bvh,
    /// `bvh` + `simd`: the wide BVH with its boxes and spheres in lanes.
    WideBvh,
    /// Intel Embree 3, the peer (needs the `embree` build feature), with rtprof's own
    /// quadric tests as user geometry: the baseline's picture.
    Embree,
    /// Embree with its own sphere kernel (sphere points).
    EmbreeNative,
    /// Embree's packet API (`rtcIntersect8` / `rtcOccluded8`) on the renderer's packets,
    /// with Embree's own spheres and cone curves.
    EmbreePackets,
}

impl Accelerator {
    /// Whether the structure is a bounding volume hierarchy of rtprof's own (whose tree
    /// figures and `accel.*` node counts exist).
    pub fn is_bvh(self) -> bool {
        matches!(self, Accelerator::Bvh | Accelerator::WideBvh)
    }

    /// Whether the work inside a query is counted (`tests.*`, `ops.*`, `accel.*`): not
    /// inside Embree, so no flops or roofline point can be derived for it.
    pub fn counts_its_work(self) -> bool {
        !self.is_embree()
    }

    /// Whether Intel Embree answers the queries (any of its modes).
    pub fn is_embree(self) -> bool {
        matches!(
            self,
            Accelerator::Embree | Accelerator::EmbreeNative | Accelerator::EmbreePackets
        )
    }

    /// Whether the structure traces the renderer's packets of eye rays together
    /// (its intersector has `Intersector::PACKETS`): the wide BVH and Embree's packets.
    pub fn walks_packets(self) -> bool {
        matches!(self, Accelerator::WideBvh | Accelerator::EmbreePackets)
    }

    /// Whether every query tests every primitive (brute force, with or without lanes):
    /// the time grows linearly in the primitives.
    pub fn tests_everything(self) -> bool {
        matches!(self, Accelerator::BruteForce | Accelerator::Simd)
    }
}

/// The choices a set of variants makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct VariantConfig {
    pub sqrt: SqrtMethod,
    pub accel: Accelerator,
    pub projection: Projection,
    pub diffuse: DiffuseForm,
    pub checkerboard: bool,
    /// Eye rays traced in packets (`packets` with the wide BVH; `embree-packets`).
    pub packets: bool,
}

/// Which choice a variant makes (variants with the same choice conflict).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Choice {
    Nothing,
    Sqrt,
    Accel,
    Projection,
    Diffuse,
    Sampling,
    EyeRays,
}

impl Variant {
    /// Every variant, in the order reports list them.
    pub const ALL: [Variant; 14] = [
        Variant::Baseline,
        Variant::FastSqrt,
        Variant::FastSqrtTuned,
        Variant::FastSqrtNewton,
        Variant::Bounded,
        Variant::Ortho,
        Variant::NoRsqrtShading,
        Variant::PixelAvg,
        Variant::Simd,
        Variant::Bvh,
        Variant::Embree,
        Variant::EmbreeNative,
        Variant::EmbreePackets,
        Variant::Packets,
    ];

    /// The command-line name.
    pub fn name(self) -> &'static str {
        match self {
            Variant::Baseline => "baseline",
            Variant::FastSqrt => "fast-sqrt",
            Variant::FastSqrtTuned => "fast-sqrt-tuned",
            Variant::FastSqrtNewton => "fast-sqrt-newton",
            Variant::Bounded => "bounded",
            Variant::Ortho => "ortho",
            Variant::NoRsqrtShading => "no-rsqrt-shading",
            Variant::PixelAvg => "pixel-avg",
            Variant::Simd => "simd",
            Variant::Bvh => "bvh",
            Variant::Embree => "embree",
            Variant::EmbreeNative => "embree-native",
            Variant::EmbreePackets => "embree-packets",
            Variant::Packets => "packets",
        }
    }

    /// One line saying what the variant does (and where the thesis has it).
    pub fn description(self) -> &'static str {
        match self {
            Variant::Baseline => {
                "brute force over all primitives, std sqrt, perspective camera (the software reference)"
            }
            Variant::FastSqrt => {
                "every sqrt by the bit trick i = (i + 0x3F800000) >> 1 (thesis 8.3.1)"
            }
            Variant::FastSqrtTuned => {
                "the same bit trick with the constant that minimises the maximum relative error"
            }
            Variant::FastSqrtNewton => "the bit trick followed by one Heron/Newton step",
            Variant::Bounded => {
                "observer offsets precomputed once (scene in eye coordinates): eye rays need no O - C subtraction, the screen is walked row by row (8.3.2)"
            }
            Variant::Ortho => {
                "orthographic projection: origins walk the pixel grid, one direction, no per-ray normalize (8.3.2)"
            }
            Variant::NoRsqrtShading => {
                "sphere diffuse term 1 - |I - M|²/2r², no normalize or sqrt (8.3.4, exact squared form)"
            }
            Variant::PixelAvg => {
                "trace a checkerboard of samples, fill the rest with the mean of traced neighbours (8.3.5)"
            }
            Variant::Simd => {
                "spheres and cylinders tested 8 at a time in SIMD lanes, then one minimum (8.3.3); with bvh: 8-wide nodes whose boxes, leaf spheres and the triangles of polygons and patches are tested in lanes"
            }
            Variant::Bvh => {
                "bounding volume hierarchy (binned SAH) over all primitives, front-to-back traversal"
            }
            Variant::Embree => {
                "Intel Embree 3's single-ray queries (build quality high), the peer: triangles Embree's, quadrics rtprof's tests as user geometry (the baseline's picture); needs --features embree"
            }
            Variant::EmbreeNative => {
                "embree with Embree's own sphere kernel (sphere points): its real speed on spheres; its more accurate test can change pixels"
            }
            Variant::EmbreePackets => {
                "Embree's packet API: eye rays 8 neighbours at a time by rtcIntersect8, their shadow rays light by light by rtcOccluded8 (coherent flag); spheres, cylinders and cones Embree's own (sphere points, open cone curves), a hit's distance then rtprof's test of the primitive Embree found (the baseline's rays); silhouette pixels can differ"
            }
            Variant::Packets => {
                "with bvh+simd: eye rays traced 8 neighbours at a time, and so are the rays they spawn, level by level of the ray tree (shadow rays light by light, refraction rays, reflection rays): one walk of the wide tree per packet; eye-ray packets walk it by their bounds (Embree's coherent traversal: one box step per node for all 8 rays, each ray's own box test only at leaves, a triangle tested against all the rays at once), other packets ray by ray; the same picture, work counted per ray"
            }
        }
    }

    /// Whether this build can run the variant (`embree` needs the `embree` feature).
    pub fn available(self) -> bool {
        !matches!(
            self,
            Variant::Embree | Variant::EmbreeNative | Variant::EmbreePackets
        ) || cfg!(feature = "embree")
    }

    /// Whether the variant may change the picture (all others must match baseline).
    pub fn changes_picture(self) -> bool {
        matches!(
            self,
            Variant::FastSqrt
                | Variant::FastSqrtTuned
                | Variant::FastSqrtNewton
                | Variant::Ortho
                | Variant::NoRsqrtShading
                | Variant::PixelAvg
                | Variant::EmbreeNative
                | Variant::EmbreePackets
        )
    }

    fn choice(self) -> Choice {
        match self {
            Variant::Baseline => Choice::Nothing,
            Variant::FastSqrt | Variant::FastSqrtTuned | Variant::FastSqrtNewton => Choice::Sqrt,
            Variant::Bounded | Variant::Ortho => Choice::Projection,
            Variant::NoRsqrtShading => Choice::Diffuse,
            Variant::PixelAvg => Choice::Sampling,
            Variant::Simd
            | Variant::Bvh
            | Variant::Embree
            | Variant::EmbreeNative
            | Variant::EmbreePackets => Choice::Accel,
            Variant::Packets => Choice::EyeRays,
        }
    }

    fn apply(self, config: &mut VariantConfig) {
        match self {
            Variant::Baseline => {}
            Variant::FastSqrt => config.sqrt = SqrtMethod::BitTrick,
            Variant::FastSqrtTuned => config.sqrt = SqrtMethod::TunedBitTrick,
            Variant::FastSqrtNewton => config.sqrt = SqrtMethod::NewtonBitTrick,
            Variant::Bounded => config.projection = Projection::EyeRows,
            Variant::Ortho => config.projection = Projection::Orthographic,
            Variant::NoRsqrtShading => config.diffuse = DiffuseForm::Squared,
            Variant::PixelAvg => config.checkerboard = true,
            // `simd` and `bvh` together are the wide BVH, in either order.
            Variant::Simd | Variant::Bvh
                if config.accel.is_bvh() || config.accel == Accelerator::Simd =>
            {
                config.accel = Accelerator::WideBvh
            }
            Variant::Simd => config.accel = Accelerator::Simd,
            Variant::Bvh => config.accel = Accelerator::Bvh,
            Variant::Embree => config.accel = Accelerator::Embree,
            Variant::EmbreeNative => config.accel = Accelerator::EmbreeNative,
            // Embree's packet API answers the renderer's packets: its packet path.
            Variant::EmbreePackets => {
                config.accel = Accelerator::EmbreePackets;
                config.packets = true;
            }
            Variant::Packets => config.packets = true,
        }
    }
}

impl fmt::Display for Variant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A variant list that cannot be used.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum VariantError {
    #[error("unknown variant '{name}' (known: {known}; `rtprof variants` describes them)")]
    Unknown { name: String, known: String },
    #[error("variants '{0}' and '{1}' cannot be combined: both choose the {2}")]
    Conflict(&'static str, &'static str, &'static str),
    #[error("'baseline' means no optimization and cannot be combined with '{0}'")]
    BaselineCombined(&'static str),
    #[error("the list of variants is empty: name at least one (e.g. baseline,bvh)")]
    EmptyList,
    #[error("'{0}' needs {1} (e.g. {2})")]
    Needs(&'static str, &'static str, &'static str),
}

/// A combination of variants, parsed from a list separated by `,` or `+`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VariantSet(Vec<Variant>);

impl Default for VariantSet {
    fn default() -> Self {
        Self(vec![Variant::Baseline])
    }
}

impl VariantSet {
    /// Parses a list of sets separated by `,`, each combining variants with `+` (e.g.
    /// `baseline,bvh,bvh+fast-sqrt`); the list names at least one set.
    pub fn parse_list(list: &str) -> Result<Vec<Self>, VariantError> {
        let sets = list
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
            .map(Self::parse)
            .collect::<Result<Vec<_>, _>>()?;
        if sets.is_empty() {
            return Err(VariantError::EmptyList);
        }
        Ok(sets)
    }

    /// Parses `"a,b"` or `"a+b"`; names are case-insensitive, duplicates collapse, an
    /// empty list is `baseline`. Variants that make the same choice are refused.
    pub fn parse(list: &str) -> Result<Self, VariantError> {
        let mut out: Vec<Variant> = Vec::new();
        for name in list
            .split([',', '+'])
            .map(str::trim)
            .filter(|n| !n.is_empty())
        {
            let variant = Variant::ALL
                .into_iter()
                .find(|v| v.name().eq_ignore_ascii_case(name))
                .ok_or_else(|| VariantError::Unknown {
                    name: name.to_string(),
                    known: Variant::ALL.map(Variant::name).join(", "),
                })?;
            if out.contains(&variant) {
                continue;
            }
            for &earlier in &out {
                if earlier == Variant::Baseline || variant == Variant::Baseline {
                    let other = if earlier == Variant::Baseline {
                        variant
                    } else {
                        earlier
                    };
                    return Err(VariantError::BaselineCombined(other.name()));
                }
                if earlier.choice() == variant.choice() && !Self::combine(earlier, variant) {
                    let what = match variant.choice() {
                        Choice::Sqrt => "square-root method",
                        Choice::Accel => "intersection structure",
                        Choice::Projection => "camera projection",
                        Choice::Diffuse => "diffuse term",
                        Choice::Sampling => "sampling",
                        Choice::EyeRays => "eye-ray grouping",
                        Choice::Nothing => "nothing",
                    };
                    return Err(VariantError::Conflict(earlier.name(), variant.name(), what));
                }
            }
            out.push(variant);
        }
        if out.is_empty() {
            out.push(Variant::Baseline);
        }
        let set = Self(out);
        let config = set.config();
        if config.packets && !config.accel.walks_packets() {
            // Only the wide BVH and Embree's packets walk packets; elsewhere the flag
            // would change nothing.
            return Err(VariantError::Needs(
                "packets",
                "the wide BVH, bvh and simd together",
                "bvh+simd+packets",
            ));
        }
        Ok(set)
    }

    /// Whether two variants that make the same choice still combine: `simd` inside
    /// `bvh` is the wide BVH.
    fn combine(a: Variant, b: Variant) -> bool {
        matches!(
            (a, b),
            (Variant::Simd, Variant::Bvh) | (Variant::Bvh, Variant::Simd)
        )
    }

    /// The variants in the set.
    pub fn variants(&self) -> &[Variant] {
        &self.0
    }

    /// The choices the set makes.
    pub fn config(&self) -> VariantConfig {
        let mut config = VariantConfig::default();
        for v in &self.0 {
            v.apply(&mut config);
        }
        config
    }

    /// Whether any variant of the set may change the picture.
    pub fn changes_picture(&self) -> bool {
        self.0.iter().any(|v| v.changes_picture())
    }
}

impl fmt::Display for VariantSet {
    /// Names joined with `+` (the form `compare --variants` takes for combinations).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<_> = self.0.iter().map(|v| v.name()).collect();
        f.write_str(&names.join("+"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_list_splits_on_commas_and_combines_on_plus() {
        let sets = VariantSet::parse_list(" baseline, bvh+fast-sqrt ,,bvh").unwrap();
        let names: Vec<String> = sets.iter().map(ToString::to_string).collect();
        assert_eq!(names, ["baseline", "bvh+fast-sqrt", "bvh"]);
        assert!(matches!(
            VariantSet::parse_list(" , "),
            Err(VariantError::EmptyList)
        ));
        assert!(VariantSet::parse_list("bvh,nonsense").is_err());
    }

    #[test]
    fn parses_lists_and_rejects_unknown_names() {
        assert_eq!(
            VariantSet::parse("baseline").map(|s| s.to_string()),
            Ok("baseline".into())
        );
        assert_eq!(
            VariantSet::parse(" Baseline, baseline ").map(|s| s.variants().len()),
            Ok(1)
        );
        assert_eq!(
            VariantSet::parse("bvh,fast-sqrt").map(|s| s.to_string()),
            Ok("bvh+fast-sqrt".into())
        );
        let err = VariantSet::parse("baseline,warp-drive")
            .err()
            .map(|e| e.to_string())
            .unwrap_or_default();
        assert!(err.starts_with("unknown variant 'warp-drive' (known: baseline, fast-sqrt,"));
    }

    #[test]
    fn variants_choosing_the_same_thing_conflict() {
        let conflict = |list: &str| VariantSet::parse(list).err();
        assert_eq!(
            conflict("simd,embree"),
            Some(VariantError::Conflict(
                "simd",
                "embree",
                "intersection structure"
            ))
        );
        assert!(matches!(
            conflict("bvh+simd+embree"),
            Some(VariantError::Conflict("bvh", "embree", _))
        ));
        assert!(matches!(
            conflict("fast-sqrt+fast-sqrt-newton"),
            Some(VariantError::Conflict(..))
        ));
        assert!(matches!(
            conflict("ortho,bounded"),
            Some(VariantError::Conflict(..))
        ));
        assert_eq!(
            conflict("baseline,bvh"),
            Some(VariantError::BaselineCombined("bvh"))
        );
    }

    #[test]
    fn packets_go_with_the_wide_bvh_only() {
        let config = VariantSet::parse("bvh+simd+packets").map(|s| s.config());
        assert!(matches!(
            config,
            Ok(VariantConfig {
                accel: Accelerator::WideBvh,
                packets: true,
                ..
            })
        ));
        let embree = ["packets+embree", "packets+embree-native"];
        for alone in ["packets", "bvh+packets", "simd+packets"]
            .into_iter()
            .chain(embree)
        {
            let err = VariantSet::parse(alone).err();
            assert!(
                matches!(err, Some(VariantError::Needs("packets", ..))),
                "{alone}: {err:?}"
            );
        }
        assert!(matches!(
            VariantSet::parse("baseline+packets"),
            Err(VariantError::BaselineCombined("packets"))
        ));
    }

    /// The renderer compiles its packet path only for intersectors with
    /// `Intersector::PACKETS` (render.rs); the rules above must let `packets` run with
    /// exactly those, or a packet render would silently trace one ray at a time.
    #[test]
    fn the_packet_path_is_compiled_for_the_structure_packets_run_with() {
        use crate::accel::{BruteForce, Bvh, Intersector, Simd, WideBvh};
        let structures = [
            ("", BruteForce::PACKETS),
            ("simd+", Simd::PACKETS),
            ("bvh+", Bvh::PACKETS),
            ("bvh+simd+", WideBvh::PACKETS),
        ];
        for (structure, compiled) in structures {
            let name = format!("{structure}packets");
            assert_eq!(VariantSet::parse(&name).is_ok(), compiled, "{name}");
        }
        #[cfg(feature = "embree")]
        {
            use crate::accel::{Embree, EmbreePackets};
            assert_eq!(VariantSet::parse("embree+packets").is_ok(), Embree::PACKETS);
            // `embree-packets` takes the packet path by itself (and with `packets`).
            for name in ["embree-packets", "embree-packets+packets"] {
                let config = VariantSet::parse(name).map(|s| s.config());
                let packets = config.as_ref().map(|c| c.packets);
                assert_eq!(packets, Ok(EmbreePackets::PACKETS), "{name}");
                assert!(
                    matches!(
                        config,
                        Ok(VariantConfig {
                            accel: Accelerator::EmbreePackets,
                            ..
                        })
                    ),
                    "{name}: {config:?}"
                );
            }
        }
    }

    #[test]
    fn config_collects_every_choice() {
        let set = VariantSet::parse("bvh,fast-sqrt-tuned,ortho,pixel-avg,no-rsqrt-shading")
            .unwrap_or_default();
        let config = set.config();
        assert_eq!(config.accel, Accelerator::Bvh);
        assert_eq!(config.sqrt, SqrtMethod::TunedBitTrick);
        assert_eq!(config.projection, Projection::Orthographic);
        assert_eq!(config.diffuse, DiffuseForm::Squared);
        assert!(config.checkerboard && set.changes_picture());
        assert_eq!(VariantSet::default().config(), VariantConfig::default());
        assert!(!VariantSet::parse("bvh,simd").is_ok_and(|s| s.changes_picture()));
        for wide in ["bvh+simd", "simd+bvh", "simd,bvh,simd"] {
            let accel = VariantSet::parse(wide).map(|s| s.config().accel);
            assert_eq!(accel, Ok(Accelerator::WideBvh), "{wide}");
        }
    }
}
