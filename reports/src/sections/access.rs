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

/// The scenes and variants of `(scene, variant)` rows, as a scene × variant table lays
/// them out: scenes in the rows' order, variants in the suite's order (then any other,
/// as met), each once.
pub fn pivot<'a>(
    r: &'a Results,
    rows: &[(&'a SceneResult, &'a VariantResult)],
) -> (Vec<&'a SceneResult>, Vec<&'a str>) {
    let mut variants: Vec<&str> = r.suite.variants.iter().map(|v| v.as_str()).collect();
    let mut scenes: Vec<&SceneResult> = Vec::new();
    for (scene, v) in rows {
        if !variants.contains(&v.variant.as_str()) {
            variants.push(v.variant.as_str());
        }
        if !scenes.iter().any(|s| std::ptr::eq(*s, *scene)) {
            scenes.push(scene);
        }
    }
    (scenes, variants)
}

/// The row of `rows` for `scene` and `variant`, if any.
pub fn pivot_cell<'a>(
    rows: &[(&'a SceneResult, &'a VariantResult)],
    scene: &SceneResult,
    variant: &str,
) -> Option<&'a VariantResult> {
    rows.iter()
        .find(|(s, v)| std::ptr::eq(*s, scene) && v.variant.as_str() == variant)
        .map(|(_, v)| *v)
}
