//! The outside tracers rtprof ships definitions for (`runner/tracers/*.toml`): POV-Ray
//! 3.7 and Tachyon, as Debian installs them; the Embree yardstick (peers/embree/, built
//! by scripts/build-embree-peer.sh) in its packet and its single-ray mode; and rtprof
//! itself as its users run it (a whole process, what a peer timed as a whole process is
//! set against). `--tracer NAME` names one, and `--peers` runs every one that is
//! installed.

use super::definition::TracerDef;
use crate::error::RunError;

/// Each built-in peer: its name and its definition's text.
pub const PEERS: [(&str, &str); 5] = [
    ("povray", include_str!("../../tracers/povray.toml")),
    ("tachyon", include_str!("../../tracers/tachyon.toml")),
    (
        "embree-yardstick",
        include_str!("../../tracers/embree-yardstick.toml"),
    ),
    (
        "embree-yardstick-single",
        include_str!("../../tracers/embree-yardstick-single.toml"),
    ),
    ("rtprof", include_str!("../../tracers/rtprof.toml")),
];

/// The built-in definition called `name`, if there is one.
pub fn peer(name: &str) -> Option<Result<TracerDef, RunError>> {
    PEERS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| TracerDef::parse(text, &format!("built-in {n}.toml")))
}

/// The built-in peers, each with whether its program is installed.
pub fn peers() -> Result<Vec<(TracerDef, bool)>, RunError> {
    PEERS
        .iter()
        .map(|(n, text)| {
            let def = TracerDef::parse(text, &format!("built-in {n}.toml"))?;
            let installed = def.command.first().is_some_and(|p| {
                p == "{rtprof}" || launch::resolve(std::ffi::OsStr::new(p)).is_ok()
            });
            Ok((def, installed))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_built_in_definitions_are_valid_and_named_as_listed() {
        for (name, _) in PEERS {
            let def = peer(name).unwrap().unwrap();
            assert_eq!(def.name, name);
            assert!(def.deterministic);
        }
        // `embree` names rtprof's own Embree variant, not a peer.
        assert!(peer("embree").is_none());
        assert!(peer("embree-yardstick").is_some());
    }

    #[test]
    fn the_embree_yardstick_is_asked_for_the_variants_shading_and_depth() {
        for name in ["embree-yardstick", "embree-yardstick-single"] {
            let def = peer(name).unwrap().unwrap();
            assert_eq!(def.command[0], "rtprof-embree");
            let line = def.command.join(" ");
            assert!(
                line.contains("--shading {shading} --depth {depth}"),
                "{line}"
            );
            assert!(matches!(
                def.time,
                super::super::TimeSource::Printout { .. }
            ));
        }
    }
}
