//! The report's outline: its sections in order ([`SECTIONS`]), their headings and the
//! part each stands in. One table, read by the builder of every section and by the
//! outputs (the HTML's contents, the PDF's parts).

/// Where a section stands: the main body, the appendix, or folded into a chapter of
/// the main body as one of its parts (a sub-heading with the section's id as anchor).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    Main,
    /// Inside the chapter with this id.
    Within(&'static str),
    Appendix,
}

/// The report's sections: id, heading and part, in order. The main body answers first
/// and then has four chapters (profile, variants, hardware, images); what supports
/// them (per-scene tables, rates, rooflines, maps, SPD statistics, benchmarks) is the
/// appendix. The comparison comes only with several runs, and first: a report of
/// several runs opens with what changed. The ray-rates, roofline, pixel-maps and
/// bvh-quality sections come only with results that hold their data.
pub const SECTIONS: [(&str, &str, Part); 28] = [
    ("comparison", "What changed between the runs", Part::Main),
    ("answers", "Answers", Part::Main),
    ("profile", "Profile: where the time goes", Part::Main),
    ("profile-flat", "Flat profile", Part::Within("profile")),
    (
        "profile-charts",
        "Calls and self time per function",
        Part::Within("profile"),
    ),
    ("flamegraphs", "Flamegraphs", Part::Within("profile")),
    (
        "amdahl",
        "Amdahl's law: what speeding up a function would give",
        Part::Within("profile"),
    ),
    (
        "variants",
        "Variants: what each optimization buys and costs",
        Part::Main,
    ),
    ("hardware", "Hardware: the FPGA pipeline", Part::Main),
    (
        "hardware-tables",
        "The model against tables 7 and 8",
        Part::Within("hardware"),
    ),
    (
        "hardware-synthesis",
        "The generated RTL through Yosys: cells, logic depth, clock",
        Part::Within("hardware"),
    ),
    (
        "hw-optimizations",
        "The thesis's optimizations in cycles and logic",
        Part::Within("hardware"),
    ),
    (
        "device-utilization",
        "Device utilization",
        Part::Within("hardware"),
    ),
    (
        "design-space",
        "Would it pay off: every design on every device",
        Part::Within("hardware"),
    ),
    (
        "sw-hw",
        "Software against hardware",
        Part::Within("hardware"),
    ),
    (
        "images",
        "Images: what the variants change in the picture",
        Part::Main,
    ),
    (
        "summary",
        "All findings, the machine and the scenes",
        Part::Appendix,
    ),
    (
        "variants-by-scene",
        "Variants scene by scene",
        Part::Appendix,
    ),
    (
        "profile-details",
        "Profile details: call graphs, native symbols, the best variant",
        Part::Appendix,
    ),
    (
        "ray-rates",
        "Rays per second and where the time goes",
        Part::Appendix,
    ),
    (
        "roofline",
        "Roofline: attained GFLOP/s against the machine's peaks",
        Part::Appendix,
    ),
    ("pixel-maps", "Per-pixel maps of the work", Part::Appendix),
    (
        "time-vs-primitives",
        "Render time against primitive count",
        Part::Appendix,
    ),
    ("spd", "SPD scene statistics", Part::Appendix),
    (
        "bvh-quality",
        "BVH quality: predicted against measured cost",
        Part::Appendix,
    ),
    (
        "criterion",
        "Micro-benchmarks: time and instructions",
        Part::Appendix,
    ),
    ("failures", "Failures", Part::Appendix),
    ("reproduce", "How to reproduce", Part::Appendix),
];

/// The heading of section `id` (the id itself when it is not one of [`SECTIONS`]).
pub fn heading_of(id: &str) -> &str {
    SECTIONS
        .iter()
        .find(|(sid, _, _)| *sid == id)
        .map_or(id, |(_, heading, _)| heading)
}

/// The part of the report section `id` stands in ([`Part::Main`] when it is not one of
/// [`SECTIONS`]).
pub fn part_of(id: &str) -> Part {
    SECTIONS
        .iter()
        .find(|(sid, _, _)| *sid == id)
        .map_or(Part::Main, |(_, _, part)| *part)
}
