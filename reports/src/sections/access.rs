//! Small readers of the results types that several section builders share.

use crate::results::{Results, SceneFamily, SceneResult, VariantResult};

/// The reference variant's result on a scene, if it ran.
pub fn reference<'a>(r: &Results, scene: &'a SceneResult) -> Option<&'a VariantResult> {
    r.baseline(scene)
}

/// Whether a scene is one of the Standard Procedural Databases.
pub fn is_spd(scene: &SceneResult) -> bool {
    scene.spd || scene.family == SceneFamily::Spd
}

/// The speed-up over baseline, NaN when there is none.
pub fn speedup(v: &VariantResult) -> f64 {
    v.speedup.unwrap_or(f64::NAN)
}

/// The scene a section's sentence speaks of: the profiled scene (the run's heaviest)
/// when it has what the sentence needs (`has`), else the first scene that does.
pub fn headline_scene(r: &Results, has: impl Fn(&SceneResult) -> bool) -> Option<&SceneResult> {
    let profiled = r
        .profile
        .as_ref()
        .and_then(|p| r.scenes.iter().find(|s| s.name == p.scene))
        .filter(|s| has(s));
    profiled.or_else(|| r.scenes.iter().find(|s| has(s)))
}

/// The fastest variant of a scene (the least median time).
pub fn fastest(scene: &SceneResult) -> Option<&VariantResult> {
    scene
        .variants
        .iter()
        .filter(|v| v.time.median > 0.0)
        .min_by(|a, b| a.time.median.total_cmp(&b.time.median))
}
