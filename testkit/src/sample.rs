//! A realistic synthetic suite run, for tests and for the report's look.
//!
//! [`sample_results`] builds a [`Results`] that exercises every part of the schema:
//! test-bench scenes (`balls`, `cylinder`, `both` with 1 to 7 primitives) at 640x480,
//! one SPD scene (`rings`, 8402 primitives) at 320x240, six variants with times,
//! intervals, speed-ups, exact counts and image metrics, a profile of `rings`
//! (baseline and `bvh`), the hardware model's tables 7 and 8 (computed by `hwmodel`
//! for the thesis's design, with the thesis's figures it holds), two devices, machine and build
//! information, three criterion estimates with their instruction counts and one failure. The numbers are made up but
//! consistent with each other (speed-ups are baseline median / variant median, counts
//! follow from the ray counts, histograms sum to the pixel count).
//! [`crate::files::write_sample_files`] writes the files it refers to.

use std::collections::BTreeMap;

use results::{
    AmdahlFigures, AmdahlRow, Band, Build, CriterionEstimate, DeviceUse, Estimate, FailedPart,
    Failure, FlatRow, HardwareResult, HwRow, InstructionCount, Machine, Profile, ProfileResult,
    ProfileView, Quality, Results, SCHEMA, SceneFamily, SceneHardware, SceneResult, SuiteInfo,
    TimeCovers, TimingPolicy, VariantName, VariantResult,
};

/// The variants of the sample, baseline first.
pub const SAMPLE_VARIANTS: [&str; 6] =
    ["baseline", "simd", "bvh", "fast-sqrt", "ortho", "pixel-avg"];

/// The name of one of [`SAMPLE_VARIANTS`] (all are tracer's single variants).
fn variant_name(name: &str) -> VariantName {
    tracer::Variant::ALL
        .into_iter()
        .find(|v| v.name() == name)
        .map_or_else(VariantName::reference, VariantName::from)
}

/// Frame-time constants of the thesis's design (eq. 49): 50 MHz, 3 cycles per primitive.
const HW_CLOCK_HZ: f64 = 50e6;
const HW_FILL_CYCLES: u64 = 342;

/// One scene of the sample: name, family, spheres, cylinders, polygons, size.
struct SceneSpec {
    name: &'static str,
    family: SceneFamily,
    spheres: u64,
    cylinders: u64,
    polygons: u64,
    width: u32,
    height: u32,
}

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

fn sample_variant(s: &SceneSpec, variant: &str, base_median: f64) -> VariantResult {
    let speedup = variant_speedup(s, variant);
    let median = base_median / speedup;
    let (time, samples) = sample_times(median, &format!("t/{}/{variant}", s.name));
    let counts = sample_counts(s, variant);
    let quality = (variant != "baseline").then(|| {
        let rms = variant_rms(s, variant);
        Quality {
            rms,
            band: Band::of(rms),
            psnr: (rms > 0.0).then(|| 20.0 * (255.0 / rms).log10()),
            ssim: if rms > 0.0 { 1.0 - rms / 260.0 } else { 1.0 },
            max_abs_diff: (rms * 4.2).min(255.0) as u32,
        }
    });
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
        counts,
        image,
        heat_map,
        quality,
        histogram: sample_histogram(s.pixels(), object_pixels, centre, spread),
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
        software_seconds,
        speedup: software_seconds.median / seconds,
        emulator_rms,
        emulator_band: Band::of(emulator_rms),
        emulator_image: Some(image_path(s.name, "emulator")),
        software_image: Some(image_path(s.name, "software-gray")),
    }
}

fn sample_scene(s: &SceneSpec, failed: &[(&str, &str)]) -> SceneResult {
    let base_median = baseline_seconds(s);
    let variants = SAMPLE_VARIANTS
        .iter()
        .filter(|v| !failed.contains(&(s.name, **v)))
        .map(|v| sample_variant(s, v, base_median))
        .collect();
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
        published: None,
        // 12 bytes a pixel; the sample's scenes hold about 100 bytes a primitive.
        memory: Some(results::MemoryUse {
            scene_bytes: 100 * s.primitives(),
            accelerator_bytes: 0,
            framebuffer_bytes: 12 * u64::from(s.width) * u64::from(s.height),
            peak_bytes: 100 * s.primitives() + 12 * u64::from(s.width) * u64::from(s.height),
            bvh_bytes_per_primitive: None,
        }),
    }
}

/// Flat-profile functions of `rings` (baseline): name, % time, inclusive %, count key.
const BASELINE_FLAT: [(&str, f64, f64, Option<&str>); 13] = [
    (
        "tracer::primitives::cylinder::Cylinder::intersect",
        31.2,
        38.9,
        Some("tests.cylinder.tests"),
    ),
    (
        "tracer::primitives::sphere::Sphere::intersect",
        22.4,
        28.6,
        Some("tests.sphere.tests"),
    ),
    ("tracer::vec3::dot", 14.8, 14.8, Some("ops.dot")),
    ("tracer::vec3::Vec3::sub", 8.1, 8.1, Some("ops.sub")),
    (
        "tracer::scene::Scene::intersect",
        7.5,
        82.1,
        Some("calls.intersect"),
    ),
    ("tracer::render::trace", 3.2, 97.4, Some("calls.trace")),
    ("tracer::shading::shade", 2.6, 14.2, Some("calls.shade")),
    (
        "tracer::fast_sqrt::WithSqrt::sqrt",
        1.9,
        1.9,
        Some("ops.sqrt"),
    ),
    (
        "tracer::vec3::Vec3::normalize",
        1.1,
        2.0,
        Some("ops.normalize"),
    ),
    (
        "tracer::camera::Camera::primary_ray",
        0.6,
        1.3,
        Some("rays.primary"),
    ),
    (
        "tracer::shading::color_contribution",
        0.5,
        3.1,
        Some("calls.color_contribution"),
    ),
    (
        "tracer::primitives::polygon::Polygon::intersect",
        0.4,
        0.5,
        Some("tests.polygon.tests"),
    ),
    ("tracer::render::render::{{closure}}", 0.2, 99.6, None),
];

/// The same for `rings` with `bvh`.
const BVH_FLAT: [(&str, f64, f64, Option<&str>); 9] = [
    (
        "tracer::accel::bvh::Bvh::intersect",
        27.5,
        71.0,
        Some("calls.intersect"),
    ),
    (
        "tracer::accel::aabb::Aabb::hit",
        21.8,
        21.8,
        Some("accel.nodes_visited"),
    ),
    (
        "tracer::primitives::cylinder::Cylinder::intersect",
        14.1,
        16.9,
        Some("tests.cylinder.tests"),
    ),
    (
        "tracer::primitives::sphere::Sphere::intersect",
        11.7,
        13.2,
        Some("tests.sphere.tests"),
    ),
    ("tracer::shading::shade", 7.9, 24.5, Some("calls.shade")),
    ("tracer::accel::bvh::Bvh::occluded", 6.2, 15.4, None),
    ("tracer::vec3::dot", 4.4, 4.4, Some("ops.dot")),
    ("tracer::render::trace", 3.6, 97.9, Some("calls.trace")),
    (
        "tracer::vec3::Vec3::normalize",
        1.8,
        2.6,
        Some("ops.normalize"),
    ),
];

fn amdahl_figures(fraction: f64) -> AmdahlFigures {
    let speedup = |factor: f64| 1.0 / ((1.0 - fraction) + fraction / factor);
    AmdahlFigures {
        fraction,
        speedup_2x: speedup(2.0),
        speedup_10x: speedup(10.0),
        speedup_limit: if fraction < 1.0 {
            1.0 / (1.0 - fraction)
        } else {
            f64::INFINITY
        },
    }
}

fn amdahl_row(name: &str, fraction: f64, inclusive: f64) -> AmdahlRow {
    let own = amdahl_figures(fraction);
    AmdahlRow {
        name: name.to_string(),
        fraction,
        speedup_2x: own.speedup_2x,
        speedup_10x: own.speedup_10x,
        speedup_limit: own.speedup_limit,
        inclusive: Some(amdahl_figures(inclusive)),
    }
}

fn sample_profile(
    scene: &SceneResult,
    variant: &str,
    rows: &[(&str, f64, f64, Option<&str>)],
) -> Profile {
    let total = scene
        .variants
        .iter()
        .find(|v| v.variant == variant)
        .map_or(1.0, |v| v.time.median);
    let counts = scene
        .variants
        .iter()
        .find(|v| v.variant == variant)
        .map(|v| v.counts.clone())
        .unwrap_or_default();
    let seconds_per_sample = 0.001;
    let flat: Vec<FlatRow> = rows
        .iter()
        .map(|(name, percent, inclusive, key)| FlatRow {
            name: (*name).to_string(),
            percent: *percent,
            self_seconds: total * percent / 100.0,
            total_seconds: total * inclusive / 100.0,
            calls: key.and_then(|k| counts.get(k).copied()),
            inclusive_percent: Some(*inclusive),
            self_interval: None,
            inclusive_interval: None,
            noise: false,
            root: false,
        })
        .collect();
    let amdahl = flat
        .iter()
        .take(6)
        .map(|r| {
            let inclusive = r.inclusive_percent.unwrap_or(r.percent);
            amdahl_row(&r.name, r.percent / 100.0, inclusive / 100.0)
        })
        .collect();
    let stem = format!("profile/{}-{variant}", scene.name);
    Profile {
        variant: variant_name(variant),
        samples: (total / seconds_per_sample).round() as u64,
        seconds_per_sample,
        flat,
        flat_text: format!("{stem}-flat.txt"),
        callgraph_text: format!("{stem}-callgraph.txt"),
        flame_svg: format!("{stem}-flame.svg"),
        amdahl,
        renders: Some(1),
        samples_asked: Some((total / seconds_per_sample).round() as u64),
        cpu_seconds: Some(total),
        view: ProfileView::Native,
        second_view: None,
        exports: Vec::new(),
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
                plls: 2,
                pll_capacity: 4,
                fits: true,
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
                plls: 2,
                pll_capacity: 8,
                fits: true,
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
    };
    // Speed-ups, intervals and verdicts by the one rule, from the samples above.
    results::change::fill_speedups(&mut results, results::NOISE_THRESHOLD);
    results
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_variant_names_are_tracer_variants() {
        for v in SAMPLE_VARIANTS {
            assert_eq!(variant_name(v).as_str(), v);
        }
    }

    #[test]
    fn sample_is_consistent_and_round_trips() {
        let r = sample_results();
        assert!(r.scenes.len() >= 6);
        for scene in &r.scenes {
            let base = r.baseline(scene).expect("baseline");
            for v in &scene.variants {
                assert_eq!(v.histogram.len(), 256);
                let sum: u64 = v.histogram.iter().sum();
                assert_eq!(sum, u64::from(scene.width) * u64::from(scene.height));
                let ratio = base.time.median / v.time.median;
                assert!(
                    v.speedup.is_some_and(|s| (ratio - s).abs() < 1e-9),
                    "{}/{}",
                    scene.name,
                    v.variant
                );
                assert!(v.time.low <= v.time.median && v.time.median <= v.time.high);
                assert_eq!(v.quality.is_none(), v.variant.is_reference());
            }
            assert_eq!(scene.hardware.is_none(), scene.spd);
        }
        // Without serde_json's `float_roundtrip` feature a float may come back one ulp
        // off: integers and strings must match exactly, floats to 1e-12.
        let text = serde_json::to_string(&r).expect("serialize");
        let back = Results::from_json(&text).expect("parse");
        assert_eq!(back.scenes.len(), r.scenes.len());
        for (a, b) in r.scenes.iter().zip(&back.scenes) {
            assert_eq!(a.name, b.name);
            assert_eq!(a.hardware.is_some(), b.hardware.is_some());
            for (x, y) in a.variants.iter().zip(&b.variants) {
                assert!(x.counts == y.counts && x.histogram == y.histogram && x.image == y.image);
                assert!((x.time.median - y.time.median).abs() <= 1e-12 * x.time.median.abs());
            }
        }
        assert!(back.failures == r.failures && back.machine == r.machine);
        let models = |r: &Results| -> Vec<results::HwFigures> {
            r.hardware
                .iter()
                .flat_map(|h| h.ops.iter().chain(&h.blocks))
                .map(|row| row.model)
                .collect()
        };
        assert_eq!(models(&back), models(&r));
    }
}
