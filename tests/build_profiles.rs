//! The build profiles keep their rules (docs/build-times.md): dependencies build at
//! opt-level 0 without debug info except a list of hot crates, optimised, the same list
//! in the test and release profiles (cargo has no shared lists, so it is written twice
//! and checked here; the test profile may build one at 1 where 3 only costs build time),
//! rtprof's crates that render in the tests optimised and the others not,
//! and every crate the lists name is one the build has (a crate renamed or dropped by an
//! upgrade would otherwise leave its entry silently unused).

use std::collections::BTreeSet;
use toml::Table;

fn manifest() -> Table {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml");
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.parse().unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn lock_names() -> BTreeSet<String> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.lock");
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let lock: Table = text.parse().unwrap_or_else(|e| panic!("{path}: {e}"));
    lock["package"]
        .as_array()
        .expect("Cargo.lock lists packages")
        .iter()
        .map(|p| p["name"].as_str().expect("a package has a name").to_owned())
        .collect()
}

/// The `[profile.<name>.package]` table.
fn overrides(manifest: &Table, profile: &str) -> Table {
    manifest["profile"][profile]["package"]
        .as_table()
        .unwrap_or_else(|| panic!("no [profile.{profile}.package] table"))
        .clone()
}

/// The dependencies a profile optimises (`opt-level` 1 or more), by name, with the level.
fn hot(overrides: &Table, own: &BTreeSet<String>) -> Vec<(String, i64)> {
    overrides
        .iter()
        .filter(|(name, _)| !own.contains(*name))
        .filter_map(|(name, o)| Some((name.clone(), o.get("opt-level")?.as_integer()?)))
        .filter(|(_, level)| *level > 0)
        .collect()
}

/// The workspace's own crates (their overrides are not dependencies').
fn workspace_members(manifest: &Table) -> BTreeSet<String> {
    manifest["workspace"]["members"]
        .as_array()
        .expect("a workspace member list")
        .iter()
        .filter_map(|m| m.as_str())
        .map(|m| m.rsplit('/').next().unwrap_or(m).to_owned())
        .collect()
}

#[test]
fn dependencies_build_unoptimized_without_debug_info_but_the_hot_ones() {
    let manifest = manifest();
    for profile in ["dev", "release"] {
        let all = &overrides(&manifest, profile)["*"];
        assert_eq!(
            all.get("opt-level").and_then(|v| v.as_integer()),
            Some(0),
            "[profile.{profile}.package] \"*\" should build dependencies at opt-level 0"
        );
        assert_eq!(
            all.get("debug").and_then(|v| v.as_bool()),
            Some(false),
            "[profile.{profile}.package] \"*\" should build dependencies without debug info"
        );
    }
    // Unoptimised typst typesets every PDF of the tests; its checks made that slower.
    let all = &overrides(&manifest, "dev")["*"];
    for check in ["debug-assertions", "overflow-checks"] {
        assert_eq!(
            all.get(check).and_then(|v| v.as_bool()),
            Some(false),
            "[profile.dev.package] \"*\" should build dependencies without {check}"
        );
    }
    let own = workspace_members(&manifest);
    let dev = hot(&overrides(&manifest, "dev"), &own);
    let release = hot(&overrides(&manifest, "release"), &own);
    assert!(dev.len() >= 10, "the hot list is nearly empty: {dev:?}");
    let names = |list: &[(String, i64)]| list.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(
        names(&dev),
        names(&release),
        "the hot crates differ between [profile.dev.package] and [profile.release.package]"
    );
    for ((name, in_dev), (_, in_release)) in dev.iter().zip(&release) {
        assert!(
            in_dev <= in_release,
            "{name} is optimised more for the tests ({in_dev}) than in release ({in_release})"
        );
    }
}

/// The tests read function names from sampled stacks (the profile and flat-profile
/// tests), and inlined frames keep their paths only with "limited" debug info or more;
/// "full" costs a sixth more build time for variables no test reads.
#[test]
fn the_test_profile_keeps_the_names_the_profile_tests_read() {
    let dev = &manifest()["profile"]["dev"];
    assert_eq!(dev["debug"].as_str(), Some("limited"));
}

/// rtprof's crates whose tests do no long work build unoptimised for the tests; the ones
/// that render in them (the renderers, the SPD generators, the hardware model's
/// emulator) keep the profile's opt-level 1: unoptimised, their renders take several
/// times as long.
#[test]
fn the_crates_that_render_in_the_tests_stay_optimised() {
    let manifest = manifest();
    let dev = overrides(&manifest, "dev");
    let level = |name: &str| {
        dev.get(name)
            .and_then(|o| o.get("opt-level"))
            .and_then(|v| v.as_integer())
    };
    assert_eq!(
        manifest["profile"]["dev"]["opt-level"].as_integer(),
        Some(1)
    );
    for name in ["tracer", "spd", "hwmodel"] {
        assert!(
            level(name).is_none_or(|l| l >= 1),
            "{name} at {level:?}",
            level = level(name)
        );
    }
    let own = workspace_members(&manifest);
    let unoptimised = own.iter().filter(|n| level(n) == Some(0)).count();
    assert!(
        unoptimised >= 5,
        "only {unoptimised} of rtprof's crates build unoptimised"
    );
}

#[test]
fn the_profiles_name_only_crates_the_build_has() {
    let manifest = manifest();
    let names = lock_names();
    for profile in ["dev", "release"] {
        for name in overrides(&manifest, profile).keys() {
            assert!(
                name == "*" || names.contains(name),
                "[profile.{profile}.package] names {name}, which is not in Cargo.lock"
            );
        }
    }
}

#[test]
fn rtprof_s_own_crates_keep_one_codegen_unit_and_the_profiler_s_debug_info() {
    let release = &manifest()["profile"]["release"];
    assert_eq!(release["codegen-units"].as_integer(), Some(1));
    assert_eq!(release["debug"].as_str(), Some("limited"));
    // tracer holds the renderers (tracer::RenderWith): it must not be split.
    let overrides = overrides(&manifest(), "release");
    assert!(
        overrides
            .get("tracer")
            .is_none_or(|t| t.get("codegen-units").is_none()),
        "tracer is split into several codegen units"
    );
}
