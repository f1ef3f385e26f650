//! The peer sentence against Intel Embree as its users run it: the yardstick program
//! (peers/embree/, the built-in tracers `embree-yardstick`, packets, and
//! `embree-yardstick-single`, single rays). On each SPD scene, rtprof's fastest variant
//! that kept the picture against the faster of the yardstick's modes: rtprof's time ÷
//! Embree's (below 1× rtprof is faster), their geometric mean, and the scenes where
//! rtprof is behind.

use super::family_groups::FAMILY_GROUPS;
use super::outside_tracers::{fastest_kept, not_comparable};
use crate::findings::geometric_mean;
use crate::format;
use crate::results::{Results, SceneFamily};

/// The yardstick's modes: the tracer's name and how the sentence names the mode.
const MODES: [(&str, &str); 2] = [
    ("embree-yardstick", "packets"),
    ("embree-yardstick-single", "single rays"),
];

/// rtprof's time ÷ each mode's and ÷ the faster mode's on one scene.
struct SceneRatios {
    scene: String,
    modes: [Option<f64>; 2],
    best: f64,
}

fn ratios(r: &Results) -> Vec<SceneRatios> {
    let spd = FAMILY_GROUPS
        .iter()
        .find(|(name, _)| *name == "SPD")
        .map_or(&[SceneFamily::Spd][..], |(_, members)| members);
    r.scenes
        .iter()
        .filter(|s| spd.contains(&s.family))
        .filter_map(|scene| {
            let ours = fastest_kept(scene)?.time.median;
            let modes = MODES.map(|(name, _)| {
                scene
                    .variants
                    .iter()
                    .find(|v| v.variant.outside_name() == Some(name))
                    .filter(|v| not_comparable(v).is_none() && v.time.median > 0.0)
                    .map(|v| ours / v.time.median)
            });
            // The faster mode is the one rtprof's time is the largest multiple of.
            let best = modes.iter().flatten().copied().reduce(f64::max)?;
            Some(SceneRatios {
                scene: scene.name.clone(),
                modes,
                best,
            })
        })
        .collect()
}

/// "Against the peer, Intel Embree as its users run it (…): on the SPD scenes rtprof's
/// fastest variant that kept the picture takes 1.47× the time of Embree's faster mode
/// (geometric mean over 7 scenes; packets 1.47×, single rays 0.77×); behind on gears
/// (2.27×) and teapot (2.69×)"; `None` when the yardstick drew no SPD scene.
pub fn sentence(r: &Results) -> Option<String> {
    let scenes = ratios(r);
    let (best, n) = geometric_mean(scenes.iter().map(|s| s.best))?;
    let per_mode: Vec<String> = MODES
        .iter()
        .enumerate()
        .filter_map(|(i, (_, what))| {
            let (m, k) = geometric_mean(scenes.iter().filter_map(|s| s.modes[i]))?;
            let over = if k == n {
                String::new()
            } else {
                format!(" over {}", format::plural(k, "scene"))
            };
            Some(format!("{what} {}{over}", format::speedup(m)))
        })
        .collect();
    let behind: Vec<String> = scenes
        .iter()
        .filter(|s| s.best > 1.0)
        .map(|s| format!("{} ({})", s.scene, format::speedup(s.best)))
        .collect();
    let standing = if behind.is_empty() {
        "ahead of it on every one".to_string()
    } else {
        format!("behind it on {}", format::join_list(&behind))
    };
    Some(format!(
        "Against the peer, Intel Embree 3 as its users run it (the yardstick, peers/embree/: \
         a program on Embree's API with its own camera loop and shading, Embree's geometry \
         types and its high-quality build; its trace time as it prints it): on the SPD \
         scenes rtprof's fastest variant that kept the picture takes {} the time of \
         Embree's faster mode (geometric mean over {}; {}), {standing}.",
        format::speedup(best),
        format::plural(n, "scene"),
        format::join_list(&per_mode),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::results::{SceneResult, VariantName};
    use testkit::sample_results;

    /// A copy of `template` as SPD scene `name`: its reference variant at `ours`
    /// seconds, the yardstick's packet mode at `packets` (when it ran) and its single
    /// rays at `single`.
    fn scene(
        template: &SceneResult,
        name: &str,
        ours: f64,
        packets: Option<f64>,
        single: f64,
    ) -> SceneResult {
        let mut s = template.clone();
        s.name = name.to_string();
        s.family = SceneFamily::Spd;
        let mut reference = s
            .variants
            .iter()
            .find(|v| v.variant.is_reference())
            .cloned()
            .unwrap_or_else(|| panic!("the sample scene has a reference variant"));
        reference.time.median = ours;
        s.variants = vec![reference.clone()];
        for (tracer, seconds) in [
            ("embree-yardstick", packets),
            ("embree-yardstick-single", Some(single)),
        ] {
            let Some(seconds) = seconds else { continue };
            let mut v = reference.clone();
            v.variant = VariantName::outside(tracer).unwrap_or_else(|e| panic!("{e}"));
            v.time.median = seconds;
            v.quality = None;
            s.variants.push(v);
        }
        s
    }

    #[test]
    fn sets_rtprof_against_the_faster_mode_and_names_the_scenes_behind() {
        let mut r = sample_results();
        let template = r.scenes[0].clone();
        // gears: 90 ms against packets 40 (2.25×) and single 111; rings: 136 against
        // 227 and 247 (the faster mode's 227: 0.599×); tree: packets did not run.
        r.scenes = vec![
            scene(&template, "gears", 0.090, Some(0.040), 0.111),
            scene(&template, "rings", 0.136, Some(0.227), 0.247),
            scene(&template, "tree", 0.063, None, 0.085),
        ];
        let text = sentence(&r).unwrap_or_default();
        // By hand: (2.25 × 136/227 × 63/85)^(1/3).
        let best = (2.25f64 * (0.136 / 0.227) * (0.063 / 0.085)).cbrt();
        assert!(
            text.contains(&format!("takes {} the time", format::speedup(best))),
            "{text}"
        );
        assert!(text.contains("geometric mean over 3 scenes"), "{text}");
        // Packets over its two scenes: sqrt(2.25 × 136/227).
        let packets = (2.25f64 * 0.136 / 0.227).sqrt();
        assert!(
            text.contains(&format!(
                "packets {} over 2 scenes",
                format::speedup(packets)
            )),
            "{text}"
        );
        assert!(text.contains("behind it on gears (2.25×)"), "{text}");
        assert!(!text.contains("rings ("), "{text}");
    }

    #[test]
    fn no_sentence_without_the_yardstick_on_an_spd_scene() {
        let mut r = sample_results();
        for s in &mut r.scenes {
            s.variants.retain(|v| !v.variant.is_outside());
        }
        assert_eq!(sentence(&r), None);
    }
}
