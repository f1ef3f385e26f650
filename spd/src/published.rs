//! The ray statistics the SPD publishes for its seven classic scenes (SPD 3.14
//! `Readme.txt`, the table after the scene descriptions): 513 × 513 eye rays through
//! pixel corners, maximum depth 5, the testing procedure's rules. "Classical ray tracers
//! should all be within about 10 %" of them, so they check a tracer's shading rules.

/// The published counts of one scene at its default size factor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PublishedStatistics {
    pub scene: &'static str,
    /// Eye rays: 513 × 513 for every scene.
    pub eye_rays: u64,
    /// Eye rays that hit an object.
    pub eye_hits: u64,
    /// Rays reflected off reflecting and transmitting surfaces.
    pub reflection_rays: u64,
    /// Rays refracted by transmitting surfaces.
    pub refraction_rays: u64,
    /// Rays shot toward the lights.
    pub shadow_rays: u64,
}

/// The frame the figures are for: 512 × 512 pixels, corner rays.
pub const FRAME: (u32, u32) = (512, 512);

/// Maximum ray-tree depth of the figures (the eye ray is depth 1).
pub const MAX_DEPTH: u32 = 5;

/// How far a classical tracer may be from the figures ("within about 10 %").
pub const TOLERANCE: f64 = 0.10;

const EYE_RAYS: u64 = 513 * 513;

/// The table, in [`crate::CLASSIC`] order.
pub const PUBLISHED: [PublishedStatistics; 7] = [
    stats("balls", 263_169, 175_095, 0, 954_368),
    stats("gears", 245_086, 304_643, 207_564, 2_246_955),
    stats("mount", 173_125, 354_769, 354_769, 412_922),
    stats("rings", 263_169, 315_236, 0, 1_085_002),
    stats("teapot", 161_120, 225_248, 0, 407_656),
    stats("tetra", 49_788, 0, 0, 46_112),
    stats("tree", 169_836, 0, 0, 1_097_419),
];

const fn stats(
    scene: &'static str,
    eye_hits: u64,
    reflection_rays: u64,
    refraction_rays: u64,
    shadow_rays: u64,
) -> PublishedStatistics {
    PublishedStatistics {
        scene,
        eye_rays: EYE_RAYS,
        eye_hits,
        reflection_rays,
        refraction_rays,
        shadow_rays,
    }
}

/// The published figures of `scene` (a classic SPD name), if there are any.
pub fn published(scene: &str) -> Option<&'static PublishedStatistics> {
    PUBLISHED.iter().find(|p| p.scene == scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_classic_scene_has_figures_and_only_those() {
        for name in crate::CLASSIC {
            assert_eq!(published(name).map(|p| p.scene), Some(name));
        }
        assert_eq!(published("jacks"), None);
        // The eye rays bound the hits: at most every one hits (balls and rings do).
        for p in PUBLISHED {
            assert!(p.eye_hits <= p.eye_rays, "{}", p.scene);
        }
        assert_eq!(published("rings").map(|p| p.eye_hits), Some(513 * 513));
    }
}
