//! A realistic synthetic suite run, for tests and for the report's look.
//!
//! [`sample_results`] builds a [`Results`] that exercises every part of the schema:
//! test-bench scenes (`balls`, `cylinder`, `both` with 1 to 7 primitives) at 640x480,
//! one SPD scene (`rings`, 8402 primitives) at 320x240, six variants with times,
//! intervals, speed-ups, exact counts and image metrics, a profile of `rings`
//! (baseline and `bvh`), the hardware model's tables 7 and 8 (computed by `hwmodel`
//! for the thesis's design, with the thesis's figures it holds), two devices, machine and build
//! information, three criterion estimates with their instruction counts and one failure;
//! the machine's measured peaks, every variant's roofline point and rays per second,
//! `simd`'s lane utilization, both BVH builders' quality on `rings` and the per-pixel
//! maps of `rings` for baseline, `bvh` and `simd` (their files are not written). The
//! numbers are made up but consistent with each other (speed-ups are baseline median /
//! variant median, counts follow from the ray counts, histograms sum to the pixel
//! count, achieved GFLOP/s are the flops over the median time, time shares sum to 1).
//! [`crate::files::write_sample_files`] writes the files it refers to.

use std::collections::BTreeMap;

mod pixel_maps;
mod profile;
mod scene_spec;
mod synthesis;
use pixel_maps::sample_pixel_maps;
use profile::{BASELINE_FLAT, BVH_FLAT, sample_profile};
use scene_spec::{SceneSpec, variant_name};
use synthesis::sample_synthesis;

use results::{
    Band, Build, BvhQuality, CodeKind, CriterionEstimate, DeviceUse, Efficiency, Estimate,
    FailedPart, Failure, HardwareResult, HwRow, InstructionCount, Machine, MachinePeak,
    ProfileResult, Quality, RayRates, Results, SCHEMA, SceneFamily, SceneHardware, SceneResult,
    SuiteInfo, TimeCovers, TimingPolicy, VariantName, VariantResult,
};

/// The variants of the sample, baseline first.
pub const SAMPLE_VARIANTS: [&str; 6] =
    ["baseline", "simd", "bvh", "fast-sqrt", "ortho", "pixel-avg"];

/// Frame-time constants of the thesis's design (eq. 49): 50 MHz, 3 cycles per primitive.
const HW_CLOCK_HZ: f64 = 50e6;
const HW_FILL_CYCLES: u64 = 342;

const SCENES: [SceneSpec; 11] = [
    tb("balls1", SceneFamily::Balls, 1, 0),
    tb("balls2", SceneFamily::Balls, 2, 0),
    tb("balls4", SceneFamily::Balls, 4, 0),
    tb("balls7", SceneFamily::Balls, 7, 0),
    tb("cylinder1", SceneFamily::Cylinder, 0, 1),
    tb("cylinder4", SceneFamily::Cylinder, 0, 4),
    tb("cylinder7", SceneFamily::Cylinder, 0, 7),
    tb("both1", SceneFamily::Both, 1, 0),
    tb("both5", SceneFamily::Both, 3, 2),
    tb("both7", SceneFamily::Both, 4, 3),
    SceneSpec {
        name: "rings",
        family: SceneFamily::Spd,
        spheres: 4200,
        cylinders: 4200,
        polygons: 2,
        width: 320,
        height: 240,
    },
];

const fn tb(name: &'static str, family: SceneFamily, spheres: u64, cylinders: u64) -> SceneSpec {
    SceneSpec {
        name,
        family,
        spheres,
        cylinders,
        polygons: 0,
        width: 640,
        height: 480,
    }
}

impl SceneSpec {
    fn primitives(&self) -> u64 {
        self.spheres + self.cylinders + self.polygons
    }
    fn is_spd(&self) -> bool {
        matches!(self.family, SceneFamily::Spd)
    }
    fn pixels(&self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }
}

/// A deterministic number in [0, 1) from a string (FNV-1a, then a mix).
fn unit_hash(key: &str) -> f64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in key.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h ^= h >> 33;
    h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
    h ^= h >> 33;
    (h >> 11) as f64 / (1u64 << 53) as f64
}

/// Baseline median time of a scene, seconds.
fn baseline_seconds(s: &SceneSpec) -> f64 {
    if s.is_spd() {
        return 3.87;
    }
    let jitter = 1.0 + 0.15 * (unit_hash(s.name) - 0.5);
    (0.0062 + 0.0021 * s.spheres as f64 + 0.0034 * s.cylinders as f64) * jitter
}

/// Speed-up of a variant over baseline on a scene.
fn variant_speedup(s: &SceneSpec, variant: &str) -> f64 {
    let n = s.primitives() as f64;
    let jitter = 1.0 + 0.06 * (unit_hash(&format!("{}/{variant}", s.name)) - 0.5);
    let base = match variant {
        "baseline" => return 1.0,
        "simd" if s.is_spd() => 2.1,
        "simd" => 1.45 + 0.04 * n,
        "bvh" if s.is_spd() => 37.5,
        "bvh" => 0.86 + 0.05 * n,
        "fast-sqrt" => 1.06,
        "ortho" => 1.13,
        "pixel-avg" => 1.88,
        _ => 1.0,
    };
    base * jitter
}

/// RMS of a variant's image against baseline on a scene.
fn variant_rms(s: &SceneSpec, variant: &str) -> f64 {
    let u = unit_hash(&format!("rms/{}/{variant}", s.name));
    match variant {
        "fast-sqrt" => 5.0 + 1.6 * s.cylinders.min(7) as f64 + 2.0 * u,
        "ortho" => 24.0 + 4.0 * s.primitives().min(7) as f64 + 3.0 * u,
        "pixel-avg" => 3.0 + 5.0 * u,
        _ => 0.0,
    }
}

/// Exact counts of one render, flattened like the runner writes them.
fn sample_counts(s: &SceneSpec, variant: &str) -> BTreeMap<String, u64> {
    let pixels = s.pixels();
    let lights: u64 = if s.is_spd() { 3 } else { 1 };
    let coverage = if s.is_spd() {
        0.72
    } else {
        (0.08 + 0.06 * s.primitives() as f64).min(0.6)
    };
    let primary = if variant == "pixel-avg" {
        pixels.div_ceil(2)
    } else {
        pixels
    };
    let primary_hit = (primary as f64 * coverage) as u64;
    // Test-bench materials are diffuse: no reflection rays there.
    let reflection = if s.is_spd() { primary_hit * 2 / 3 } else { 0 };
    let reflection_hit = reflection * 2 / 5;
    let shaded = primary_hit + reflection_hit;
    let shadow = shaded * lights;
    let shadow_blocked = shadow / 7;
    let rays = primary + reflection + shadow;
    let bvh = variant == "bvh";
    let tests_per_ray = |count: u64| -> u64 {
        if count == 0 {
            0
        } else if bvh {
            // A BVH visits a logarithmic number of leaves.
            (((count as f64).log2().max(1.0) * 1.6).ceil() as u64).min(count)
        } else {
            count
        }
    };
    let sphere_tests = rays * tests_per_ray(s.spheres);
    let cylinder_tests = rays * tests_per_ray(s.cylinders);
    let polygon_tests = rays * tests_per_ray(s.polygons);
    let normalize = if variant == "ortho" {
        shaded * 2
    } else {
        primary + shaded * 2 + reflection
    };
    let dot = sphere_tests * 2 + cylinder_tests * 6 + polygon_tests * 2 + shaded * (3 + lights);
    let sub = sphere_tests + cylinder_tests * 2 + polygon_tests * 3 + shaded * 2;
    let sqrt = normalize + (sphere_tests + cylinder_tests) / 4 + shaded;
    let (nodes, leaves) = if bvh {
        let depth = (s.primitives() as f64).log2().ceil().max(1.0) as u64;
        (rays * depth * 2, rays * tests_per_ray(s.primitives()) / 2)
    } else {
        (0, 0)
    };
    let sphere_hits = if s.primitives() == 0 {
        0
    } else {
        shaded * s.spheres / s.primitives()
    };
    let cylinder_hits = shaded.saturating_sub(sphere_hits);
    let rows: [(&str, u64); 33] = [
        ("calls.primary_ray_setup", 1),
        ("calls.trace", primary + reflection),
        ("calls.intersect", rays),
        ("calls.shade", shaded),
        ("calls.color_contribution", shaded * lights),
        ("ops.add", shaded * (2 + lights) + primary),
        ("ops.sub", sub),
        ("ops.cross", 2),
        ("ops.dot", dot),
        ("ops.normalize", normalize),
        ("ops.scale", primary * 3 + shaded * (2 + lights)),
        ("ops.sqrt", sqrt),
        ("ops.pow", if s.is_spd() { shaded * lights } else { 0 }),
        ("tests.sphere.tests", sphere_tests),
        ("tests.sphere.hits", sphere_hits),
        ("tests.cylinder.tests", cylinder_tests),
        ("tests.cylinder.hits", cylinder_hits),
        ("tests.cone.tests", 0),
        ("tests.cone.hits", 0),
        ("tests.polygon.tests", polygon_tests),
        (
            "tests.polygon.hits",
            if s.polygons > 0 { shaded / 9 } else { 0 },
        ),
        ("tests.patch.tests", 0),
        ("tests.patch.hits", 0),
        ("tests.plane.tests", 0),
        ("tests.plane.hits", 0),
        ("rays.primary", primary),
        ("rays.primary_hit", primary_hit),
        ("rays.shadow", shadow),
        ("rays.shadow_blocked", shadow_blocked),
        ("rays.reflection", reflection),
        ("rays.refraction", 0),
        ("accel.nodes_visited", nodes),
        ("accel.leaves_visited", leaves),
    ];
    rows.iter().map(|(k, v)| ((*k).to_string(), *v)).collect()
}

/// A 256-bin gray histogram summing to `pixels`: a background peak and a bump of
/// object pixels around `centre`.
fn sample_histogram(pixels: u64, object_pixels: u64, centre: f64, spread: f64) -> Vec<u64> {
    let weights: Vec<f64> = (0..256)
        .map(|i| {
            let z = (i as f64 - centre) / spread;
            (-0.5 * z * z).exp()
        })
        .collect();
    let total: f64 = weights.iter().sum();
    let mut bins: Vec<u64> = weights
        .iter()
        .map(|w| (w / total * object_pixels as f64) as u64)
        .collect();
    let used: u64 = bins.iter().sum();
    // Background (dark gray) takes the rest, so the bins sum to the pixel count.
    bins[12] += pixels.saturating_sub(used);
    bins
}

/// Timed repeats around a median, and their estimate.
fn sample_times(median: f64, key: &str) -> (Estimate, Vec<f64>) {
    let spread = 0.01 + 0.02 * unit_hash(key);
    let offsets = [-1.1, -0.4, 0.0, 0.6, 2.3];
    let samples: Vec<f64> = offsets
        .iter()
        .map(|o| median * (1.0 + o * spread))
        .collect();
    let estimate = Estimate {
        median,
        low: median * (1.0 - 0.9 * spread),
        high: median * (1.0 + 1.4 * spread),
    };
    (estimate, samples)
}

fn image_path(scene: &str, what: &str) -> String {
    format!("images/{scene}-{what}.png")
}

/// The sample machine's measured peaks: two cores with AVX2 and FMA, a modest memory bus.
fn sample_peak() -> MachinePeak {
    MachinePeak {
        peak_gflops: 148.6,
        bandwidth_gbs: 11.8,
        // L1-resident triad: two cores' loads and stores at a few bytes a cycle each.
        cache_bandwidth_gbs: 190.0,
        threads: 2,
        fma_kernel: "AVX2+FMA, 8 lanes × 10 chains".to_string(),
        stream_bytes: 3 * 4 * (8 << 20),
        // The same chains one lane wide: a fifth of the SIMD peak on the sample
        // machine (eight lanes, but one lane's scalar FMAs issue at a higher clock).
        scalar_peak_gflops: Some(29.72),
        scalar_kernel: Some("scalar FMA, 1 lane × 10 chains".to_string()),
    }
}

/// Flops the sample charges each counted vector operation (a dot product: three
/// multiplies and two adds).
const SAMPLE_FLOPS: [(&str, u64); 8] = [
    ("ops.dot", 5),
    ("ops.sub", 3),
    ("ops.add", 3),
    ("ops.cross", 9),
    ("ops.scale", 3),
    ("ops.normalize", 9),
    ("ops.sqrt", 1),
    ("ops.pow", 1),
];

/// Bytes the sample's traffic model charges a primitive test (a record of five
/// floats), a SIMD lane (the same record in structure-of-arrays form), a BVH node and
/// a leaf visited: every byte asked of the memory system, wherever it is found, as the
/// cache-aware roofline counts them.
const TEST_BYTES: u64 = 20;
const LANE_BYTES: u64 = 20;
const NODE_BYTES: u64 = 32;
const LEAF_BYTES: u64 = 8;

/// The lanes of the sample's SIMD variant.
const SIMD_LANES: u64 = 8;

/// SIMD lanes one ray issues: whole chunks of spheres and of cylinders.
fn lanes_per_ray(s: &SceneSpec) -> u64 {
    s.spheres.div_ceil(SIMD_LANES) * SIMD_LANES + s.cylinders.div_ceil(SIMD_LANES) * SIMD_LANES
}

/// The share of `simd`'s lanes that hold a primitive.
fn lane_utilization(s: &SceneSpec) -> f64 {
    (s.spheres + s.cylinders) as f64 / lanes_per_ray(s).max(1) as f64
}

/// A variant's roofline point, from its counts and median time.
fn sample_efficiency(
    s: &SceneSpec,
    variant: &str,
    counts: &BTreeMap<String, u64>,
    median: f64,
) -> Efficiency {
    let get = |k: &str| counts.get(k).copied().unwrap_or(0);
    let flops: u64 = SAMPLE_FLOPS.iter().map(|(k, w)| get(k) * w).sum();
    let tests: u64 = counts
        .iter()
        .filter(|(k, _)| k.starts_with("tests.") && k.ends_with(".tests"))
        .map(|(_, n)| n)
        .sum();
    let primitive_bytes = if variant == "simd" {
        let vector_tests = get("tests.sphere.tests") + get("tests.cylinder.tests");
        lanes_per_ray(s) * get("calls.intersect") * LANE_BYTES + (tests - vector_tests) * TEST_BYTES
    } else {
        tests * TEST_BYTES
    };
    let bytes_moved = primitive_bytes
        + get("accel.nodes_visited") * NODE_BYTES
        + get("accel.leaves_visited") * LEAF_BYTES;
    let arithmetic_intensity = flops as f64 / bytes_moved as f64;
    let achieved_gflops = flops as f64 / median / 1e9;
    let code = VariantName::parse(variant).map_or(CodeKind::Scalar, |v| CodeKind::of_variant(&v));
    let roof = sample_peak().roof(code, arithmetic_intensity).gflops;
    Efficiency {
        flops,
        bytes_moved,
        arithmetic_intensity,
        achieved_gflops,
        roof_gflops: Some(roof),
        fraction_of_roof: Some(achieved_gflops / roof),
    }
}

/// A variant's time split by ray kind and its rays per second: the queries take most of
/// a brute-force render's time and less of a tree's; a shadow ray (any hit) costs 0.6
/// of a closest-hit ray.
fn sample_ray_rates(
    s: &SceneSpec,
    variant: &str,
    counts: &BTreeMap<String, u64>,
    median: f64,
) -> RayRates {
    let get = |k: &str| counts.get(k).copied().unwrap_or(0) as f64;
    let (eye, secondary, shadow) = (
        get("rays.primary"),
        get("rays.reflection") + get("rays.refraction"),
        get("rays.shadow"),
    );
    let queries = if variant == "bvh" { 0.72 } else { 0.9 };
    let weight = eye + secondary + 0.6 * shadow;
    let share = |rays: f64, cost: f64| queries * cost * rays / weight;
    let (eye_fraction, secondary_fraction, shadow_fraction) =
        (share(eye, 1.0), share(secondary, 1.0), share(shadow, 0.6));
    let rate = |rays: f64, fraction: f64| {
        (rays > 0.0 && fraction > 0.0).then(|| rays / (fraction * median) / 1e6)
    };
    RayRates {
        eye_fraction,
        secondary_fraction,
        shadow_fraction,
        // The sample's workers never wait: a large frame has rows for every thread.
        other_fraction: 1.0 - queries,
        idle_fraction: 0.0,
        eye_mrays_per_s: rate(eye, eye_fraction),
        secondary_mrays_per_s: rate(secondary, secondary_fraction),
        shadow_mrays_per_s: rate(shadow, shadow_fraction),
        all_mrays_per_s: (eye + secondary + shadow) / median / 1e6,
        clock_overhead: 1.06 + 0.1 * unit_hash(&format!("clock/{}/{variant}", s.name)),
    }
}

fn sample_variant(s: &SceneSpec, variant: &str, base_median: f64) -> VariantResult {
    let speedup = variant_speedup(s, variant);
    let median = base_median / speedup;
    let (time, samples) = sample_times(median, &format!("t/{}/{variant}", s.name));
    let counts = sample_counts(s, variant);
    let quality_of = |rms: f64| Quality {
        rms,
        band: Band::of(rms),
        psnr: (rms > 0.0).then(|| 20.0 * (255.0 / rms).log10()),
        ssim: if rms > 0.0 { 1.0 - rms / 260.0 } else { 1.0 },
        max_abs_diff: (rms * 4.2).min(255.0) as u32,
    };
    let quality = (variant != "baseline").then(|| quality_of(variant_rms(s, variant)));
    // Baseline is a little off the f64 truth on the SPD's small spheres; a variant's
    // error against the truth is at least the larger of the two.
    let baseline_truth_rms = if s.is_spd() { 0.4 } else { 0.0 };
    let truth_rms = if variant == "baseline" {
        baseline_truth_rms
    } else {
        variant_rms(s, variant).max(baseline_truth_rms)
    };
    let vs_f64_reference = Some(quality_of(truth_rms));
    let hit = counts.get("rays.primary_hit").copied().unwrap_or(0);
    let primary = counts.get("rays.primary").copied().unwrap_or(0);
    // Pixel averaging fills the untraced pixels from neighbours: same coverage.
    let object_pixels = (hit * s.pixels()).checked_div(primary).unwrap_or(0);
    let (centre, spread) = match variant {
        "ortho" => (150.0, 34.0),
        "fast-sqrt" => (136.0, 42.0),
        _ => (140.0, 40.0),
    };
    // One image the runner could not write, to show how the report copes.
    let image = (!(s.is_spd() && variant == "pixel-avg")).then(|| image_path(s.name, variant));
    let heat_map = (variant != "baseline" && image.is_some())
        .then(|| image_path(s.name, &format!("{variant}-diff")));
    VariantResult {
        variant: variant_name(variant),
        time,
        cpu_samples: samples.iter().map(|s| s * 1.9).collect(),
        samples,
        // Camera space and structure build: a few microseconds per primitive.
        preprocessing_seconds: Some(4e-6 * s.primitives() as f64),
        speedup: Some(speedup),
        speedup_interval: None,
        verdict: None,
        image,
        heat_map,
        quality,
        vs_f64_reference,
        histogram: sample_histogram(s.pixels(), object_pixels, centre, spread),
        lane_utilization: (variant == "simd").then(|| lane_utilization(s)),
        efficiency: Some(sample_efficiency(s, variant, &counts, median)),
        ray_rates: Some(sample_ray_rates(s, variant, &counts, median)),
        outside: None,
        counts,
    }
}

/// The sample's software peer on the hardware's job, one thread: fixed seconds and
/// seconds per primitive.
pub const SAMPLE_PEER_FIXED_S: f64 = 0.002;
pub const SAMPLE_PEER_PER_PRIMITIVE_S: f64 = 0.0005;

/// A time measured without spread.
fn exact(seconds: f64) -> results::Estimate {
    results::Estimate {
        median: seconds,
        low: seconds,
        high: seconds,
    }
}

fn sample_scene_hardware(s: &SceneSpec, base_median: f64) -> SceneHardware {
    let n = s.primitives();
    let cycles = u64::from(s.width) * u64::from(s.height) * 3 * n + HW_FILL_CYCLES;
    let seconds = cycles as f64 / HW_CLOCK_HZ;
    // Diffuse-only gray is a little cheaper than the full render.
    let (software_seconds, _) = sample_times(base_median * 0.82, &format!("sw/{}", s.name));
    let emulator_rms = 2.0 + 1.3 * s.cylinders as f64 + 3.0 * unit_hash(&format!("emu/{}", s.name));
    SceneHardware {
        primitives: n,
        cycles,
        seconds,
        fits: true,
        fit_state: Some(hwmodel::device::FitState::Fits),
        software_seconds,
        speedup: software_seconds.median / seconds,
        // The peer grows linearly with the primitives, exactly, so that the break-even
        // can be computed by hand: 2 ms + 0.5 ms a primitive on one thread at the
        // sample's size, half that on its two threads.
        peer: Some(results::SoftwarePeer {
            // A valid name (reports' tests check it arrives as written).
            variant: VariantName::parse("bvh+simd+packets")
                .unwrap_or_else(|_| VariantName::reference()),
            one_thread: exact(SAMPLE_PEER_FIXED_S + SAMPLE_PEER_PER_PRIMITIVE_S * n as f64),
            all_threads: exact(
                (SAMPLE_PEER_FIXED_S + SAMPLE_PEER_PER_PRIMITIVE_S * n as f64) / 2.0,
            ),
            threads: 2,
        }),
        emulator_rms,
        emulator_band: Band::of(emulator_rms),
        emulator_image: Some(image_path(s.name, "emulator")),
        software_image: Some(image_path(s.name, "software-gray")),
    }
}

/// `total` spread over bins by `weights` (rounded down), the rest in the heaviest bin,
/// so the bins sum to `total`.
fn spread(total: u64, weights: &[f64]) -> Vec<u64> {
    let sum: f64 = weights.iter().sum();
    let mut bins: Vec<u64> = weights
        .iter()
        .map(|w| (w / sum * total as f64) as u64)
        .collect();
    let heaviest = weights
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(i, _)| i);
    let used: u64 = bins.iter().sum();
    if let Some(bin) = bins.get_mut(heaviest) {
        *bin += total.saturating_sub(used);
    }
    bins
}

/// Bell-shaped weights over depths 0 to `deepest` around `centre`.
fn depth_weights(centre: f64, width: f64, deepest: usize) -> Vec<f64> {
    (0..=deepest)
        .map(|d| {
            let z = (d as f64 - centre) / width;
            // No leaf above depth 3: the top of a tree is all interior nodes.
            if d < 3 { 0.0 } else { (-0.5 * z * z).exp() }
        })
        .collect()
}

/// What differs between the sample's two builds of a tree.
struct TreeSpec {
    builder: &'static str,
    /// Leaves per primitive count, as weights (index 0: empty leaves).
    leaf_sizes: &'static [f64],
    depth_centre: f64,
    depth_width: f64,
    deepest: usize,
    sah_cost: f64,
    epo: f64,
    /// Nodes, leaves and tests per ray: predicted, measured.
    nodes: (f64, f64),
    leaves: (f64, f64),
    tests: (f64, f64),
    trace_seconds: f64,
}

/// One build of a tree over `s`'s primitives.
fn sample_tree(s: &SceneSpec, t: &TreeSpec) -> BvhQuality {
    let mean_leaf: f64 = t
        .leaf_sizes
        .iter()
        .enumerate()
        .map(|(size, w)| size as f64 * w)
        .sum::<f64>()
        / t.leaf_sizes.iter().sum::<f64>();
    let leaves = (s.primitives() as f64 / mean_leaf).round() as u64;
    let leaf_size_histogram = spread(leaves, t.leaf_sizes);
    let depth_histogram = spread(
        leaves,
        &depth_weights(t.depth_centre, t.depth_width, t.deepest),
    );
    let nodes = 2 * leaves - 1;
    BvhQuality {
        builder: t.builder.to_string(),
        nodes,
        leaves,
        // 32-byte nodes and a 4-byte reference per primitive.
        bytes: nodes * 32 + s.primitives() * 4,
        max_depth: t.deepest as u32,
        max_leaf_size: (t.leaf_sizes.len() - 1) as u32,
        sah_cost: t.sah_cost,
        epo: t.epo,
        depth_histogram,
        leaf_size_histogram,
        predicted_nodes_per_ray: t.nodes.0,
        measured_nodes_per_ray: t.nodes.1,
        predicted_leaves_per_ray: t.leaves.0,
        measured_leaves_per_ray: t.leaves.1,
        predicted_tests_per_ray: t.tests.0,
        measured_tests_per_ray: t.tests.1,
        width: s.width,
        height: s.height,
        trace_seconds: t.trace_seconds,
    }
}

/// Both builders' trees of an SPD scene: the SAH tree is cheaper by its metrics and in
/// time, yet visits a few more nodes per ray than the midpoint split (the metric does
/// not predict everything, and the report has to say so). `bvh_seconds` is the `bvh`
/// variant's median, which uses the SAH tree.
fn sample_bvh_quality(s: &SceneSpec, bvh_seconds: f64) -> Vec<BvhQuality> {
    if !s.is_spd() {
        return Vec::new();
    }
    let sah = TreeSpec {
        builder: "binned_sah",
        leaf_sizes: &[0.0, 0.06, 0.14, 0.22, 0.24, 0.16, 0.09, 0.05, 0.04],
        depth_centre: 11.5,
        depth_width: 1.6,
        deepest: 16,
        sah_cost: 38.2,
        epo: 12.4,
        nodes: (31.4, 44.9),
        leaves: (6.1, 8.3),
        tests: (9.8, 14.2),
        trace_seconds: bvh_seconds,
    };
    let midpoint = TreeSpec {
        builder: "midpoint",
        leaf_sizes: &[
            0.02, 0.10, 0.15, 0.16, 0.14, 0.12, 0.09, 0.07, 0.05, 0.04, 0.03, 0.02, 0.01,
        ],
        depth_centre: 13.5,
        depth_width: 3.0,
        deepest: 23,
        sah_cost: 61.7,
        epo: 27.9,
        nodes: (52.3, 42.1),
        leaves: (9.8, 10.4),
        tests: (18.2, 21.5),
        trace_seconds: bvh_seconds * 1.27,
    };
    vec![sample_tree(s, &sah), sample_tree(s, &midpoint)]
}

fn sample_scene(s: &SceneSpec, failed: &[(&str, &str)]) -> SceneResult {
    let base_median = baseline_seconds(s);
    let variants: Vec<VariantResult> = SAMPLE_VARIANTS
        .iter()
        .filter(|v| !failed.contains(&(s.name, **v)))
        .map(|v| sample_variant(s, v, base_median))
        .collect();
    let bvh_seconds = base_median / variant_speedup(s, "bvh");
    let bvh_quality = sample_bvh_quality(s, bvh_seconds);
    let pixel_maps = sample_pixel_maps(s, &variants);
    let mut primitive_counts = BTreeMap::new();
    for (kind, n) in [
        ("spheres", s.spheres),
        ("cylinders", s.cylinders),
        ("polygons", s.polygons),
    ] {
        if n > 0 {
            primitive_counts.insert(kind.to_string(), n);
        }
    }
    SceneResult {
        name: s.name.to_string(),
        source: if s.is_spd() {
            "../shared/spd/rings.nff".to_string()
        } else {
            "builtin".to_string()
        },
        family: s.family,
        primitives: s.primitives(),
        primitive_counts,
        width: s.width,
        height: s.height,
        spd: s.is_spd(),
        variants,
        hardware: (!s.is_spd()).then(|| sample_scene_hardware(s, base_median)),
        calibration: {
            let (time, samples) = sample_times(0.003, &format!("calibration/{}", s.name));
            Some(results::Calibration {
                time,
                cpu_samples: samples.iter().map(|s| s * 1.9).collect(),
                samples,
            })
        },
        yardstick: {
            let (time, samples) = sample_times(0.002, &format!("yardstick/{}", s.name));
            Some(results::Yardstick {
                width: s.width / results::Yardstick::DIVISOR,
                height: s.height / results::Yardstick::DIVISOR,
                time,
                cpu_samples: samples.iter().map(|s| s * 1.9).collect(),
                samples,
            })
        },
        published: None,
        // 12 bytes a pixel; the sample's scenes hold about 100 bytes a primitive.
        memory: Some(results::MemoryUse {
            scene_bytes: 100 * s.primitives(),
            accelerator_bytes: 0,
            framebuffer_bytes: 12 * u64::from(s.width) * u64::from(s.height),
            peak_bytes: 100 * s.primitives() + 12 * u64::from(s.width) * u64::from(s.height),
            bvh_bytes_per_primitive: None,
        }),
        bvh_quality,
        pixel_maps,
        f64_reference: Some(results::F64Reference {
            image: image_path(s.name, "f64-reference"),
            seconds: 3.0 * base_median,
        }),
        threads: None,
    }
}

/// Tables 7 and 8 as the model computes them for the thesis's design (the thesis's
/// figures come with them from `hwmodel`, the one place they are typed).
fn sample_hardware() -> HardwareResult {
    let lib = hwmodel::library::Library::cyclone_iv_e();
    let tables = hwmodel::table::tables(&lib, &hwmodel::design::Design::thesis());
    HardwareResult {
        family: tables.family.clone(),
        ops: tables.ops.iter().map(HwRow::from_model_row).collect(),
        blocks: tables.blocks.iter().map(HwRow::from_model_row).collect(),
        synthesis: Some(sample_synthesis()),
        // The generator's goal: 12 levels at 1 ns + 1.5 ns a level, 1000 / 19 MHz.
        rtl_clock: Some(results::RtlClock {
            mhz: 1000.0 / 19.0,
            levels: 12,
            synthesized: false,
            source: "the sample's level goal".to_string(),
        }),
        // both7's upload: 356 bytes at 115,200 baud.
        upload: Some(results::Upload {
            primitives: 7,
            bytes: 356,
            baud: 115_200,
            seconds: 356.0 * 10.0 / 115_200.0,
        }),
        devices: vec![
            DeviceUse {
                device: "EP4CE115".to_string(),
                validated: true,
                le: 83_948,
                le_capacity: 114_480,
                mult: 532,
                mult_capacity: 532,
                soft_mult_elements: 36,
                mem_bits: 2_534_933,
                mem_capacity: 3_981_312,
                mem_blocks: 340,
                mem_block_capacity: 432,
                plls: 2,
                pll_capacity: 4,
                fits: true,
                fit_state: Some(hwmodel::device::FitState::Fits),
                largest_units: Some(1),
            },
            DeviceUse {
                device: "5CGXFC9".to_string(),
                validated: false,
                le: 81_032,
                le_capacity: 301_000,
                mult: 245,
                mult_capacity: 1026,
                soft_mult_elements: 0,
                mem_bits: 2_534_933,
                mem_capacity: 12_492_800,
                mem_blocks: 330,
                mem_block_capacity: 1220,
                plls: 2,
                pll_capacity: 8,
                fits: true,
                fit_state: Some(hwmodel::device::FitState::Fits),
                largest_units: Some(5),
            },
        ],
    }
}

/// The synthetic run.
pub fn sample_results() -> Results {
    let failed = [("rings", "ortho")];
    let scenes: Vec<SceneResult> = SCENES.iter().map(|s| sample_scene(s, &failed)).collect();
    let profile = scenes
        .iter()
        .find(|s| s.name == "rings")
        .map(|rings| ProfileResult {
            scene: rings.name.clone(),
            width: rings.width,
            height: rings.height,
            baseline: sample_profile(rings, "baseline", &BASELINE_FLAT),
            best: Some(sample_profile(rings, "bvh", &BVH_FLAT)),
            diff_flame_svg: Some(format!("profile/{}-diff-baseline-bvh.svg", rings.name)),
            diff_shrunk_flame_svg: None,
        });
    let ns = |median: f64| Estimate {
        median,
        low: median * 0.98,
        high: median * 1.03,
    };
    let mut results = Results {
        schema: SCHEMA.to_string(),
        created: "2025-11-21T16:51:07Z".to_string(),
        command: "rtprof suite --scenes ../shared/spd -o out/suite".to_string(),
        machine: Machine {
            cpu_model: "Intel(R) Xeon(R) CPU @ 2.20GHz".to_string(),
            cores: 2,
            os: "linux x86_64 (Debian GNU/Linux 13)".to_string(),
            hostname: "bench-1".to_string(),
        },
        build: Build {
            rtprof_version: "0.1.0".to_string(),
            rustc: "rustc 1.95.0 (2025-10-28)".to_string(),
            git_commit: "183fc3d5b2e0a1c4f9d87e6b5a4c3d2e1f0a9b8c".to_string(),
            profile: "release".to_string(),
        },
        suite: SuiteInfo {
            name: "default".to_string(),
            quick: false,
            threads: 2,
            variants: SAMPLE_VARIANTS.iter().map(|v| variant_name(v)).collect(),
            timing: TimingPolicy {
                min_repeats: 5,
                min_seconds: 0.2,
                max_repeats: 100,
                bootstrap_resamples: 2000,
                confidence: 0.95,
                seed: 0x5eed,
                covers: TimeCovers::Tracing,
                interleaved: true,
            },
            wall_seconds: 96.4,
            noise_threshold: Some(results::NOISE_THRESHOLD),
            shard: None,
        },
        scenes,
        profile,
        hardware: Some(sample_hardware()),
        failures: vec![Failure {
            scene: Some("rings".to_string()),
            part: FailedPart::Variant(variant_name("ortho")),
            message: "render exceeded the 60 s budget for one repeat; skipped".to_string(),
        }],
        // The bit trick runs more instructions than `sqrtss` yet takes less time: the
        // report has to say when the two disagree.
        criterion: vec![
            CriterionEstimate {
                id: "sqrt/fast-sqrt-newton".to_string(),
                mean: ns(820.0),
                median: ns(815.0),
                measured: Some("2026-11-21T10:00:00Z".to_string()),
            },
            CriterionEstimate {
                id: "sqrt/std".to_string(),
                mean: ns(1180.0),
                median: ns(1175.0),
                measured: Some("2026-11-21T10:00:00Z".to_string()),
            },
            CriterionEstimate {
                id: "intersect/sphere/hit".to_string(),
                mean: ns(11.8),
                median: ns(11.6),
                measured: Some("2026-11-21T10:00:00Z".to_string()),
            },
        ],
        instructions: vec![
            InstructionCount {
                id: "intersect/sphere/hit".to_string(),
                instructions: 62,
                estimated_cycles: Some(210),
                measured: Some("2026-11-21T10:05:00Z".to_string()),
            },
            InstructionCount {
                id: "sqrt/fast-sqrt-newton".to_string(),
                instructions: 11_451,
                estimated_cycles: Some(14_500),
                measured: Some("2026-11-21T10:05:00Z".to_string()),
            },
            InstructionCount {
                id: "sqrt/std".to_string(),
                instructions: 6_330,
                estimated_cycles: Some(9_289),
                measured: Some("2026-11-21T10:05:00Z".to_string()),
            },
        ],
        peak: Some(sample_peak()),
        outside_profiles: Vec::new(),
    };
    // Speed-ups, intervals and verdicts by the one rule, from the samples above.
    results::change::fill_speedups(&mut results, results::NOISE_THRESHOLD);
    results
}

#[cfg(test)]
mod tests;
