//! The thesis's profile (ch. 8.1, table 6: gprof's flat profile of SPD rings at
//! 640×480, colour, on a Core i5-4570), typed once, with the rtprof counter and phase
//! each row corresponds to, so a report can set a run's profile beside it row by row.

/// One row of table 6 and where rtprof has the same work.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Table6Row {
    /// The name as table 6 prints it.
    pub thesis_name: &'static str,
    /// % of the time, self.
    pub percent: f64,
    pub self_seconds: f64,
    pub calls: f64,
    /// The rtprof counter of the same calls.
    pub counter: &'static str,
    /// The tracer's profile phase of the same work, when it is one (the vector
    /// operations are inlined into their callers, so they are counted, not timed).
    pub phase: Option<&'static str>,
}

/// Eye rays of the thesis's profiled frame (640×480, one ray a pixel).
pub const TABLE_6_EYE_RAYS: u64 = 640 * 480;

/// The scene and frame of table 6.
pub const TABLE_6_SCENE: &str = "SPD rings, 640×480";

const fn row(
    thesis_name: &'static str,
    percent: f64,
    self_seconds: f64,
    calls: f64,
    counter: &'static str,
    phase: Option<&'static str>,
) -> Table6Row {
    Table6Row {
        thesis_name,
        percent,
        self_seconds,
        calls,
        counter,
        phase,
    }
}

/// The rows of table 6 that rtprof counts (the `RayTracer` and `Primary ray info`
/// rows, one call each, are the program's entry points).
pub const TABLE_6: [Table6Row; 15] = [
    row(
        "Intersection test",
        12.00,
        53.56,
        1.0056e6,
        "calls.intersect",
        None,
    ),
    row(
        "Shading",
        0.00,
        0.00,
        3.072e5,
        "calls.shade",
        Some("shading"),
    ),
    row(
        "Color Contribution",
        0.00,
        0.01,
        2.328e5,
        "calls.color_contribution",
        None,
    ),
    row("Vector +", 0.00, 0.01, 4.789101e6, "ops.add", None),
    row("Vector -", 7.55, 33.70, 4.156549e9, "ops.sub", None),
    row("Vector cross", 0.00, 0.01, 1.312802e6, "ops.cross", None),
    row("Vector dotPoint", 21.91, 97.78, 3.902026e9, "ops.dot", None),
    row(
        "Vector normalize",
        0.00,
        0.01,
        3.182902e6,
        "ops.normalize",
        None,
    ),
    row("Vector scale", 0.01, 0.06, 3.363227e7, "ops.scale", None),
    row("SQRT", 0.04, 0.18, 4.761192e7, "ops.sqrt", None),
    row("Pow", 0.00, 0.00, 4.10344e5, "ops.pow", None),
    row(
        "Sphere Intersection test",
        15.15,
        67.60,
        4.22352e9,
        "tests.sphere.tests",
        Some("sphere test"),
    ),
    row(
        "Cylinder Intersection test",
        21.12,
        94.25,
        4.22352e9,
        "tests.cylinder.tests",
        Some("cylinder test"),
    ),
    row(
        "Polygon Intersection test",
        0.01,
        0.06,
        1.0056e6,
        "tests.polygon.tests",
        Some("polygon test"),
    ),
    row(
        "Plane Intersection test",
        0.02,
        0.08,
        1.0056e6,
        "tests.plane.tests",
        None,
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_is_the_digests_and_its_own_arithmetic_holds() {
        // 4,200 spheres and 4,200 cylinders each tested by every one of the 1.0056e6
        // intersection queries (the thesis's own reading of its table).
        let queries = TABLE_6[0].calls;
        for name in ["Sphere Intersection test", "Cylinder Intersection test"] {
            let r = TABLE_6.iter().find(|r| r.thesis_name == name).unwrap();
            assert_eq!(r.calls, 4200.0 * queries);
        }
        // Subtraction is called more than the dot product in the table itself.
        let calls = |name: &str| {
            TABLE_6
                .iter()
                .find(|r| r.thesis_name == name)
                .unwrap()
                .calls
        };
        assert!(calls("Vector -") > calls("Vector dotPoint"));
        // Every counter named is a distinct counter.
        let mut keys: Vec<&str> = TABLE_6.iter().map(|r| r.counter).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), TABLE_6.len());
    }
}
