//! Attribution a user can trust, checked against independent expectations:
//! - known split: the sphere and cylinder tests' costs measured on a scene of only
//!   spheres and a scene of only cylinders predict the sphere : cylinder time ratio of
//!   the mixed scene (the phase view, whatever the optimizer inlined);
//! - the differential flamegraph of baseline against bvh on SPD rings shows the
//!   intersection tests shrinking and the traversal growing.
//!
//! One test function: the sampler is one per process (SIGPROF), so the profiles run in
//! turn.

use std::path::Path;

use analysis::profile::flat::FlatProfile;
use runner::profile_job::{ProfileJob, VariantProfile};
use tracer::{RenderOptions, Sampling, Scene, ShadingMode, VariantSet, parse_nff};

/// Samples per profile of the differential graph: a 95 % interval of about ±4 points on
/// a 50 % share.
const MIN_SAMPLES: u64 = 500;
/// Samples per profile of the known split. The sphere tests are about a tenth of the mixed
/// scene's samples; at 500 samples their count (~55) alone has a 13 % relative error and
/// the ratio check failed one run in ten. At 3,000 it is about 5 %.
const SPLIT_SAMPLES: u64 = 3000;
/// Rounds the split's samples are taken in (see the test). Under perf cpu-clock at 4,000
/// Hz the whole test takes about 7 s (77 s under setitimer) and rounds cost little: in
/// one round, two of six runs predicted 0.30-0.35 against 0.22 measured (ratio 0.64-0.72,
/// a failure); in three, six runs gave ratios 0.88-1.05.
const SPLIT_ROUNDS: u64 = 3;

fn profile(
    scene: &Scene,
    name: &str,
    size: (u32, u32),
    variant: &str,
    min_samples: u64,
) -> VariantProfile {
    let pool = runner::pool::thread_pool(Some(2)).unwrap();
    let job = ProfileJob {
        scene,
        options: RenderOptions::new(size.0, size.1, Sampling::PixelCenters, ShadingMode::Color),
        pool: &pool,
        // The timer's default, as `rtprof profile` (4,000 Hz under perf cpu-clock).
        frequency: None,
        name,
        min_samples,
        stop: &tracer::NEVER_STOP,
    };
    let set = VariantSet::parse(variant).unwrap();
    job.profile(&set, &runner::progress::Silent)
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Self seconds and calls per render of a phase in a flat profile.
fn phase(flat: &FlatProfile, name: &str) -> (f64, u64) {
    let row = flat
        .rows
        .iter()
        .find(|r| r.name == name)
        .unwrap_or_else(|| panic!("no '{name}' row in\n{}", flat.to_text()));
    (row.self_seconds, row.calls.unwrap_or(0))
}

#[test]
fn phase_attribution_follows_the_known_costs_and_the_bvh_diff() {
    // A 3x3x3 lattice: 27 spheres and 54 cylinders, brute force.
    let mixed_text = tracer::generators::lattice(3).unwrap();
    let keep = |drop: &str| -> String {
        mixed_text
            .lines()
            .filter(|l| !l.starts_with(drop))
            .map(|l| format!("{l}\n"))
            .collect()
    };
    let scene = |text: &str, name: &str| parse_nff(text, name).unwrap();
    let spheres = scene(&keep("c "), "spheres");
    let cylinders = scene(&keep("s "), "cylinders");
    let mixed = scene(&mixed_text, "lattice3");
    assert!(spheres.primitive_count() > 0 && cylinders.primitive_count() > 0);
    let size = (64, 48);

    // The three profiles run in interleaved rounds and their figures are summed, so that
    // the machine's speed drifting (other processes on a shared machine, frequency
    // changes) weighs on the three alike: profiled one after the other, the sphere-only
    // cost per test moved between 2.6 and 4.6 ns from run to run on a busy machine.
    let (mut sphere_only, mut cylinder_only) = ((0.0, 0), (0.0, 0));
    let (mut sphere_s, mut cylinder_s, mut sphere_tests, mut cylinder_tests) = (0.0, 0.0, 0, 0);
    let mut both = None;
    for _ in 0..SPLIT_ROUNDS {
        let samples = SPLIT_SAMPLES / SPLIT_ROUNDS;
        let p = profile(&spheres, "spheres", size, "baseline", samples);
        let (s, calls) = phase(&p.phases.flat, "sphere test");
        sphere_only = (sphere_only.0 + s, sphere_only.1 + calls * p.renders);
        let p = profile(&cylinders, "cylinders", size, "baseline", samples);
        let (s, calls) = phase(&p.phases.flat, "cylinder test");
        cylinder_only = (cylinder_only.0 + s, cylinder_only.1 + calls * p.renders);
        let p = profile(&mixed, "lattice3", size, "baseline", samples);
        let (s, calls) = phase(&p.phases.flat, "sphere test");
        (sphere_s, sphere_tests) = (sphere_s + s, calls);
        let (s, calls) = phase(&p.phases.flat, "cylinder test");
        (cylinder_s, cylinder_tests) = (cylinder_s + s, calls);
        both = Some(p);
    }
    let both = both.expect("at least one round");
    // CPU seconds of one test of a kind: its self time over every test of every render.
    assert!(sphere_only.1 > 0 && cylinder_only.1 > 0, "no tests counted");
    let sphere_cost = sphere_only.0 / sphere_only.1 as f64;
    let cylinder_cost = cylinder_only.0 / cylinder_only.1 as f64;
    let measured = sphere_s / cylinder_s;
    let predicted = (sphere_tests as f64 * sphere_cost) / (cylinder_tests as f64 * cylinder_cost);
    eprintln!(
        "sphere test {:.1} ns, cylinder test {:.1} ns; mixed: {sphere_tests} and {cylinder_tests} tests per render; sphere : cylinder time measured {measured:.3}, predicted {predicted:.3}",
        sphere_cost * 1e9,
        cylinder_cost * 1e9
    );
    assert!(
        (measured / predicted - 1.0).abs() <= 0.25,
        "measured {measured:.3} vs predicted {predicted:.3}"
    );

    // Amdahl: all the tests together is one row, their self shares summed (tests are
    // leaves), and its limit is 1 / (1 - share).
    let all = both
        .phases
        .amdahl
        .iter()
        .find(|r| r.name == runner::profile_job::ALL_TESTS)
        .expect("no all-tests row");
    let tests: f64 = both
        .phases
        .flat
        .rows
        .iter()
        .filter(|r| r.name.ends_with(" test"))
        .map(|r| r.percent / 100.0)
        .sum();
    assert!((all.fraction - tests).abs() < 1e-9 && (all.inclusive_fraction - tests).abs() < 1e-9);
    assert!(
        (all.inclusive_speedup_limit - 1.0 / (1.0 - tests)).abs()
            < 1e-6 * all.inclusive_speedup_limit
    );

    // Baseline against bvh on SPD rings: the tests shrink, the traversal grows.
    let rings_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shared/spd/rings.nff");
    let rings = tracer::load_nff(&rings_path).unwrap();
    let base = profile(&rings, "rings", (48, 36), "baseline", MIN_SAMPLES);
    let bvh = profile(&rings, "rings", (48, 36), "bvh", MIN_SAMPLES);
    let dir = std::env::temp_dir().join(format!("rtprof-attribution-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (grown, shrunk) =
        runner::profile_files::save_differential(&dir, "", "rings", &base, &bvh).unwrap();
    let svg = |rel: &str| std::fs::read_to_string(dir.join(rel)).unwrap();
    let (grown, shrunk) = (svg(&grown), svg(&shrunk));
    std::fs::remove_dir_all(&dir).ok();
    // Frame titles end in the change of share: "(N samples, P%; +D%)".
    let change = |svg: &str, frame: &str| -> Option<f64> {
        svg.split("<title>").skip(1).find_map(|part| {
            let title = part.split_once("</title>")?.0;
            let rest = title.strip_prefix(&format!("{frame} ("))?;
            let delta = rest.rsplit_once("; ")?.1.trim_end_matches(')');
            delta.trim_end_matches('%').parse::<f64>().ok()
        })
    };
    for test in ["sphere test", "cylinder test"] {
        let d =
            change(&shrunk, test).unwrap_or_else(|| panic!("no {test} frame in the shrunk graph"));
        assert!(d < 0.0, "{test} should shrink: {d:+}%");
    }
    let d = change(&grown, "traversal").expect("no traversal frame in the grown graph");
    assert!(d > 0.0, "traversal should grow: {d:+}%");
}
