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

#[test]
fn pixel_maps_stand_side_by_side_per_counter_and_missing_files_cost_their_tile() {
    let dir = TempDir::new("machine-maps").expect("temp dir");
    let r = sample_results();
    write_sample_files(dir.path()).expect("sample files");
    // The maps of rings are lost: each tile must say so.
    std::fs::remove_dir_all(dir.path().join("pixel-maps/rings")).expect("remove the maps");
    let run = Run {
        label: "bench-1".to_string(),
        results: r.clone(),
        base_dir: dir.path().to_path_buf(),
    };
    let doc = document::build(&[run]).expect("document");
    let s = section(&doc, "pixel-maps");
    let scene = rings(&r);

    let grids = grids(s);
    let labels: Vec<&str> = grids.iter().map(|g| g.row_labels[0].as_str()).collect();
    assert_eq!(
        labels,
        [
            "time",
            "sphere tests",
            "cylinder tests",
            "polygon tests",
            "BVH nodes",
            "shadow rays",
            "ray-tree depth"
        ]
    );
    for g in &grids {
        assert_eq!(g.columns, 3);
        assert!(g.wide, "maps take the whole width");
    }
    // The suite's variant order: baseline, simd, bvh.
    let order: Vec<&str> = r
        .suite
        .variants
        .iter()
        .map(|v| v.as_str())
        .filter(|v| scene.pixel_maps.iter().any(|m| m.variant == *v))
        .collect();
    assert_eq!(order, ["baseline", "simd", "bvh"]);
    let time = grids[0];
    for (tile, name) in time.tiles.iter().zip(&order) {
        assert!(
            tile.caption
                .starts_with(&format!("{name} · time.ns, ns per sample (min ")),
            "{}",
            tile.caption
        );
        // The map files are gone: each tile says so.
        assert!(
            matches!(&tile.visual, Visual::Missing { text } if text.contains(&format!("image missing: pixel-maps/rings/{name}/time.ns.png"))),
            "{:?}",
            tile.visual
        );
    }
    // Only bvh traverses a tree.
    let nodes = grids[4];
    assert!(
        matches!(&nodes.tiles[0].visual, Visual::Placeholder { text } if text == "no BVH nodes with baseline")
    );
    assert!(
        matches!(&nodes.tiles[1].visual, Visual::Placeholder { text } if text == "no BVH nodes with simd")
    );
    assert!(
        nodes.tiles[2]
            .caption
            .starts_with("bvh · accel.nodes_visited, nodes per sample")
    );

    // The busiest pixel's sphere tests (the most tested kind of baseline: the first of
    // the largest maxima) and the clock.
    let max_of = |name: &str, key: &str| {
        scene
            .pixel_maps
            .iter()
            .find(|m| m.variant == name)
            .and_then(|m| m.maps.iter().find(|x| x.key == key))
            .map(|x| x.max)
            .expect("map")
    };
    let text = prose(s);
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
}

#[test]
fn pixel_map_files_are_embedded_when_they_are_there() {
    let dir = TempDir::new("machine-map-files").expect("temp dir");
    let r = sample_results();
    let maps = &rings(&r).pixel_maps[0];
    let legend = reports::pixel_maps::Legend {
        title: "time.ns".to_string(),
        unit: "ns per sample".to_string(),
        min: 0.0,
        max: 10.0,
    };
    let values: Vec<f64> = (0..maps.columns * maps.rows)
        .map(|i| f64::from(i % 11))
        .collect();
    let picture = reports::pixel_maps::false_colour(&values, maps.columns, maps.rows, &legend);
    let path = dir.path().join(&maps.directory).join("time.ns.png");
    std::fs::create_dir_all(path.parent().expect("parent")).expect("mkdir");
    picture.save(&path).expect("png");
    let doc = document_of(r.clone(), dir.path());
    let tile = &grids(section(&doc, "pixel-maps"))[0].tiles[0];
    let Visual::Image(image) = &tile.visual else {
        panic!("not embedded: {:?}", tile.visual);
    };
    // Laid out at the file's size, embedded at most as wide as a small map is drawn
    // (the PNG header's width: bytes 16 to 19, big-endian).
    assert_eq!(
        (image.width, image.height),
        (f64::from(picture.width()), f64::from(picture.height()))
    );
    let png = &doc.assets.get(&image.asset).expect("asset").bytes;
    let width = u32::from_be_bytes([png[16], png[17], png[18], png[19]]);
    assert!(
        width <= reports::pixel_maps::MIN_WIDTH && width < picture.width(),
        "{width}"
    );
    let html = reports::html::render(&doc);
    assert!(html.contains("alt=\"rings baseline time.ns\""));
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
