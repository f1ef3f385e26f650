//! The phase stack seen from a render: where each counted event happens, that the
//! phased render draws the plain render's picture, that every thread's stack is empty
//! after a render, and (by hand, in release) what recording the phases costs.

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;
use tracer::counter::{PhaseGuard, STAT_COUNT, enter_phase, phase_depth, phases_of};
use tracer::{
    Counter, NoCount, Phase, Phased, RenderOptions, Sampling, Scene, ShadingMode, Stat, VariantSet,
    phase_names, phase_stack_key, render_variant,
};

fn builtin(name: &str) -> Scene {
    tracer::builtin_scenes::find(name)
        .unwrap_or_else(|| panic!("no builtin {name}"))
        .parse()
        .unwrap_or_else(|e| panic!("{e}"))
}

fn generated(text: Result<String, tracer::generators::GeneratorError>, name: &str) -> Scene {
    let text = text.unwrap_or_else(|e| panic!("{e}"));
    tracer::parse_nff(&text, name).unwrap_or_else(|e| panic!("{e}"))
}

fn options(width: u32, height: u32) -> RenderOptions {
    RenderOptions::new(width, height, Sampling::PixelCenters, ShadingMode::Color)
}

fn variants(list: &str) -> VariantSet {
    VariantSet::parse(list).unwrap_or_else(|e| panic!("{e}"))
}

/// A counter that records phases like [`Phased`] and, at every counted event, the
/// phase stack the thread was in: the probe of where the renderer marks its work.
#[derive(Clone, Debug, Default)]
struct Probe {
    stacks: BTreeMap<usize, BTreeSet<u64>>,
}

impl tracer::RenderWith for Probe {
    fn render_variant(
        scene: &Scene,
        options: &tracer::RenderOptions,
        variants: &VariantSet,
        progress: &(dyn Fn(u64) + Sync),
        stop: &std::sync::atomic::AtomicBool,
    ) -> Result<tracer::VariantRender<Self>, tracer::RenderError> {
        tracer::render_variant_with::<Self>(scene, options, variants, progress, stop)
    }
}

impl Counter for Probe {
    const ENABLED: bool = true;
    const PHASES: bool = true;
    type PhaseGuard = PhaseGuard;

    fn enter_phase(phase: Phase) -> PhaseGuard {
        enter_phase(phase)
    }

    fn tally(&mut self, stat: Stat) {
        self.stacks
            .entry(stat as usize)
            .or_default()
            .insert(phase_stack_key());
    }

    fn merge(&mut self, other: &Self) {
        for (stat, keys) in &other.stacks {
            self.stacks.entry(*stat).or_default().extend(keys);
        }
    }

    fn totals(&self) -> Option<[u64; STAT_COUNT]> {
        None
    }
}

impl Probe {
    /// The phase stacks seen at `stat`, outermost first.
    fn at(&self, stat: Stat) -> Vec<Vec<Phase>> {
        self.stacks
            .get(&(stat as usize))
            .map(|keys| keys.iter().map(|&k| phases_of(k)).collect())
            .unwrap_or_default()
    }
}

fn probe(scene: &Scene, list: &str) -> Probe {
    render_variant::<Probe>(scene, &options(24, 18), &variants(list), &|_| {})
        .unwrap_or_else(|e| panic!("{e}"))
        .rendered
        .counter
}

/// The phase a stack's `level` may sit under (the nesting the renderer's calls make).
fn allowed_parents(phase: Phase, accel_has_traversal: bool) -> Vec<Option<Phase>> {
    use Phase::*;
    let query = if accel_has_traversal {
        vec![Some(Traversal)]
    } else {
        vec![Some(ClosestHit), Some(ShadowQuery)]
    };
    match phase {
        SampleRow => vec![None],
        CameraRay => vec![None, Some(SampleRow)],
        ClosestHit => vec![Some(SampleRow), Some(SecondaryRays)],
        Shading => vec![Some(SampleRow), Some(SecondaryRays)],
        ShadowQuery | SecondaryRays => vec![Some(Shading)],
        Traversal => vec![Some(ClosestHit), Some(ShadowQuery)],
        SphereTest | CylinderTest | ConeTest | PolygonTest | PatchTest | TriangleTest => query,
        PixelFill => vec![None],
    }
}

/// Every stack follows the call nesting of the renderer.
fn check_nesting(probe: &Probe, accel_has_traversal: bool) {
    for keys in probe.stacks.values() {
        for &key in keys {
            let stack = phases_of(key);
            for (level, &phase) in stack.iter().enumerate() {
                let parent = level.checked_sub(1).map(|p| stack[p]);
                assert!(
                    allowed_parents(phase, accel_has_traversal).contains(&parent),
                    "{phase:?} under {parent:?} in {:?}",
                    phase_names(key)
                );
            }
        }
    }
}

fn leaves(stacks: &[Vec<Phase>]) -> BTreeSet<Phase> {
    stacks.iter().filter_map(|s| s.last().copied()).collect()
}

#[test]
fn nested_phases_give_the_stack_outermost_first() {
    let key = Phased::in_phase(Phase::SampleRow, || {
        Phased::in_phase(Phase::Shading, || {
            Phased::in_phase(Phase::SecondaryRays, || {
                Phased::in_phase(Phase::ClosestHit, || {
                    Phased::in_phase(Phase::Traversal, || {
                        Phased::in_phase(Phase::SphereTest, phase_stack_key)
                    })
                })
            })
        })
    });
    assert_eq!(
        phase_names(key),
        [
            "sample row",
            "shading",
            "reflection/refraction set-up",
            "closest hit",
            "traversal",
            "sphere test"
        ]
    );
    // The plain counter records nothing.
    assert_eq!(NoCount::in_phase(Phase::SphereTest, phase_stack_key), 0);
    assert_eq!(phase_stack_key(), 0);
}

#[test]
fn every_primitive_test_is_its_kinds_phase_under_the_query_or_the_traversal() {
    let scene = builtin("primitives");
    let tests = [
        (Stat::SphereTest, Phase::SphereTest),
        (Stat::CylinderTest, Phase::CylinderTest),
        (Stat::ConeTest, Phase::ConeTest),
        (Stat::PolygonTest, Phase::PolygonTest),
        (Stat::PatchTest, Phase::PatchTest),
    ];
    for (list, traversal) in [
        ("baseline", false),
        ("bvh", true),
        ("simd", false),
        ("bounded", false),
    ] {
        let p = probe(&scene, list);
        check_nesting(&p, traversal);
        for (stat, phase) in tests {
            let stacks = p.at(stat);
            assert!(!stacks.is_empty(), "{list}: no {stat:?}");
            assert_eq!(leaves(&stacks), BTreeSet::from([phase]), "{list}: {stat:?}");
            // Eye rays test every kind; shadow rays test the quadrics at least (with a
            // BVH no shadow ray from above reaches the floor's leaf).
            let queries: BTreeSet<Phase> = stacks
                .iter()
                .map(|s| s[s.len() - if traversal { 3 } else { 2 }])
                .collect();
            assert!(queries.contains(&Phase::ClosestHit), "{list}: {stat:?}");
            if matches!(stat, Stat::SphereTest | Stat::CylinderTest) || !traversal {
                assert!(queries.contains(&Phase::ShadowQuery), "{list}: {stat:?}");
            }
        }
        assert_eq!(leaves(&p.at(Stat::Shade)), BTreeSet::from([Phase::Shading]));
        assert_eq!(
            leaves(&p.at(Stat::PrimaryRaySetup)),
            BTreeSet::from([Phase::CameraRay])
        );
        assert_eq!(
            leaves(&p.at(Stat::Intersect)),
            BTreeSet::from([Phase::ClosestHit, Phase::ShadowQuery])
        );
        if traversal {
            assert_eq!(
                leaves(&p.at(Stat::NodesVisited)),
                BTreeSet::from([Phase::Traversal])
            );
        }
        // The glass sphere and the mirror floor: secondary rays recurse through
        // shading > set-up, several levels deep.
        let deepest_shading = p
            .at(Stat::Shade)
            .iter()
            .map(|s| s.iter().filter(|&&x| x == Phase::Shading).count())
            .max();
        assert!(deepest_shading >= Some(3), "{list}: {deepest_shading:?}");
    }
}

#[test]
fn the_wide_bvh_tests_polygons_and_patches_as_triangles_in_their_own_phase() {
    let p = probe(&builtin("primitives"), "bvh+simd");
    check_nesting(&p, true);
    let stacks = p.at(Stat::TriangleTest);
    assert!(!stacks.is_empty(), "no triangle test");
    assert_eq!(leaves(&stacks), BTreeSet::from([Phase::TriangleTest]));
    // The outlines are tested as triangles only: no polygon or patch test is left.
    assert!(p.at(Stat::PolygonTest).is_empty() && p.at(Stat::PatchTest).is_empty());
}

#[test]
fn a_sphere_test_under_the_bvh_is_closest_hit_traversal_sphere_test() {
    let p = probe(&builtin("primitives"), "bvh");
    let eye: Vec<Vec<&str>> = p
        .at(Stat::SphereTest)
        .into_iter()
        .filter(|s| s.len() == 4)
        .map(|s| s.into_iter().map(Phase::name).collect())
        .collect();
    assert!(
        eye.contains(&vec![
            "sample row",
            "closest hit",
            "traversal",
            "sphere test"
        ]),
        "{eye:?}"
    );
    let shadow = p.at(Stat::CylinderTest).into_iter().any(|s| {
        s == [
            Phase::SampleRow,
            Phase::Shading,
            Phase::ShadowQuery,
            Phase::Traversal,
            Phase::CylinderTest,
        ]
    });
    assert!(shadow);
}

#[test]
fn the_phased_render_draws_the_plain_renders_picture() {
    let scenes = [
        builtin("primitives"),
        generated(tracer::generators::lattice(3), "lattice3"),
    ];
    for scene in &scenes {
        for list in [
            "baseline",
            "bvh",
            "simd",
            "bounded",
            "pixel-avg",
            "fast-sqrt",
        ] {
            let set = variants(list);
            for sampling in [Sampling::PixelCenters, Sampling::SpdCorners] {
                let opts = RenderOptions::new(20, 15, sampling, ShadingMode::Color);
                let plain = render_variant::<NoCount>(scene, &opts, &set, &|_| {})
                    .unwrap_or_else(|e| panic!("{e}"))
                    .rendered;
                let phased = render_variant::<Phased>(scene, &opts, &set, &|_| {})
                    .unwrap_or_else(|e| panic!("{e}"))
                    .rendered;
                assert_eq!(plain.frame.pixels, phased.frame.pixels, "{list}");
                assert_eq!(plain.rays, phased.rays, "{list}");
                assert!(phased.counts().is_none());
            }
        }
    }
}

#[test]
fn every_threads_stack_is_empty_after_a_render_and_rows_are_roots() {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let scene = builtin("primitives");
    let row_keys = std::sync::Mutex::new(BTreeSet::new());
    let record = |_: u64| {
        if let Ok(mut keys) = row_keys.lock() {
            keys.insert(phase_stack_key());
        }
    };
    for list in ["baseline", "bvh", "simd", "pixel-avg"] {
        pool.install(|| {
            render_variant::<Phased>(&scene, &options(24, 18), &variants(list), &record)
        })
        .unwrap_or_else(|e| panic!("{e}"));
        let depths = pool.broadcast(|_| (phase_depth(), phase_stack_key()));
        assert_eq!(depths, vec![(0, 0); 3], "{list}");
        assert_eq!((phase_depth(), phase_stack_key()), (0, 0));
    }
    // The progress call runs at the end of each row, inside the row's phase only.
    let keys = row_keys.into_inner().unwrap_or_default();
    assert_eq!(keys, BTreeSet::from([Phase::SampleRow as u64]));
}

/// Median of a few timings, in seconds.
fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    xs[xs.len() / 2]
}

/// On-CPU nanoseconds of the calling thread so far (Linux's schedstat), if readable.
fn thread_cpu_ns() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

/// Wall and on-CPU seconds per render of `batch` renders of `scene` with counter `C`
/// (the CPU time is the calling thread's: call it on the pool's one worker).
fn time_renders<C: tracer::RenderWith>(scene: &Scene, set: &VariantSet, batch: u32) -> (f64, f64) {
    let opts = options(320, 240);
    let cpu = thread_cpu_ns();
    let start = Instant::now();
    for _ in 0..batch {
        let out = render_variant::<C>(scene, &opts, set, &|_| {});
        assert!(out.is_ok());
    }
    let wall = start.elapsed().as_secs_f64();
    let cpu = match (cpu, thread_cpu_ns()) {
        (Some(a), Some(b)) => (b - a) as f64 * 1e-9,
        _ => f64::NAN,
    };
    (wall / f64::from(batch), cpu / f64::from(batch))
}

/// The phase recording's cost: the three scenes at the suite's profile size (320x240)
/// with `baseline`, `bvh` and `simd`, plain and phased renders interleaved, 5 timings
/// of each (each a batch of at least ~0.3 s), on one worker thread so that other
/// processes disturb the two alike; the thread's on-CPU time is timed beside the wall
/// time (it leaves out the time other processes hold the core, but is kept in coarse
/// ticks on some kernels). Prints the medians' ratios.
#[test]
#[ignore = "timing; run by hand in release"]
fn phase_overhead() {
    let scenes = [
        (
            "lattice5",
            generated(tracer::generators::lattice(5), "lattice5"),
        ),
        (
            "sphereflake2",
            generated(tracer::generators::sphereflake(2), "sphereflake2"),
        ),
        ("both7", builtin("both7")),
    ];
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    // Everything runs on the pool's one worker, so its CPU time covers the renders.
    pool.install(|| {
        for list in ["baseline", "bvh", "simd"] {
            let set = variants(list);
            for (name, scene) in &scenes {
                let (once, _) = time_renders::<NoCount>(scene, &set, 1);
                let batch = (0.3 / once).ceil().clamp(1.0, 1000.0) as u32;
                let (mut plain, mut phased) = (Vec::new(), Vec::new());
                for _ in 0..5 {
                    plain.push(time_renders::<NoCount>(scene, &set, batch));
                    phased.push(time_renders::<Phased>(scene, &set, batch));
                }
                let wall = |xs: &[(f64, f64)]| median(xs.iter().map(|x| x.0).collect());
                let cpu = |xs: &[(f64, f64)]| median(xs.iter().map(|x| x.1).collect());
                println!(
                    "{list:8} {name:12} NoCount {:8.3} ms  Phased {:8.3} ms  ratio {:.3} wall \
                     ({:.3} on-CPU)  ({batch} renders per timing)",
                    wall(&plain) * 1e3,
                    wall(&phased) * 1e3,
                    wall(&phased) / wall(&plain),
                    cpu(&phased) / cpu(&plain),
                );
            }
        }
    });
}
