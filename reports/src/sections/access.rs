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
