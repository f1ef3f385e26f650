//! The groups of scenes a report shows variants by, in order: the families that answer
//! different questions (the thesis's test bench, the SPD, generated scenes, the rest).

use crate::results::SceneFamily;

/// The families of scenes a report groups variants by, in order: the thesis's test
/// bench (its three families together), the SPD, generated scenes, the rest.
pub const FAMILY_GROUPS: [(&str, &[SceneFamily]); 4] = [
    (
        "thesis test bench",
        &[SceneFamily::Balls, SceneFamily::Cylinder, SceneFamily::Both],
    ),
    ("SPD", &[SceneFamily::Spd]),
    ("generated", &[SceneFamily::Generated]),
    ("other", &[SceneFamily::Other]),
];
