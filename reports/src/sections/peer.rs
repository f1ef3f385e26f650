//! The peer sentence of the variants chapter: rtprof's fastest variant that keeps the
//! picture and the rays against Intel
//! Embree in both its modes, single rays (`embree`) and packets (`embree-packets`),
//! per family of scenes, when the run has them (`rtprof suite --embree`).

use super::answers::VariantLine;
use super::family_groups::FAMILY_GROUPS;
use crate::format;

/// Embree's modes as the report names them, by variant name.
const MODES: [(&str, &str); 2] = [
    ("embree", "single-ray queries"),
    ("embree-packets", "packet queries"),
];

/// What the comparison measures and what it does not: Embree inside rtprof's renderer,
/// not a program written around Embree.
const CAVEAT: &str = "Embree runs here inside rtprof's renderer, with rtprof's camera, \
    shading and bookkeeping per ray, its robust (watertight) triangle test, and rtprof's \
    test of each primitive it finds (so the rays are the baseline's, counted); a program \
    built around Embree, shading in its own loop, can be faster than these figures: \
    the yardstick (peers/embree/, scripts/build-embree-peer.sh) measures that.";

/// Whether Embree answers the variant's queries (any of its modes).
fn is_embree(line: &VariantLine) -> bool {
    line.variant
        .set()
        .is_ok_and(|s| s.config().accel.is_embree())
}

/// "On the SPD scenes rtprof's fastest variant (of those that keep the picture and the
/// rays), X (a× geometric mean), runs at b× the
/// speed of Embree's single-ray queries (`embree`, c×) and d× that of its packet
/// queries (`embree-packets`, e×)", per family group where both sides ran; `None`
/// without an Embree mode. The caveat (Embree inside rtprof's renderer is not Embree as
/// its users run it) follows when `caveat`: when the yardstick did not run.
pub fn sentence(lines: &[VariantLine], caveat: bool) -> Option<String> {
    let mut parts = Vec::new();
    for (g, (family, _)) in FAMILY_GROUPS.iter().enumerate() {
        let geomean = |l: &VariantLine| l.families.get(g).and_then(|f| f.geomean);
        let Some((best, ours)) = lines
            .iter()
            // As in the answers: a variant that changes the picture or the rays
            // (pixel-avg, fast-sqrt) does other work than Embree's.
            .filter(|l| !is_embree(l) && !l.variant.is_reference() && !l.has_cost())
            .filter_map(|l| Some((l, geomean(l)?)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            continue;
        };
        let peers: Vec<String> = MODES
            .iter()
            .filter_map(|&(name, what)| {
                let theirs = lines
                    .iter()
                    .find(|l| l.variant.as_str() == name)
                    .and_then(geomean)?;
                Some(format!(
                    "{} the speed of Embree's {what} (`{name}`, {})",
                    format::speedup(ours / theirs),
                    format::speedup(theirs)
                ))
            })
            .collect();
        if peers.is_empty() {
            continue;
        }
        parts.push(format!(
            "on the {family} scenes rtprof's fastest variant, {} ({} geometric mean), runs at {}",
            best.variant,
            format::speedup(ours),
            format::join_list(&peers)
        ));
    }
    (!parts.is_empty()).then(|| {
        let text = format!(
            "Against Intel Embree 3 inside rtprof's renderer (the embree variants: rtprof's camera, shading and counted rays, Embree's queries; speed-ups over baseline): {}.",
            parts.join("; ")
        );
        if caveat {
            format!("{text} {CAVEAT}")
        } else {
            text
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::VariantName;
    use crate::sections::answers::FamilyFigures;

    fn line(name: &str, spd: f64) -> VariantLine {
        let mut families = vec![FamilyFigures::default(); FAMILY_GROUPS.len()];
        let g = FAMILY_GROUPS
            .iter()
            .position(|(f, _)| *f == "SPD")
            .unwrap_or(0);
        families[g].geomean = Some(spd);
        VariantLine {
            variant: VariantName::parse(name).unwrap_or_else(|e| panic!("{e}")),
            families,
            worst: None,
            picture_changed: false,
            rays_changed: 0,
            compared: 1,
        }
    }

    #[test]
    fn names_both_embree_modes_against_the_fastest_of_rtprof() {
        let lines = [
            line("bvh", 10.0),
            line("bvh+simd+packets", 40.0),
            line("embree", 50.0),
            line("embree-packets", 80.0),
        ];
        let text = sentence(&lines, true).unwrap_or_default();
        assert!(
            text.contains("bvh+simd+packets (40.0× geometric mean)"),
            "{text}"
        );
        // 40 / 50 and 40 / 80: rtprof's speed as a share of each mode's.
        assert!(
            text.contains("0.80× the speed of Embree's single-ray queries (`embree`, 50.0×)"),
            "{text}"
        );
        assert!(
            text.contains("0.50× the speed of Embree's packet queries (`embree-packets`, 80.0×)"),
            "{text}"
        );
        assert!(text.contains("on the SPD scenes"), "{text}");
        assert!(
            text.ends_with(CAVEAT),
            "the caveat follows the figures: {text}"
        );
    }

    #[test]
    fn a_variant_that_changes_the_picture_is_not_set_against_embree() {
        let mut pixel_avg = line("pixel-avg", 90.0);
        pixel_avg.picture_changed = true;
        let lines = [line("bvh+simd", 30.0), pixel_avg, line("embree", 60.0)];
        let text = sentence(&lines, true).unwrap_or_default();
        assert!(text.contains("bvh+simd (30.0× geometric mean)"), "{text}");
        assert!(!text.contains("pixel-avg"), "{text}");
    }

    #[test]
    fn no_sentence_without_embree() {
        assert_eq!(
            sentence(&[line("bvh", 10.0), line("bvh+simd", 20.0)], true),
            None
        );
    }
}
