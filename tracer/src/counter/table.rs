//! The counter table: every counter of the tracer declared once, in the order of the
//! thesis's gprof table 6 (calls, operations, tests, rays, acceleration). pbrt-v4's
//! `STAT_COUNTER` is the model: a counter is declared where it is defined, and
//! everything that names it is made from that declaration.
//!
//! Each row gives the event the counting layer tallies ([`Stat`], or `_` for the ray
//! counts the renderer keeps in a [`RayCounts`]), the counter's path in [`Counts`]
//! (which is also its dotted key in `rtprof count` and in results.json, and its path in
//! the JSON of `rtprof count --json`), what it counts, and the profiled functions that
//! are called exactly that many times, by the name the profile prints (see
//! [`CounterDef::functions`]). From the table come the [`Stat`] enum, [`COUNTERS`],
//! [`Counts::from_parts`], [`Counts::from_keys`], [`Counts::rows`] and
//! [`Counts::function_calls`].

use super::counts::{Counts, RayCounts};

/// One counter's declaration (a row of [`COUNTERS`]).
#[derive(Clone, Copy, Debug)]
pub struct CounterDef {
    /// Dotted key, `group.name` or `tests.kind.tests`: the path in [`Counts`] and in the
    /// JSON of `rtprof count --json`, and the key in `rtprof count` and results.json.
    pub key: &'static str,
    /// The event the counting layer tallies; `None` for a ray count (kept by the
    /// renderer in [`RayCounts`]).
    pub stat: Option<Stat>,
    /// What is counted, in a few words.
    pub description: &'static str,
    /// Functions called exactly this many times, named as the profile prints them:
    /// `Type::method`, `module::function`, or the bare operation name for a method of
    /// the counting layer (see [`super::COUNTING_LAYER`]). A test checks that each
    /// names a function of the tracer's source, so a rename cannot silently leave the
    /// profile's `calls` column blank.
    pub functions: &'static [&'static str],
    /// Reads this counter from a report.
    pub value: fn(&Counts) -> u64,
    /// Writes this counter into a report ([`Counts::from_keys`]: counts another
    /// program's probe made, by key).
    pub set: fn(&mut Counts, u64),
}

/// A profiled function whose calls are a combination of counters (not one counter).
#[derive(Clone, Copy, Debug)]
pub struct DerivedCalls {
    /// The function, named as in [`CounterDef::functions`].
    pub function: &'static str,
    /// Its calls.
    pub value: fn(&Counts) -> u64,
}

/// Declares the counters: the [`Stat`] enum, [`COUNTERS`] and [`Counts::from_parts`].
///
/// Row: `Stat => path.to.field: "description" ["function", …];`, with `_` in place of
/// the `Stat` for a ray count. Rows are collected one by one (`@row`), then expanded
/// at once (`@emit`).
macro_rules! counter_table {
    // A ray count: no `Stat`.
    (@row [$($stats:tt)*] [$($defs:tt)*]
        _ => $first:ident $(. $rest:ident)+ : $description:literal [$($function:literal),* $(,)?];
        $($tail:tt)*
    ) => {
        counter_table!(@row [$($stats)*]
            [$($defs)* {(_) ($first $(. $rest)+) $description [$($function),*]}]
            $($tail)*);
    };
    // A count the counting layer keeps.
    (@row [$($stats:tt)*] [$($defs:tt)*]
        $stat:ident => $first:ident $(. $rest:ident)+ : $description:literal [$($function:literal),* $(,)?];
        $($tail:tt)*
    ) => {
        counter_table!(@row [$($stats)* ($stat $description)]
            [$($defs)* {($stat) ($first $(. $rest)+) $description [$($function),*]}]
            $($tail)*);
    };
    (@row [$($stats:tt)*] [$($defs:tt)*]) => {
        counter_table!(@emit [$($stats)*] [$($defs)*]);
    };
    (@emit [$(($stat:ident $stat_description:literal))*]
        [$({($source:tt) ($first:ident $(. $rest:ident)+) $description:literal [$($function:literal),*]})*]
    ) => {
        /// One event the counting layer tallies (declared in the counter table,
        /// [`COUNTERS`]; ray counts are not events, the renderer keeps them).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr(usize)]
        pub enum Stat {
            $(#[doc = $stat_description] $stat,)*
        }

        impl Stat {
            /// Every event, in table order (`Stat::ALL[s as usize] == s`).
            pub const ALL: &'static [Stat] = &[$(Stat::$stat),*];
        }

        /// Every counter, in the order of the thesis's table 6.
        pub const COUNTERS: &[CounterDef] = &[$(
            CounterDef {
                key: concat!(stringify!($first) $(, ".", stringify!($rest))+),
                stat: counter_table!(@stat $source),
                description: $description,
                functions: &[$($function),*],
                value: |counts: &Counts| counts.$first $(.$rest)+,
                set: |counts: &mut Counts, value: u64| counts.$first $(.$rest)+ = value,
            },
        )*];

        impl Counts {
            /// Assembles the report from a counter's totals and the ray counts.
            pub fn from_parts(totals: &[u64; STAT_COUNT], rays: RayCounts) -> Self {
                let mut counts = Counts {
                    rays,
                    ..Counts::default()
                };
                $(counter_table!(@store $source counts totals $first $(. $rest)+);)*
                counts
            }
        }
    };
    (@stat _) => { None };
    (@stat $stat:ident) => { Some(Stat::$stat) };
    // Ray counts arrive whole in `rays`.
    (@store _ $counts:ident $totals:ident $($path:tt)+) => {};
    (@store $stat:ident $counts:ident $totals:ident $($path:tt)+) => {
        $counts.$($path)+ = $totals[Stat::$stat as usize];
    };
    // The entry: every row, unparsed.
    ($($rows:tt)*) => {
        counter_table!(@row [] [] $($rows)*);
    };
}

counter_table! {
    // calls.*: the tracer's main functions.
    PrimaryRaySetup => calls.primary_ray_setup: "camera set-ups (one per render)" [];
    Trace => calls.trace: "closest-hit queries: eye, reflection and refraction rays"
        // `closest` is each structure's one closest-hit search; the `closest_hit`
        // wrappers of brute force and the BVH are left out: with `bounded`, eye rays
        // enter through `closest_hit_from_eye` instead.
        ["BruteForce::closest", "Bvh::closest", "Simd::closest_hit"];
    Intersect => calls.intersect: "intersection queries: closest-hit and shadow" [];
    Shade => calls.shade: "hits shaded" ["Shader::shade"];
    ColorContribution => calls.color_contribution: "lights reached from a shaded hit"
        ["shading::color_contribution"];
    // ops.*: the counting layer's maths, one per call whatever the width.
    Add => ops.add: "vector sums" ["add"];
    Sub => ops.sub: "vector differences" ["sub"];
    Cross => ops.cross: "cross products" ["cross"];
    Dot => ops.dot: "dot products" ["dot"];
    Normalize => ops.normalize: "normalizations (their inner dot and root not counted)"
        ["normalize"];
    Scale => ops.scale: "vector times scalar" ["scale"];
    Sqrt => ops.sqrt: "scalar square roots" ["sqrt"];
    Pow => ops.pow: "powers (the Phong highlight)" ["pow"];
    // tests.*: a test per primitive tested against a ray, a hit per test that found an
    // intersection inside the query's range. Every test runs against the query's reach
    // (the closest-so-far comparison is the caller's), so hits do not depend on the
    // order of the primitives in the file.
    SphereTest => tests.sphere.tests: "ray-sphere tests run" ["Sphere::intersect"];
    SphereHit => tests.sphere.hits:
        "ray-sphere tests that found a visible intersection inside the query's range (beyond the ray's offset, before the light for a shadow ray), nearest or not" [];
    CylinderTest => tests.cylinder.tests: "ray-cylinder tests run" ["Cylinder::intersect"];
    CylinderHit => tests.cylinder.hits:
        "ray-cylinder tests that found a visible intersection inside the query's range, nearest or not" [];
    ConeTest => tests.cone.tests: "ray-cone tests run" ["Cone::intersect"];
    ConeHit => tests.cone.hits:
        "ray-cone tests that found a visible intersection inside the query's range, nearest or not" [];
    PolygonTest => tests.polygon.tests: "ray-polygon tests run" ["Polygon::intersect"];
    PolygonHit => tests.polygon.hits:
        "ray-polygon tests whose plane hit inside the query's range lies inside the outline" [];
    PatchTest => tests.patch.tests: "ray-patch tests run" ["Patch::intersect"];
    PatchHit => tests.patch.hits:
        "ray-patch tests whose plane hit inside the query's range lies inside the outline" [];
    // The wide BVH (`bvh+simd`) tests polygons and patches as the triangles of their
    // outlines, 8 in SIMD lanes: a triangle test is the plane test of the triangle's
    // polygon or patch, then its three edges.
    TriangleTest => tests.triangle.tests:
        "ray-triangle tests run (triangles of polygons and patches, in the wide BVH's lanes)" [];
    TriangleHit => tests.triangle.hits:
        "ray-triangle tests whose plane hit inside the query's range lies inside the triangle" [];
    // The plane test opens every polygon and patch test (as in the thesis's table).
    PlaneTest => tests.plane.tests: "ray-plane tests: the first step of every polygon and patch test"
        ["PlanarOutline::intersect_plane"];
    PlaneHit => tests.plane.hits: "ray-plane tests that met the plane inside the query's range" [];
    // rays.*: the SPD's ray statistics.
    _ => rays.primary: "eye rays ((W+1)(H+1) with SPD corners, W·H otherwise)"
        ["Shader::primary", "Shader::primary_from_eye", "Camera::ray", "Camera::ray_from_eye"];
    _ => rays.primary_hit: "eye rays that hit an object" [];
    _ => rays.shadow: "shadow rays cast toward lights"
        ["BruteForce::occluded", "Simd::occluded", "Bvh::occluded"];
    _ => rays.shadow_blocked: "shadow rays that found an occluder" [];
    _ => rays.reflection: "reflection rays spawned" [];
    _ => rays.refraction: "refraction rays spawned" [];
    // accel.*: the BVH's traversal and the SIMD lanes (zero for the other structures).
    NodesVisited => accel.nodes_visited: "BVH nodes visited" [];
    LeavesVisited => accel.leaves_visited: "BVH leaves visited" [];
    LanesIssued => accel.lanes_issued: "SIMD lanes issued (8 per chunk of primitives or wide node tested)" [];
    LanesActive => accel.lanes_active: "SIMD lanes issued that held a primitive or a child box" [];
}

/// Profiled functions whose calls combine counters.
pub const DERIVED_CALLS: &[DerivedCalls] = &[DerivedCalls {
    // Eye rays start in `Shader::primary`; `trace` is every later (secondary) ray.
    function: "Shader::trace",
    value: |counts| counts.calls.trace.saturating_sub(counts.rays.primary),
}];

/// Number of [`Stat`] variants.
pub const STAT_COUNT: usize = Stat::ALL.len();

impl Counts {
    /// Every count as `(dotted key, value)`, in the order of the thesis's table 6.
    pub fn rows(&self) -> Vec<(&'static str, u64)> {
        COUNTERS
            .iter()
            .map(|def| (def.key, (def.value)(self)))
            .collect()
    }

    /// The counts as a text table (`rtprof count`): name, value, and what the counter
    /// counts (its description in the counter table).
    pub fn to_text(&self) -> String {
        self.to_text_with(None)
    }

    /// The table of [`Counts::to_text`] with one more column before the meaning,
    /// `(heading, cell of a value)`: `rtprof record` adds each count per eye ray. The
    /// caller formats the cells (numbers are formatted in `reports`, which the tracer
    /// does not depend on), so there is one table and one layout.
    pub fn to_text_with(&self, extra: Option<(&str, &dyn Fn(u64) -> String)>) -> String {
        let width = COUNTERS.iter().map(|d| d.key.len()).max().unwrap_or(4);
        let extra_width = extra.map_or(0, |(heading, _)| heading.chars().count().max(12));
        let mut out = format!("{:<width$}  {:>16}  ", "name", "calls");
        if let Some((heading, _)) = extra {
            out += &format!("{heading:>extra_width$}  ");
        }
        out += "meaning\n";
        for def in COUNTERS {
            let value = (def.value)(self);
            out += &format!("{:<width$}  {value:>16}  ", def.key);
            if let Some((_, cell)) = extra {
                out += &format!("{:>extra_width$}  ", cell(value));
            }
            out += def.description;
            out.push('\n');
        }
        out
    }

    /// A report from counts given by dotted key (another program's probe writes the
    /// counter table's keys): the counts, and the keys the table does not have.
    pub fn from_keys<'k>(totals: impl IntoIterator<Item = (&'k str, u64)>) -> (Self, Vec<String>) {
        let mut counts = Counts::default();
        let mut unknown = Vec::new();
        for (key, value) in totals {
            match by_key(key) {
                Some(def) => (def.set)(&mut counts, value),
                None => unknown.push(key.to_string()),
            }
        }
        (counts, unknown)
    }

    /// The counter table as a Markdown page (docs/counters.md is this text; a test
    /// keeps the two equal): each counter's key and meaning, in table order.
    pub fn table_markdown() -> String {
        let mut out = String::from(
            "# The counters\n\n\
             Generated from the counter table (`tracer/src/counter/table.rs`), the one place\n\
             each counter is declared; `rtprof count` prints the same meanings beside the\n\
             values. A test (`tracer/tests/counter_docs.rs`) fails when this page and the\n\
             table differ; `RTPROF_BLESS=1 cargo test -p tracer --test counter_docs`\n\
             rewrites it.\n\n| counter | meaning |\n|---|---|\n",
        );
        for def in COUNTERS {
            out += &format!("| `{}` | {} |\n", def.key, def.description);
        }
        out
    }

    /// Exact calls of the profiled functions the counters determine, by the name the
    /// profile prints (table order, then [`DERIVED_CALLS`]). Functions not listed have
    /// no exact count. Every structure's query functions are listed; a profile keeps
    /// those it sampled.
    pub fn function_calls(&self) -> Vec<(&'static str, u64)> {
        let declared = COUNTERS.iter().flat_map(|def| {
            let n = (def.value)(self);
            def.functions.iter().map(move |&f| (f, n))
        });
        let derived = DERIVED_CALLS.iter().map(|d| (d.function, (d.value)(self)));
        declared.chain(derived).collect()
    }
}

/// The declaration of the counter with dotted key `key`.
pub fn by_key(key: &str) -> Option<&'static CounterDef> {
    COUNTERS.iter().find(|def| def.key == key)
}

/// The counting layer's operations that profiles print by their bare name (`dot`,
/// `sqrt`: the declared functions without a `::`), methods of the
/// [`super::COUNTING_LAYER`] types.
pub fn counted_operations() -> Vec<&'static str> {
    COUNTERS
        .iter()
        .flat_map(|def| def.functions.iter().copied())
        .filter(|f| !f.contains("::"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::counter::{COUNTING_LAYER, Count, Counter};
    use std::collections::{BTreeMap, BTreeSet};

    /// A report in which every counter has its own value: totals 1000 + the event's
    /// index, rays 2000 + their position.
    fn distinct_counts() -> Counts {
        let mut counter = Count::default();
        for &stat in Stat::ALL {
            counter.tally_n(stat, 1000 + stat as u64);
        }
        let rays = RayCounts {
            primary: 2000,
            primary_hit: 2001,
            shadow: 2002,
            shadow_blocked: 2003,
            reflection: 2004,
            refraction: 2005,
        };
        Counts::from_parts(&counter.totals().unwrap_or([0; STAT_COUNT]), rays)
    }

    /// `"a.b.c": n` for every number in `value`.
    fn json_leaves(prefix: &str, value: &serde_json::Value, out: &mut BTreeMap<String, u64>) {
        match value {
            serde_json::Value::Object(map) => {
                for (k, v) in map {
                    let key = if prefix.is_empty() {
                        k.clone()
                    } else {
                        format!("{prefix}.{k}")
                    };
                    json_leaves(&key, v, out);
                }
            }
            serde_json::Value::Number(n) => {
                out.insert(prefix.to_string(), n.as_u64().unwrap_or(u64::MAX));
            }
            other => panic!("{prefix}: not a number or object: {other}"),
        }
    }

    #[test]
    fn every_stat_has_exactly_one_row_and_lands_in_it() {
        for (index, &stat) in Stat::ALL.iter().enumerate() {
            assert_eq!(stat as usize, index);
            let rows: Vec<_> = COUNTERS.iter().filter(|d| d.stat == Some(stat)).collect();
            assert_eq!(rows.len(), 1, "{stat:?}");
            // The total of this event, and of no other, is what the row reads.
            assert_eq!(
                (rows[0].value)(&distinct_counts()),
                1000 + index as u64,
                "{stat:?}"
            );
        }
        assert_eq!(STAT_COUNT, 31);
        // The rest are the six ray counts.
        let rays: Vec<_> = COUNTERS.iter().filter(|d| d.stat.is_none()).collect();
        assert_eq!(rays.len(), 6);
        assert!(rays.iter().all(|d| d.key.starts_with("rays.")));
    }

    #[test]
    fn keys_are_unique_and_are_the_json_paths_of_counts() {
        let counts = distinct_counts();
        let keys: BTreeSet<&str> = COUNTERS.iter().map(|d| d.key).collect();
        assert_eq!(keys.len(), COUNTERS.len(), "a key is declared twice");
        let mut leaves = BTreeMap::new();
        let json = serde_json::to_value(counts).unwrap_or_default();
        json_leaves("", &json, &mut leaves);
        let rows: BTreeMap<String, u64> = counts
            .rows()
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect();
        // Every value is distinct, so equal maps mean every key reads its own field.
        assert_eq!(rows, leaves);
        assert_eq!(rows.values().collect::<BTreeSet<_>>().len(), 37);
        assert_eq!(
            by_key("tests.sphere.tests").map(|d| d.stat),
            Some(Some(Stat::SphereTest))
        );
        assert!(by_key("tests.sphere").is_none());
    }

    #[test]
    fn counts_made_from_keys_read_back_by_the_same_keys() {
        let counts = distinct_counts();
        let (back, unknown) = Counts::from_keys(counts.rows());
        assert_eq!(back, counts);
        assert!(unknown.is_empty());
        let (one, unknown) = Counts::from_keys([("tests.sphere.tests", 7), ("bvh refits", 3)]);
        assert_eq!(one.tests.sphere.tests, 7);
        assert_eq!(one.rows().iter().map(|r| r.1).sum::<u64>(), 7);
        assert_eq!(unknown, ["bvh refits"]);
    }

    #[test]
    fn the_table_with_a_column_keeps_the_plain_table_s_rows() {
        let mut counts = Counts::default();
        counts.rays.primary = 4;
        counts.tests.sphere.tests = 10;
        let plain = counts.to_text();
        let per = |v: u64| format!("{}/4", v);
        let with = counts.to_text_with(Some(("per eye ray", &per)));
        assert_eq!(plain.lines().count(), with.lines().count());
        let sphere = with
            .lines()
            .find(|l| l.starts_with("tests.sphere.tests "))
            .unwrap_or_default();
        assert!(sphere.contains(" 10  ") && sphere.contains("10/4  ray-sphere tests run"));
        assert!(
            with.lines()
                .next()
                .unwrap_or_default()
                .contains("per eye ray  meaning")
        );
        // Without the column, the line is the plain table's.
        let plain_sphere = plain
            .lines()
            .find(|l| l.starts_with("tests.sphere.tests "))
            .unwrap_or_default();
        assert_eq!(
            plain_sphere.replace(" ", ""),
            sphere.replace("10/4", "").replace(" ", "")
        );
    }

    #[test]
    fn rows_follow_table_6_groups() {
        let order = ["calls", "ops", "tests", "rays", "accel"];
        let groups: Vec<usize> = COUNTERS
            .iter()
            .map(|d| {
                let group = d.key.split('.').next().unwrap_or_default();
                order.iter().position(|g| *g == group).unwrap_or(usize::MAX)
            })
            .collect();
        assert!(groups.windows(2).all(|w| w[0] <= w[1]), "{groups:?}");
        assert_eq!(groups.last(), Some(&4));
        assert_eq!(COUNTERS[0].key, "calls.primary_ray_setup");
    }

    #[test]
    fn function_calls_take_the_counter_values() {
        let mut counts = Counts::default();
        counts.ops.dot = 42;
        counts.tests.sphere.tests = 7;
        counts.calls.trace = 10;
        counts.rays.primary = 4;
        counts.rays.shadow = 3;
        let calls: BTreeMap<&str, u64> = counts.function_calls().into_iter().collect();
        assert_eq!(calls.get("dot"), Some(&42));
        assert_eq!(calls.get("Sphere::intersect"), Some(&7));
        assert_eq!(calls.get("Bvh::closest"), Some(&10));
        assert_eq!(calls.get("Shader::trace"), Some(&6));
        assert_eq!(calls.get("Bvh::occluded"), Some(&3));
        assert_eq!(calls.get("Shader::reflect"), None);
        // One count per function name.
        assert_eq!(calls.len(), counts.function_calls().len());
        assert_eq!(
            counted_operations(),
            [
                "add",
                "sub",
                "cross",
                "dot",
                "normalize",
                "scale",
                "sqrt",
                "pow"
            ]
        );
    }

    /// A top-level item of a source file: its header (up to its `{`) and its text.
    struct Item {
        header: String,
        text: String,
    }

    /// The top-level `impl` and `trait` blocks and free functions of every source file
    /// of the crate, by module name (the file's stem, or its directory's for mod.rs).
    fn source_items() -> Vec<(String, Item)> {
        fn walk(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
            let entries = std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{e}"));
            for entry in entries.flatten() {
                let path = entry.path();
                if path.is_dir() {
                    walk(&path, out);
                } else if path.extension().is_some_and(|e| e == "rs") {
                    out.push(path);
                }
            }
        }
        let mut files = Vec::new();
        walk(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
            &mut files,
        );
        let mut items = Vec::new();
        for path in files {
            let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
            let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
            let module = match stem.as_deref() {
                Some("mod") => path
                    .parent()
                    .and_then(|p| p.file_name())
                    .map(|s| s.to_string_lossy().into_owned()),
                _ => stem,
            }
            .unwrap_or_default();
            // rustfmt's layout: a top-level item starts at column 0 and its block ends
            // with a `}` alone at column 0.
            let lines: Vec<&str> = text.lines().collect();
            let mut at = 0;
            while at < lines.len() {
                let line = lines[at];
                let opens = [
                    "impl",
                    "pub trait ",
                    "trait ",
                    "fn ",
                    "pub fn ",
                    "pub(crate) fn ",
                ]
                .iter()
                .any(|p| line.starts_with(p));
                if !opens {
                    at += 1;
                    continue;
                }
                // A one-line item (`impl Trait for Type {}`) ends where it starts.
                let end = if line.trim_end().ends_with('}') {
                    at
                } else {
                    (at..lines.len())
                        .find(|&i| lines[i] == "}")
                        .unwrap_or(lines.len())
                };
                let block = lines[at..(end + 1).min(lines.len())].join("\n");
                let header = block.split('{').next().unwrap_or_default().to_string();
                items.push((
                    module.clone(),
                    Item {
                        header,
                        text: block,
                    },
                ));
                at = end + 1;
            }
        }
        items
    }

    /// The type an `impl` or `trait` header is about (`impl<'a> Trait for Type<'a>` →
    /// `Type`), or the function a free function's header declares.
    fn subject(header: &str) -> String {
        let mut rest = header.trim_start();
        for prefix in ["pub(crate) ", "pub "] {
            rest = rest.strip_prefix(prefix).unwrap_or(rest);
        }
        let rest = if let Some(r) = rest.strip_prefix("impl") {
            // Skip the impl's generic parameters.
            let r = if r.starts_with('<') {
                let mut depth = 0;
                let mut end = 0;
                for (i, ch) in r.char_indices() {
                    match ch {
                        '<' => depth += 1,
                        '>' => {
                            depth -= 1;
                            if depth == 0 {
                                end = i + 1;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                &r[end..]
            } else {
                r
            };
            r.rsplit(" for ").next().unwrap_or(r)
        } else {
            rest.strip_prefix("trait ")
                .or_else(|| rest.strip_prefix("fn "))
                .unwrap_or(rest)
        };
        rest.trim_start()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    }

    fn declares_fn(text: &str, name: &str) -> bool {
        text.contains(&format!("fn {name}(")) || text.contains(&format!("fn {name}<"))
    }

    /// Whether `owner` (a type or trait) has a method `method` in the source.
    fn has_method(items: &[(String, Item)], owner: &str, method: &str) -> bool {
        items.iter().any(|(_, item)| {
            !item.header.contains("fn ")
                && subject(&item.header) == owner
                && declares_fn(&item.text, method)
        })
    }

    #[test]
    fn every_declared_function_is_a_function_of_the_source() {
        let items = source_items();
        assert!(items.len() > 50, "source not found: {} items", items.len());
        for owner in COUNTING_LAYER {
            assert!(
                items
                    .iter()
                    .any(|(_, i)| !i.header.contains("fn ") && subject(&i.header) == owner),
                "counting-layer type {owner} not in the source"
            );
        }
        let names = COUNTERS
            .iter()
            .flat_map(|d| d.functions.iter().copied())
            .chain(DERIVED_CALLS.iter().map(|d| d.function));
        for name in names {
            let found = match name.split_once("::") {
                // A counted operation: a method of the counting layer.
                None => COUNTING_LAYER
                    .iter()
                    .any(|owner| has_method(&items, owner, name)),
                Some((owner, function)) if owner.starts_with(char::is_uppercase) => {
                    has_method(&items, owner, function)
                }
                // `module::function`: a free function of that module.
                Some((module, function)) => items.iter().any(|(m, item)| {
                    m == module && item.header.contains("fn ") && subject(&item.header) == function
                }),
            };
            assert!(
                found,
                "{name} is declared in the counter table but not in the source"
            );
        }
    }

    #[test]
    fn the_source_check_tells_renamed_functions_apart() {
        let items = source_items();
        assert!(has_method(&items, "Sphere", "intersect"));
        assert!(!has_method(&items, "Sphere", "intersects"));
        assert!(!has_method(&items, "Sphere", "closest_hit"));
        assert!(has_method(&items, "Simd", "closest_hit"));
        assert!(has_method(&items, "Counter", "dot"));
        assert!(
            !has_method(&items, "NoCount", "dot"),
            "NoCount inherits dot"
        );
        assert_eq!(subject("impl<'s, I: Intersector> Shader<'s, I> "), "Shader");
        assert_eq!(
            subject("impl<C: Counter, S: SquareRoot> Counter for WithSqrt<C, S> "),
            "WithSqrt"
        );
        assert_eq!(
            subject("pub trait Counter: Default + Clone + Send + Sync "),
            "Counter"
        );
        assert_eq!(
            subject("fn color_contribution<C: Counter>(\n    m: &Material,"),
            "color_contribution"
        );
    }
}
