//! The sections of `rtprof.results/3`'s machine figures (ray rates, roofline, per-pixel
//! maps, BVH quality) from the synthetic sample: each is there, says the numbers its
//! data give (computed here again from the sample's fields), lays out what it should,
//! and is left out of the report of a file without those fields.

use std::path::Path;

use reports::Run;
use reports::document::{self, Block, Document, ImageGrid, Inline, Section, Table, Visual};
use reports::format;
use reports::results::{Results, SceneResult, VariantResult};
use testkit::{TempDir, sample_results, write_sample_files};

fn document_of(results: Results, dir: &Path) -> Document {
    write_sample_files(dir).expect("sample files");
    let run = Run {
        label: "bench-1".to_string(),
        results,
        base_dir: dir.to_path_buf(),
    };
    document::build(&[run]).expect("document")
}

fn section<'d>(doc: &'d Document, id: &str) -> &'d Section {
    doc.section(id).unwrap_or_else(|| panic!("no section {id}"))
}

/// The plain text of a section's paragraphs, one after another.
fn prose(s: &Section) -> String {
    s.blocks
        .iter()
        .filter_map(|b| match b {
            Block::Paragraph { content } => Some(
                content
                    .iter()
                    .map(|i| match i {
                        Inline::Text { text } | Inline::Strong { text } | Inline::Code { text } => {
                            text.as_str()
                        }
                        _ => "",
                    })
                    .collect::<String>(),
            ),
            _ => None,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn tables(s: &Section) -> Vec<&Table> {
    s.blocks
        .iter()
        .filter_map(|b| match b {
            Block::Table(t) => Some(t),
            _ => None,
        })
        .collect()
}

fn grids(s: &Section) -> Vec<&ImageGrid> {
    s.blocks
        .iter()
        .filter_map(|b| match b {
            Block::ImageGrid(g) => Some(g),
            _ => None,
        })
        .collect()
}

fn titles(t: &Table) -> Vec<&str> {
    t.columns.iter().map(|c| c.title.as_str()).collect()
}

fn rings(r: &Results) -> &SceneResult {
    r.scenes.iter().find(|s| s.name == "rings").expect("rings")
}

fn variant<'a>(scene: &'a SceneResult, name: &str) -> &'a VariantResult {
    scene
        .variants
        .iter()
        .find(|v| v.variant == name)
        .unwrap_or_else(|| panic!("no {name}"))
}

/// The share of the roof a sentence gives `variant`: the `P` of `{variant} ({kind}
/// code) attains … : P of its roof`.
fn stated_share<'t>(text: &'t str, variant: &str) -> &'t str {
    let at = text
        .find(&format!(", {variant} ("))
        .or_else(|| text.find(&format!("On rings, {variant} (")))
        .unwrap_or_else(|| panic!("{variant} not in: {text}"));
    let rest = &text[at..];
    let from = rest.find(": ").expect("a share") + 2;
    let to = rest.find(" of its roof").expect("of its roof");
    &rest[from..to]
}

/// The text in parentheses of a table cell: `17.4 (58.6 %)` gives `58.6 %`.
fn cell_share(cell: &str) -> &str {
    cell.split_once(" (")
        .and_then(|(_, rest)| rest.strip_suffix(')'))
        .unwrap_or_else(|| panic!("no share in {cell}"))
}

/// The table cell of `scene` and `variant`.
fn cell<'t>(t: &'t Table, scene: &str, variant: &str) -> &'t str {
    let column = titles(t)
        .iter()
        .position(|c| *c == variant)
        .unwrap_or_else(|| panic!("no column {variant}"));
    let row = t
        .rows
        .iter()
        .find(|row| row[0].text == scene)
        .unwrap_or_else(|| panic!("no row {scene}"));
    &row[column].text
}

#[test]
fn the_roofline_states_each_share_on_one_basis_in_the_sentence_and_the_table() {
    let dir = TempDir::new("machine-roofline").expect("temp dir");
    let r = sample_results();
    let doc = document_of(r.clone(), dir.path());
    let s = section(&doc, "roofline");
    let text = prose(s);
    let t = tables(s)[0];
    let peak = r.peak.as_ref().expect("peak");
    let scalar_peak = peak
        .scalar_peak_gflops
        .expect("the sample has a scalar peak");
    assert!(
        text.contains("149 GFLOP/s in SIMD lanes by the FMA kernel (AVX2+FMA, 8 lanes × 10 chains) and 29.7 GFLOP/s in scalar instructions (scalar FMA, 1 lane × 10 chains)"),
        "{text}"
    );

    // rings is the profiled scene: baseline (scalar code) and the fastest variant.
    let scene = rings(&r);
    let fastest = scene
        .variants
        .iter()
        .min_by(|a, b| a.time.median.total_cmp(&b.time.median))
        .expect("variants");
    for (v, comma) in [(variant(scene, "baseline"), ""), (fastest, ",")] {
        let e = v.efficiency.as_ref().expect("efficiency");
        // By hand, from the counts and the time: attained over the lower of the
        // compute peak of its code and the L1 bandwidth times its intensity.
        let attained = e.flops as f64 / v.time.median / 1e9;
        let intensity = e.flops as f64 / e.bytes_moved as f64;
        let simd_code = v.variant.as_str().contains("simd");
        let compute = if simd_code {
            peak.peak_gflops
        } else {
            scalar_peak
        };
        let fed = peak.cache_bandwidth_gbs * intensity;
        let roof = compute.min(fed);
        let share = attained / roof * 100.0;
        assert!(share < 100.0, "the sample's points are under their roofs");
        let roof_text = if fed < compute {
            format!(
                "the L1 bandwidth roof of {} GFLOP/s at that intensity",
                format::significant(roof)
            )
        } else {
            format!(
                "the {} peak of {} GFLOP/s",
                if simd_code { "SIMD" } else { "scalar" },
                format::significant(roof)
            )
        };
        let expected = format!(
            "{} ({} code){comma} attains {} GFLOP/s at {} flop/byte: {} of its roof, {roof_text}",
            v.variant,
            if simd_code { "SIMD" } else { "scalar" },
            format::significant(attained),
            format::significant(intensity),
            format::percent(share, 1)
        );
        assert!(text.contains(&expected), "{expected} not in: {text}");
        // The sentence's share of this render is the table's.
        let in_table = cell(t, "rings", v.variant.as_str());
        assert_eq!(
            stated_share(&text, v.variant.as_str()),
            cell_share(in_table)
        );
        assert_eq!(
            in_table,
            format!(
                "{} ({})",
                format::significant(attained),
                format::percent(share, 1)
            )
        );
    }

    // Its records came from the caches: baseline attains more than DRAM could feed.
    let base = variant(scene, "baseline")
        .efficiency
        .as_ref()
        .expect("efficiency");
    let dram = peak
        .peak_gflops
        .min(peak.bandwidth_gbs * base.flops as f64 / base.bytes_moved as f64);
    assert!(base.achieved_gflops > dram);
    let expected = format!(
        "and above the {} GFLOP/s DRAM alone could feed it",
        format::significant(dram)
    );
    assert!(text.contains(&expected), "{expected} not in: {text}");
    assert!(text.contains("counted vector operations only, a lower bound"));
    // No share on another basis: neither of the SIMD peak for scalar code nor of
    // "the bandwidth roof" without its level.
    assert!(!text.contains("of the 149 GFLOP/s peak"), "{text}");

    // The chart, and one row per scene, one column per variant of the suite.
    assert!(
        s.blocks
            .iter()
            .any(|b| matches!(b, Block::Figure(f) if f.id == "roofline"))
    );
    let variants: Vec<&str> = r.suite.variants.iter().map(|v| v.as_str()).collect();
    let mut expected_titles = vec!["scene"];
    expected_titles.extend(&variants);
    assert_eq!(titles(t), expected_titles);
    assert_eq!(t.rows.len(), r.scenes.len());
    // simd (SIMD code) is held to the SIMD roof in every row.
    for scene in &r.scenes {
        let v = variant(scene, "simd");
        let e = v.efficiency.as_ref().expect("efficiency");
        let roof = peak
            .peak_gflops
            .min(peak.cache_bandwidth_gbs * e.arithmetic_intensity);
        assert_eq!(
            cell_share(cell(t, &scene.name, "simd")),
            format::percent(e.achieved_gflops / roof * 100.0, 1),
            "{}",
            scene.name
        );
    }
}

#[test]
fn a_file_without_the_scalar_peak_sets_every_point_against_the_simd_roof_and_says_so() {
    let dir = TempDir::new("machine-no-scalar").expect("temp dir");
    let mut r = sample_results();
    let peak = r.peak.as_mut().expect("peak");
    peak.scalar_peak_gflops = None;
    peak.scalar_kernel = None;
    let peak = peak.clone();
    let doc = document_of(r.clone(), dir.path());
    let s = section(&doc, "roofline");
    let text = prose(s);
    assert!(
        text.contains("this file has no scalar peak, so scalar code is set against this one too"),
        "{text}"
    );
    let base = variant(rings(&r), "baseline");
    let e = base.efficiency.as_ref().expect("efficiency");
    let roof = peak
        .peak_gflops
        .min(peak.cache_bandwidth_gbs * e.arithmetic_intensity);
    let share = format::percent(e.achieved_gflops / roof * 100.0, 1);
    assert_eq!(stated_share(&text, "baseline"), share);
    assert_eq!(cell_share(cell(tables(s)[0], "rings", "baseline")), share);
    // The chart draws the roofs it has and says which one is missing.
    let Some(Block::Figure(f)) = s
        .blocks
        .iter()
        .find(|b| matches!(b, Block::Figure(f) if f.id == "roofline"))
    else {
        panic!("no roofline chart");
    };
    assert!(
        f.caption.contains("This file has no scalar peak"),
        "{}",
        f.caption
    );
}

#[test]
fn without_the_peaks_the_roofline_has_no_roof() {
    let dir = TempDir::new("machine-no-peak").expect("temp dir");
    let mut r = sample_results();
    r.peak = None;
    let doc = document_of(r, dir.path());
    let s = section(&doc, "roofline");
    assert!(
        s.blocks
            .iter()
            .any(|b| matches!(b, Block::Note(n) if n.text.contains("peaks were not measured")))
    );
    let text = prose(s);
    assert!(
        text.contains("On rings, baseline (scalar code) attains") && !text.contains("% of"),
        "{text}"
    );
    // The attained GFLOP/s alone, without a share of a roof.
    let t = tables(s)[0];
    assert!(t.rows.iter().flatten().all(|c| !c.text.contains('%')));
}

#[test]
fn the_rays_section_sets_the_lanes_in_use_against_the_speed_up() {
    let dir = TempDir::new("machine-rays").expect("temp dir");
    let r = sample_results();
    let doc = document_of(r.clone(), dir.path());
    let s = section(&doc, "ray-rates");
    let text = prose(s);

    // The fullest and the emptiest lanes of simd, from lanes active / lanes issued.
    let simd: Vec<(&SceneResult, &VariantResult)> = r
        .scenes
        .iter()
        .map(|scene| (scene, variant(scene, "simd")))
        .collect();
    let used = |(_, v): &(&SceneResult, &VariantResult)| v.lane_utilization.expect("simd lanes");
    let fullest = simd
        .iter()
        .max_by(|a, b| {
            used(a)
                .total_cmp(&used(b))
                .then(a.0.primitives.cmp(&b.0.primitives))
        })
        .expect("simd");
    let emptiest = simd
        .iter()
        .min_by(|a, b| {
            used(a)
                .total_cmp(&used(b))
                .then(a.0.primitives.cmp(&b.0.primitives))
        })
        .expect("simd");
    // rings: 4,200 spheres and 4,200 cylinders fill chunks of 8 exactly; balls1's one
    // sphere uses one lane of 8.
    assert_eq!((fullest.0.name.as_str(), used(fullest)), ("rings", 1.0));
    assert_eq!(
        (emptiest.0.name.as_str(), used(emptiest)),
        ("balls1", 0.125)
    );
    let speed =
        |(_, v): &(&SceneResult, &VariantResult)| format::speedup(v.speedup.expect("speed-up"));
    for expected in [
        format!(
            "simd keeps 100.0 % of its lanes busy on rings (8,402 primitives) at {} baseline's speed",
            speed(fullest)
        ),
        format!(
            "and only 12.5 % on balls1 (1 primitive) at {} baseline's speed",
            speed(emptiest)
        ),
    ] {
        assert!(text.contains(&expected), "{expected} not in: {text}");
    }
    let pays = fullest.1.speedup > emptiest.1.speedup;
    assert_eq!(text.contains("packing pays"), pays, "{text}");

    let t = tables(s)[0];
    let lanes = titles(t)
        .iter()
        .position(|c| *c == "SIMD lanes")
        .expect("a lanes column");
    assert_eq!(
        titles(t)[lanes - 1],
        "speed-up",
        "the lanes sit next to the speed-up"
    );
    for row in &t.rows {
        let is_simd = row[1].text == "simd";
        assert_eq!(row[lanes].text != format::DASH, is_simd, "{}", row[1].text);
    }
    // The time shares of a row (eye, secondary, shadow, other, idle) sum to 100 %.
    let row = &t.rows[0];
    let shares: f64 = row[row.len() - 5..]
        .iter()
        .map(|c| c.sort.expect("a share"))
        .sum();
    assert!((shares - 1.0).abs() < 1e-9, "{shares}");
}

#[test]
fn the_bvh_section_says_where_the_metrics_do_not_predict_the_measurement() {
    let dir = TempDir::new("machine-bvh").expect("temp dir");
    let r = sample_results();
    let doc = document_of(r.clone(), dir.path());
    let s = section(&doc, "bvh-quality");
    let text = prose(s);
    let trees = &rings(&r).bvh_quality;
    let sah = trees
        .iter()
        .find(|t| t.builder == "binned_sah")
        .expect("sah");
    let mid = trees
        .iter()
        .find(|t| t.builder == "midpoint")
        .expect("midpoint");
    assert!(sah.sah_cost < mid.sah_cost && sah.epo < mid.epo);
    // The sample's SAH tree visits more nodes per ray yet traces faster.
    assert!(sah.measured_nodes_per_ray > mid.measured_nodes_per_ray);
    assert!(sah.trace_seconds < mid.trace_seconds);
    let sig = format::significant;
    for expected in [
        format!(
            "binned_sah has the lower SAH cost ({} against {}) and the lower EPO ({} against {}) than midpoint",
            sig(sah.sah_cost),
            sig(mid.sah_cost),
            sig(sah.epo),
            sig(mid.epo)
        ),
        format!(
            "it traces faster ({} against {}), but visits more nodes per ray ({} against {}): here the metrics do not predict the nodes visited",
            format::seconds(sah.trace_seconds),
            format::seconds(mid.trace_seconds),
            sig(sah.measured_nodes_per_ray),
            sig(mid.measured_nodes_per_ray)
        ),
    ] {
        assert!(text.contains(&expected), "{expected} not in: {text}");
    }
    let t = tables(s)[0];
    assert_eq!(t.rows.len(), 2);
    let ratio = titles(t)
        .iter()
        .position(|c| *c == "measured ÷ predicted")
        .expect("ratio column");
    assert_eq!(
        t.rows[0][ratio].text,
        format::speedup(sah.measured_nodes_per_ray / sah.predicted_nodes_per_ray)
    );
    assert!(
        s.blocks
            .iter()
            .any(|b| matches!(b, Block::Figure(f) if f.id == "bvh-histograms-rings"))
    );
}

/// Writes every map of `scene`'s variants as a NumPy file of the map's grid: values
/// `value(variant, key, index)`.
fn write_maps(dir: &Path, scene: &SceneResult, value: impl Fn(&str, &str, usize) -> u64) {
    for maps in &scene.pixel_maps {
        let n = (maps.columns * maps.rows) as usize;
        for map in &maps.maps {
            let values: Vec<u64> = (0..n)
                .map(|i| value(maps.variant.as_str(), &map.key, i))
                .collect();
            let bytes = reports::npy::npy_bytes(maps.rows as usize, maps.columns as usize, &values)
                .expect("npy");
            let path = dir.join(&maps.directory).join(&map.npy);
            std::fs::create_dir_all(path.parent().expect("parent")).expect("mkdir");
            std::fs::write(path, bytes).expect("write");
        }
    }
}

/// The figures of a section, by id.
fn figures(s: &Section) -> Vec<&document::Figure> {
    s.blocks
        .iter()
        .filter_map(|b| match b {
            Block::Figure(f) => Some(f),
            _ => None,
        })
        .collect()
}

/// The pictures an SVG embeds, decoded.
fn embedded_pngs(svg: &str) -> Vec<image::RgbImage> {
    svg.split("href=\"data:image/png;base64,")
        .skip(1)
        .map(|rest| {
            let data = rest.split('"').next().expect("quote");
            image::load_from_memory(&unbase64(data))
                .expect("a PNG")
                .to_rgb8()
        })
        .collect()
}

fn unbase64(text: &str) -> Vec<u8> {
    const ALPHABET: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = Vec::new();
    let (mut bits, mut held) = (0u32, 0u32);
    for c in text.bytes().filter(|&c| c != b'=') {
        bits = (bits << 6) | ALPHABET.iter().position(|&a| a == c).expect("base64") as u32;
        held += 6;
        if held >= 8 {
            held -= 8;
            out.push((bits >> held) as u8);
        }
    }
    out
}

#[test]
fn pixel_maps_of_a_counter_share_one_scale_and_what_is_not_there_is_one_sentence() {
    let dir = TempDir::new("machine-maps").expect("temp dir");
    let r = sample_results();
    write_sample_files(dir.path()).expect("sample files");
    let scene = rings(&r);
    // Time: a ramp to 700 ns with baseline and to 470 ns with simd and bvh, so that
    // a per-map scale would draw simd's 470 in baseline's 700's colour; the depth is
    // 1 everywhere with every variant; other counters a ramp to 9.
    let top = |variant: &str| if variant == "baseline" { 700 } else { 470 };
    let n = (scene.pixel_maps[0].columns * scene.pixel_maps[0].rows) as usize;
    write_maps(dir.path(), scene, |variant, key, i| match key {
        "time.ns" => (i * top(variant) / (n - 1)) as u64,
        "ray_tree.depth" => 1,
        _ => (i % 10) as u64,
    });
    // simd's shadow rays are lost.
    std::fs::remove_file(dir.path().join("pixel-maps/rings/simd/rays.shadow.npy")).expect("remove");
    let run = Run {
        label: "bench-1".to_string(),
        results: r.clone(),
        base_dir: dir.path().to_path_buf(),
    };
    let doc = document::build(&[run]).expect("document");
    let s = section(&doc, "pixel-maps");
    let text = prose(s);

    // One figure per counter with a varying value, in row order; the depth is flat.
    let ids: Vec<&str> = figures(s).iter().map(|f| f.id.as_str()).collect();
    assert_eq!(
        ids,
        [
            "pixel-maps-rings-time_ns",
            "pixel-maps-rings-tests_sphere_tests",
            "pixel-maps-rings-tests_cylinder_tests",
            "pixel-maps-rings-tests_polygon_tests",
            "pixel-maps-rings-accel_nodes_visited",
            "pixel-maps-rings-rays_shadow",
        ]
    );
    assert!(
        text.contains("Not drawn because every sample of every variant holds the same value: the ray-tree depth is 1 everywhere."),
        "{text}"
    );
    // What a variant did not count and what could not be read: one sentence each,
    // no empty boxes.
    assert!(
        text.contains("Not drawn because not counted: no BVH nodes with baseline and simd."),
        "{text}"
    );
    assert!(
        text.contains("Not drawn because the raw values could not be read: simd's rays.shadow (pixel-maps/rings/simd/rays.shadow.npy: entity not found)."),
        "{text}"
    );
    assert!(grids(s).is_empty(), "no grids of tiles and placeholders");

    // The time row: baseline, simd and bvh on one scale from 0 to 700 ns, its values
    // once, beside the maps.
    let time = figures(s)[0];
    assert_eq!(time.title, "rings: time");
    assert!(
        time.caption
            .contains("with baseline, simd and bvh, on one colour scale from 0 s to 700 ns"),
        "{}",
        time.caption
    );
    let Visual::Image(image) = &time.visual else {
        panic!("the row is a picture");
    };
    let svg = String::from_utf8_lossy(&doc.assets.get(&image.asset).expect("asset").bytes);
    for name in [
        ">baseline<",
        ">simd<",
        ">bvh<",
        ">ns per sample<",
        ">700 ns<",
        ">0 s<",
    ] {
        assert!(svg.contains(name), "{name} not in the row");
    }
    assert_eq!(svg.matches(">ns per sample<").count(), 1, "one scale a row");
    assert!(svg.contains(">mean 350 ns, max 700 ns<") && svg.contains(">mean 235 ns, max 470 ns<"));
    let maps = embedded_pngs(&svg);
    assert_eq!(maps.len(), 3);
    // The last sample: 700 ns with baseline, 470 with simd. On the shared scale
    // simd's last sample is 470 / 700 of the way up, not at the top as on its own;
    // the same value (the first sample, 0 ns) is the same colour in both.
    let (width, height) = maps[0].dimensions();
    let last = |p: &image::RgbImage| *p.get_pixel(width - 1, height - 1);
    let first = |p: &image::RgbImage| *p.get_pixel(0, 0);
    assert_eq!(first(&maps[0]), first(&maps[1]));
    assert_ne!(last(&maps[0]), last(&maps[1]));
    assert_eq!(
        last(&maps[1]),
        last(&maps[2]),
        "simd and bvh both end at 470 ns"
    );
    // Viridis at 1 (yellow) and at 470 / 700 = 0.6714: between the keys at 0.6 (34,
    // 168, 132) and 0.7 (67, 191, 113), 71.4 % of the way: 57.6, 184.4, 118.4.
    assert_eq!(last(&maps[0]).0, [253, 231, 37]);
    assert_eq!(last(&maps[1]).0, [58, 184, 118]);

    // The busiest pixel's sphere tests and the clock, from the results.
    let max_of = |name: &str, key: &str| {
        scene
            .pixel_maps
            .iter()
            .find(|m| m.variant == name)
            .and_then(|m| m.maps.iter().find(|x| x.key == key))
            .map(|x| x.max)
            .expect("map")
    };
    let expected = format!(
        "On rings the busiest pixel makes {} sphere tests with baseline, against {} with simd and {} with bvh.",
        format::count(max_of("baseline", "tests.sphere.tests")),
        format::count(max_of("simd", "tests.sphere.tests")),
        format::count(max_of("bvh", "tests.sphere.tests")),
    );
    assert!(text.contains(&expected), "{expected} not in: {text}");
    assert!(
        text.contains("The time maps' clock ticks every 0.42 ns"),
        "{text}"
    );
    let html = reports::html::render(&doc);
    assert!(html.contains("id=\"chart-pixel-maps-rings-time_ns\""));
}

#[test]
fn pixel_maps_without_their_raw_values_say_so_in_one_sentence() {
    // The sample's files: every map's NumPy file holds one value, not the grid.
    let dir = TempDir::new("machine-map-files").expect("temp dir");
    let doc = document_of(sample_results(), dir.path());
    let s = section(&doc, "pixel-maps");
    assert!(figures(s).is_empty());
    let text = prose(s);
    assert!(
        text.contains("Not drawn because the raw values could not be read: baseline's time.ns (pixel-maps/rings/baseline/time.ns.npy: 1×1 values, not the "),
        "{text}"
    );
    assert_eq!(
        text.matches("Not drawn because the raw values could not be read")
            .count(),
        doc.sections
            .iter()
            .find(|s| s.id == "pixel-maps")
            .map_or(0, |s| s
                .blocks
                .iter()
                .filter(|b| matches!(b, Block::Heading { .. }))
                .count()),
        "one sentence a scene"
    );
}

#[test]
fn a_file_without_the_new_fields_leaves_their_sections_out() {
    let dir = TempDir::new("machine-older").expect("temp dir");
    let mut r = sample_results();
    r.peak = None;
    for scene in &mut r.scenes {
        scene.bvh_quality.clear();
        scene.pixel_maps.clear();
        for v in &mut scene.variants {
            v.efficiency = None;
            v.ray_rates = None;
            v.lane_utilization = None;
        }
    }
    let doc = document_of(r, dir.path());
    let html = reports::html::render(&doc);
    for id in ["ray-rates", "roofline", "pixel-maps", "bvh-quality"] {
        assert!(doc.section(id).is_none(), "{id} is there");
        assert!(
            !html.contains(&format!("<section id=\"{id}\">")),
            "{id} in the HTML"
        );
        assert!(
            !html.contains(&format!("href=\"#{id}\"")),
            "{id} in the nav"
        );
    }
    assert!(
        !doc.tables()
            .any(|t| t.columns.iter().any(|c| c.title == "SIMD lanes"))
    );
    assert!(doc.section("variants").is_some() && doc.section("spd").is_some());
}

#[test]
fn scenes_with_one_tree_share_a_table_of_measured_against_predicted_boxes() {
    let dir = TempDir::new("machine-bvh-single").expect("temp dir");
    let mut r = sample_results();
    // Rings keeps only the binned SAH tree, as a suite leaves a large frame.
    let scene = r
        .scenes
        .iter_mut()
        .find(|s| s.name == "rings")
        .expect("rings");
    scene.bvh_quality.retain(|t| t.builder == "binned_sah");
    let tree = scene.bvh_quality[0].clone();
    let doc = document_of(r, dir.path());
    let s = section(&doc, "bvh-quality");
    let t = tables(s)[0];
    assert_eq!(t.rows.len(), 1);
    let row = &t.rows[0];
    assert_eq!(row[0].text, "rings");
    let ratio = tree.measured_nodes_per_ray / tree.predicted_nodes_per_ray;
    let column = titles(t)
        .iter()
        .position(|c| *c == "measured ÷ predicted")
        .expect("ratio column");
    assert_eq!(row[column].text, format::speedup(ratio));
    let text = prose(s);
    assert!(
        text.contains(&format!(
            "were {} (rings) to {} (rings)",
            format::speedup(ratio),
            format::speedup(ratio)
        )),
        "{text}"
    );
}
