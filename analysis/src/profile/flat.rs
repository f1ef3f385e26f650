//! gprof's flat profile (binutils `gprof/hist.c` layout) from sampled call stacks,
//! with what gprof cannot give: inclusive time, a 95 % interval on every share, the
//! rows too rarely sampled to be told from zero, and the bottleneck by self time.
//!
//! # Figures
//! - *self* samples of a function: its frame was running; *inclusive*: it was anywhere
//!   on the stack, counted once per sample under recursion. `percent` is the self
//!   share, `inclusive_percent` the inclusive one, both of all samples (stacks without
//!   frames are ignored). Seconds = samples × `seconds_per_sample`, over all renders.
//! - `calls` are exact calls per render ([`ProfileInput`]); per-call times are
//!   `seconds / renders / calls`, in [`FlatProfile::unit`]. A count of 0 is no count
//!   (blank, as in gprof); functions with calls but no samples are listed.
//! - Intervals: Wilson score, 95 % ([`super::share_interval`]), in percent.
//! - `noise`: the self share is below the noise floor — the lower end of its 95 %
//!   interval is under half a sample, so its time cannot be told from none (for runs
//!   of more than a few dozen samples: at most one sample).
//!
//! # Rows and unit
//! Rows are sorted by self samples (descending), then calls (descending), then name,
//! so the noise rows are the last ones. The per-call unit is the finest of `s`, `ms`,
//! `us`, `ns` in which the largest per-call time of a printed row still fits gprof's
//! 8-character `%8.2f` column (below 100000): the largest value then prints with at
//! least 3 significant digits and the fast functions get the finest resolution the
//! column allows (gprof's own rule, the largest value in [1, 1000), printed a 40 ns
//! sphere test as 0.00 beside a 5 µs ray). Without any per-call time the unit is `s`.
//!
//! # Text
//! gprof's flat table with its header, preceded by the number of renders sampled
//! (for a profile read from gprof, [`super::gprof_import`], a line saying so; for
//! one run of another program, [`Origin::Recorded`], that it is one run).
//! Noise rows are left out of the table rather than printed as `0.00`: a gprof reader
//! would take `0.00` for "costs nothing". After the table (after a blank line, where
//! gprof prints its explanations) come the noise rows with their calls per render,
//! then every row's self and inclusive shares with their 95 % intervals, by inclusive
//! share, noise rows saying `noise` in the self column.

use super::Origin;
use super::c_format::{c_field, format_g};
use super::share_interval::{ShareInterval, Z_95, below_noise_floor, wilson_interval};
use super::tally::{ProfileInput, Tally, percent_of};
use serde::{Deserialize, Serialize};
use std::cmp::Reverse;
use std::fmt::Write as _;

/// Inclusive share (percent) from which a frame counts as the whole run (the render's
/// outermost frames, the single root): such rows are no bottleneck and are left out of
/// the Amdahl table, where "make the whole run free" tells nothing.
pub const WHOLE_RUN_PERCENT: f64 = 99.5;

/// What the texts of a recorded run ([`Origin::Recorded`]) say above their tables.
pub(super) const RECORDED_LINE: &str =
    "1 run of the program sampled; seconds are per run, no calls counted.\n";

/// Per-call units, coarsest first: the unit's name and the factor from seconds.
const PER_CALL_UNITS: [(&str, f64); 4] = [(" s", 1.0), ("ms", 1e3), ("us", 1e6), ("ns", 1e9)];

/// Largest value `%8.2f` prints in 8 characters (99999.99, rounding included).
const PER_CALL_COLUMN_LIMIT: f64 = 99_999.995;

/// gprof's flat profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FlatProfile {
    /// Sampled by rtprof or read from gprof (what the text says above the table).
    #[serde(default)]
    pub origin: Origin,
    pub seconds_per_sample: f64,
    /// Seconds of all samples (all renders).
    pub total_seconds: f64,
    /// Samples with at least one frame: the denominator of every share.
    pub samples: u64,
    /// Renders the samples cover (at least 1); `calls` are per render.
    pub renders: u64,
    /// Unit of the per-call columns: `" s/call"`, `"ms/call"`, `"us/call"`, `"ns/call"`.
    pub unit: String,
    pub rows: Vec<FlatRow>,
}

/// One function of the flat profile.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FlatRow {
    pub name: String,
    /// Self share: samples with this function running, in percent of all samples.
    pub percent: f64,
    /// Self seconds of this row and all rows above it.
    pub cumulative_seconds: f64,
    pub self_seconds: f64,
    /// Exact calls per render; `None` when unknown or zero.
    pub calls: Option<u64>,
    /// Self time per call (`self_seconds / renders / calls`) in [`FlatProfile::unit`].
    pub self_per_call: Option<f64>,
    /// Inclusive time per call in [`FlatProfile::unit`].
    pub total_per_call: Option<f64>,
    /// Inclusive − self seconds.
    pub children_seconds: f64,
    pub self_samples: u64,
    pub inclusive_samples: u64,
    /// Seconds of the samples with this function anywhere on the stack.
    pub inclusive_seconds: f64,
    /// Inclusive share in percent of all samples.
    pub inclusive_percent: f64,
    /// 95 % interval of `percent`, in percent.
    pub self_interval: ShareInterval,
    /// 95 % interval of `inclusive_percent`, in percent.
    pub inclusive_interval: ShareInterval,
    /// The self share is below the noise floor (see the module documentation).
    pub noise: bool,
    /// The function is only ever the outermost frame of its stacks and calls others:
    /// a thread's root (the phase view's `sample row`, a worker's entry), which holds
    /// that thread's whole work. A lone frame (`[outside the tracer's phases]`) is not.
    #[serde(default)]
    pub root: bool,
}

impl FlatRow {
    /// Whether the function stands for the whole run: a thread's root ([`FlatRow::root`])
    /// or on (nearly) every sample's stack (inclusive share at least
    /// [`WHOLE_RUN_PERCENT`]). Making it free would make the run free: no headline.
    pub fn whole_run(&self) -> bool {
        self.root || self.inclusive_percent >= WHOLE_RUN_PERCENT
    }
}

/// The finest unit in which `largest` seconds per call fit the per-call column.
fn per_call_unit(largest: Option<f64>) -> (&'static str, f64) {
    let Some(largest) = largest else {
        return PER_CALL_UNITS[0];
    };
    PER_CALL_UNITS
        .iter()
        .rev()
        .find(|(_, scale)| largest * scale < PER_CALL_COLUMN_LIMIT)
        .copied()
        .unwrap_or(PER_CALL_UNITS[0])
}

/// Builds the flat profile from sampled stacks and exact calls per render.
pub fn flat_profile(input: &ProfileInput<'_>) -> FlatProfile {
    let tally = Tally::new(input);
    // Functions seen below the outermost frame of some stack are not roots.
    let nested: std::collections::BTreeSet<&str> = input
        .samples
        .stacks
        .iter()
        .flat_map(|s| s.frames.iter().skip(1).map(String::as_str))
        .collect();
    let renders = input.renders();
    let total = tally.total_samples;
    let seconds = |count: u64| count as f64 * input.samples.seconds_per_sample;
    let per_call_seconds =
        |samples: u64, calls: u64| seconds(samples) / renders as f64 / calls as f64;
    let noise = |f: usize| below_noise_floor(tally.self_samples[f], total);
    let mut order: Vec<usize> = (0..tally.names.len()).collect();
    // Ids are in name order, so the id breaks the last tie by name.
    order.sort_by_key(|&f| {
        (
            Reverse(tally.self_samples[f]),
            Reverse(tally.calls[f].unwrap_or(0)),
            f,
        )
    });

    // Inclusive ≥ self, so the largest per-call time is an inclusive one.
    let largest = order
        .iter()
        .filter(|&&f| !noise(f))
        .filter_map(|&f| tally.calls[f].map(|c| per_call_seconds(tally.inclusive_samples[f], c)))
        .filter(|t| t.is_finite())
        .reduce(f64::max);
    let (prefix, scale) = per_call_unit(largest);
    let interval = |count: u64| wilson_interval(count, total, Z_95).scaled(100.0);

    let mut cumulative_seconds = 0.0;
    let rows = order
        .into_iter()
        .map(|f| {
            let (own, inclusive) = (tally.self_samples[f], tally.inclusive_samples[f]);
            let self_seconds = seconds(own);
            cumulative_seconds += self_seconds;
            let calls = tally.calls[f];
            FlatRow {
                name: tally.names[f].clone(),
                percent: percent_of(own, total),
                cumulative_seconds,
                self_seconds,
                calls,
                self_per_call: calls.map(|n| scale * per_call_seconds(own, n)),
                total_per_call: calls.map(|n| scale * per_call_seconds(inclusive, n)),
                children_seconds: seconds(tally.children_samples(f)),
                self_samples: own,
                inclusive_samples: inclusive,
                inclusive_seconds: seconds(inclusive),
                inclusive_percent: percent_of(inclusive, total),
                self_interval: interval(own),
                inclusive_interval: interval(inclusive),
                noise: noise(f),
                root: !nested.contains(tally.names[f].as_str()) && inclusive > own,
            }
        })
        .collect();
    FlatProfile {
        origin: Origin::Sampled,
        seconds_per_sample: input.samples.seconds_per_sample,
        total_seconds: seconds(total),
        samples: total,
        renders,
        unit: format!("{prefix}/call"),
        rows,
    }
}

/// The bottleneck a headline names: the work that costs most by itself, the function
/// with the most self samples (a leaf such as a primitive test has self = inclusive),
/// leaving out whole-run frames ([`FlatRow::whole_run`]) and noise rows. Ties go to
/// more inclusive samples, then to the name. A parent's inclusive share holds the work
/// it calls (shading holds its shadow queries' tests): [`largest_inclusive`] names it.
pub fn bottleneck(flat: &FlatProfile) -> Option<&FlatRow> {
    flat.rows
        .iter()
        .filter(|r| !r.whole_run() && !r.noise)
        .max_by(|a, b| {
            (a.self_samples, a.inclusive_samples)
                .cmp(&(b.self_samples, b.inclusive_samples))
                .then_with(|| b.name.cmp(&a.name))
        })
}

/// The function with the most inclusive samples, leaving out whole-run frames (the
/// render's outermost frames hold every sample and would always win) and functions
/// whose inclusive share is itself below the noise floor: what making it and everything
/// it calls free would buy. Ties go to more self samples, then to the name.
pub fn largest_inclusive(flat: &FlatProfile) -> Option<&FlatRow> {
    flat.rows
        .iter()
        .filter(|r| !r.whole_run() && !below_noise_floor(r.inclusive_samples, flat.samples))
        .max_by(|a, b| {
            (a.inclusive_samples, a.self_samples)
                .cmp(&(b.inclusive_samples, b.self_samples))
                .then_with(|| b.name.cmp(&a.name))
        })
}

impl FlatProfile {
    /// Sampled seconds per render: the render's CPU time as the samples measure it.
    pub fn seconds_per_render(&self) -> f64 {
        self.total_seconds / self.renders.max(1) as f64
    }

    /// The rows below the noise floor (left out of the text's table).
    pub fn noise_rows(&self) -> impl Iterator<Item = &FlatRow> {
        self.rows.iter().filter(|r| r.noise)
    }

    /// The flat profile in gprof's layout (see the module documentation), without
    /// gprof's explanations, followed by the noise rows and the shares table.
    pub fn to_text(&self) -> String {
        let mut out = String::from("Flat profile:\n\n");
        let _ = writeln!(
            out,
            "Each sample counts as {} seconds.",
            format_g(self.seconds_per_sample)
        );
        let renders = self.renders.max(1);
        if self.origin == Origin::Gprof {
            out.push_str("Read from gprof's output; calls counted by -pg.\n");
        } else if self.origin == Origin::Recorded {
            out.push_str(RECORDED_LINE);
        } else if renders == 1 {
            out.push_str("1 render sampled; calls are per render, seconds for that render.\n");
        } else {
            let _ = writeln!(
                out,
                "{renders} renders sampled; calls are per render, seconds for all {renders} renders."
            );
        }
        if self.total_seconds <= 0.0 {
            out.push_str(" no time accumulated\n\n");
        }
        let _ = writeln!(
            out,
            "{} {} {} {} {} {}  {}",
            c_field("%  ", 5, false),
            c_field("cumulative", 10, false),
            c_field("self  ", 8, false),
            c_field("", 8, false),
            c_field("self  ", 8, false),
            c_field("total ", 8, false),
            c_field("", 8, true),
        );
        let _ = writeln!(
            out,
            "{} {}  {} {} {} {}  {}",
            c_field("time", 5, false),
            c_field("seconds", 9, false),
            c_field("seconds", 8, false),
            c_field("calls", 8, false),
            c_field(&self.unit, 8, false),
            c_field(&self.unit, 8, false),
            c_field("name", 8, true),
        );
        for row in self.rows.iter().filter(|r| !r.noise) {
            let _ = write!(
                out,
                "{:6.2} {:9.2} {:8.2}",
                row.percent, row.cumulative_seconds, row.self_seconds
            );
            let _ = match (row.calls, row.self_per_call, row.total_per_call) {
                (Some(calls), Some(own), Some(total)) if calls != 0 => {
                    write!(out, " {calls:8} {own:8.2} {total:8.2}  ")
                }
                _ => write!(out, " {:8} {:8} {:8}  ", "", "", ""),
            };
            out.push_str(&row.name);
            out.push('\n');
        }
        self.push_noise(&mut out);
        self.push_shares(&mut out);
        out
    }

    /// The noise rows, with their calls per render, under a heading.
    fn push_noise(&self, out: &mut String) {
        if self.noise_rows().next().is_none() {
            return;
        }
        out.push_str(
            "\nBelow the noise floor (the 95 % interval of the self time reaches under half\n\
             a sample, so it cannot be told from none); not listed above as 0.00:\n",
        );
        let _ = writeln!(out, "{:>10}  name", "calls");
        for row in self.noise_rows() {
            let calls = row.calls.map(|c| c.to_string()).unwrap_or_default();
            let _ = writeln!(out, "{calls:>10}  {}", row.name);
        }
    }

    /// Every row's self and inclusive shares with their intervals, by inclusive share.
    fn push_shares(&self, out: &mut String) {
        if self.rows.is_empty() {
            return;
        }
        let _ = writeln!(
            out,
            "\nShares of all {} samples with 95 % intervals (Wilson score): inclusive = the\n\
             function anywhere on the stack (once per sample), self = the function running.",
            self.samples
        );
        let _ = writeln!(
            out,
            "{:>11}  {:^16}  {:>8}  {:^16}  name",
            "inclusive %", "95 % interval", "self %", "95 % interval"
        );
        let mut rows: Vec<&FlatRow> = self.rows.iter().collect();
        rows.sort_by_key(|r| Reverse(r.inclusive_samples));
        for row in rows {
            let own = if row.noise {
                "noise".to_owned()
            } else {
                format!("{:.2}", row.percent)
            };
            let (i, s) = (row.inclusive_interval, row.self_interval);
            let _ = writeln!(
                out,
                "{:>11.2}  ({:>6.2}, {:>6.2})  {own:>8}  ({:>6.2}, {:>6.2})  {}",
                row.inclusive_percent, i.low, i.high, s.low, s.high, row.name
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::gprof::tests::{close, counts, samples, three_functions};
    use crate::profile::gprof_text::*;
    use crate::profile::{CallCounts, StackSamples};

    fn flat(samples: &StackSamples, calls: &CallCounts, renders: u64) -> FlatProfile {
        flat_profile(&ProfileInput {
            samples,
            calls,
            renders,
        })
    }

    fn row<'a>(profile: &'a FlatProfile, name: &str) -> &'a FlatRow {
        profile.rows.iter().find(|r| r.name == name).unwrap()
    }

    fn interval_close(actual: ShareInterval, low: f64, high: f64) -> bool {
        (actual.low - low).abs() < 1e-6 && (actual.high - high).abs() < 1e-6
    }

    /// three_functions (main->a 30, main->a->b 50, main->c 20 samples of 10 ms) over
    /// 4 renders with calls per render a 10, b 1000, idle 5.
    fn four_renders() -> FlatProfile {
        flat(
            &three_functions(),
            &counts(&[("a", 10), ("b", 1000), ("idle", 5)]),
            4,
        )
    }

    #[test]
    fn per_render_calls_divide_the_time_of_all_renders() {
        let profile = four_renders();
        assert_eq!((profile.samples, profile.renders), (100, 4));
        assert!(close(profile.total_seconds, 1.0) && close(profile.seconds_per_render(), 0.25));
        // Self order: b 50, a 30, c 20, then idle (5 calls) before main (none) at 0.
        let names: Vec<&str> = profile.rows.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["b", "a", "c", "idle", "main"]);
        // Largest per-call time: a, 0.80 s / 4 renders / 10 calls = 20 ms = 20000 us,
        // which fits 8 columns; in ns (2e7) it would not: us/call.
        assert_eq!(profile.unit, "us/call");
        let a = row(&profile, "a");
        assert_eq!(a.calls, Some(10));
        // a self: 0.30 s / 4 / 10 = 7.5 ms = 7500 us.
        assert!(
            close(a.self_per_call.unwrap(), 7500.0) && close(a.total_per_call.unwrap(), 20000.0)
        );
        // b: 0.50 s / 4 / 1000 = 125 us, self and total (a leaf).
        let b = row(&profile, "b");
        assert!(close(b.self_per_call.unwrap(), 125.0) && close(b.total_per_call.unwrap(), 125.0));
        assert!(close(a.cumulative_seconds, 0.80) && close(a.children_seconds, 0.50));
    }

    #[test]
    fn rows_carry_self_and_inclusive_shares_with_wilson_intervals() {
        let profile = four_renders();
        let a = row(&profile, "a");
        assert_eq!((a.self_samples, a.inclusive_samples), (30, 80));
        assert!(close(a.percent, 30.0) && close(a.inclusive_percent, 80.0));
        assert!(close(a.inclusive_seconds, 0.80));
        // Wilson 95 % by hand: 30/100 -> 21.8949..39.5849 %, 80/100 -> 71.1171..86.6633 %.
        assert!(interval_close(a.self_interval, 21.894885, 39.584855));
        assert!(interval_close(a.inclusive_interval, 71.117083, 86.663307));
        // main: on every stack, never running: inclusive 100 %, 100/100 -> low
        // 100/(100 + z^2) = 100/103.841459 = 96.300650 %, high 100; self 0/100 ->
        // 0..z^2/(100 + z^2) = 3.699350 %.
        let main = row(&profile, "main");
        assert!(close(main.inclusive_percent, 100.0) && close(main.percent, 0.0));
        assert!(interval_close(main.inclusive_interval, 96.300650, 100.0));
        assert!(interval_close(main.self_interval, 0.0, 3.699350));
        // Noise: main and idle (no self samples); c with 20 is not.
        let noise: Vec<&str> = profile.noise_rows().map(|r| r.name.as_str()).collect();
        assert_eq!(noise, ["idle", "main"]);
        assert!(!row(&profile, "c").noise);
    }

    #[test]
    fn one_sample_is_noise_and_two_are_not() {
        // 1000 samples: 1 sample's Wilson low is 0.18 samples, 2 samples' 0.55.
        let stacks = samples(
            &[
                (&["main", "hot"], 997),
                (&["main", "one"], 1),
                (&["main", "two"], 2),
            ],
            0.001,
        );
        let profile = flat(&stacks, &counts(&[("one", 7)]), 1);
        assert!(row(&profile, "one").noise && !row(&profile, "two").noise);
        let text = profile.to_text();
        let table = parse_flat_text(&text).unwrap();
        // No table row prints 0.00: "one" (0.10 %) is not in the table, "two" (0.20 %) is.
        let names: Vec<&str> = table.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["hot", "two"]);
        assert!(table.iter().all(|r| r.percent > 0.0));
        let noise = parse_flat_noise(&text).unwrap();
        assert_eq!(
            noise,
            [
                ParsedNoiseRow {
                    name: "one".into(),
                    calls: Some(7)
                },
                ParsedNoiseRow {
                    name: "main".into(),
                    calls: None
                }
            ]
        );
    }

    #[test]
    fn per_call_unit_is_the_finest_that_fits_the_column() {
        assert_eq!(per_call_unit(Some(1e-4)).0, "us"); // 100000 ns would take 9 columns
        assert_eq!(per_call_unit(Some(9.99e-5)).0, "ns"); // 99900.00 ns fits
        assert_eq!(per_call_unit(Some(150.0)).0, " s");
        assert_eq!(per_call_unit(Some(2e5)).0, " s"); // too slow for any: seconds
        assert_eq!(per_call_unit(None).0, " s");
        // A 40 ns sphere test beside a 10 us ray over 10 renders: sphere 0.4 s / 10 /
        // 1e6 calls = 40 ns; trace 1.0 s / 10 / 1e4 = 10 us = 10000 ns fits: ns/call.
        let stacks = samples(
            &[
                (&["render", "trace", "sphere"], 400),
                (&["render", "trace"], 600),
            ],
            0.001,
        );
        let profile = flat(
            &stacks,
            &counts(&[("sphere", 1_000_000), ("trace", 10_000)]),
            10,
        );
        assert_eq!(profile.unit, "ns/call");
        let sphere = row(&profile, "sphere");
        assert!(close(sphere.self_per_call.unwrap(), 40.0));
        let trace = row(&profile, "trace");
        assert!(
            close(trace.self_per_call.unwrap(), 6000.0)
                && close(trace.total_per_call.unwrap(), 10000.0)
        );
        let parsed = parse_flat_text(&profile.to_text()).unwrap();
        let sphere_line = parsed.iter().find(|r| r.name == "sphere").unwrap();
        assert_eq!(sphere_line.self_per_call, Some(40.0)); // not 0.00
        // Noise rows do not choose the unit: a 1-sample function with one call per
        // render (1 ms per call) leaves ns.
        let mut with_noise = stacks.clone();
        with_noise.stacks.push(crate::profile::Stack {
            frames: vec!["render".into(), "setup".into()],
            count: 1,
        });
        let calls = counts(&[("sphere", 1_000_000), ("trace", 10_000), ("setup", 1)]);
        assert_eq!(flat(&with_noise, &calls, 10).unit, "ns/call");
    }

    #[test]
    fn largest_inclusive_is_the_largest_inclusive_row_short_of_the_whole_run() {
        // main holds 100 %: left out; a holds 80 % inclusive (self only 30 %): a, not b.
        assert_eq!(largest_inclusive(&four_renders()).unwrap().name, "a");
        // root and x hold 99.6 % (>= 99.5): both whole-run; other (4 samples) wins.
        let stacks = samples(&[(&["root", "x"], 996), (&["other"], 4)], 0.001);
        let profile = flat(&stacks, &CallCounts::new(), 1);
        assert!(row(&profile, "root").whole_run() && row(&profile, "x").whole_run());
        assert_eq!(largest_inclusive(&profile).unwrap().name, "other");
        // At 99.4 % they count; root and x tie on inclusive, x runs: x.
        let stacks = samples(&[(&["root", "x"], 994), (&["other"], 6)], 0.001);
        assert_eq!(
            largest_inclusive(&flat(&stacks, &CallCounts::new(), 1))
                .unwrap()
                .name,
            "x"
        );
        // A thread's root (outermost, with callees) is the whole run of its thread,
        // whatever its share: left out; a lone outermost frame is not a root.
        let stacks = samples(&[(&["worker", "y"], 900), (&["idle"], 100)], 0.001);
        let profile = flat(&stacks, &CallCounts::new(), 1);
        assert!(row(&profile, "worker").root && !row(&profile, "idle").root);
        assert_eq!(largest_inclusive(&profile).unwrap().name, "y");
        // Only whole-run frames and noise: none.
        let stacks = samples(&[(&["root", "x"], 999), (&["other"], 1)], 0.001);
        assert!(largest_inclusive(&flat(&stacks, &CallCounts::new(), 1)).is_none());
    }

    #[test]
    fn the_bottleneck_is_the_most_self_time_not_the_parent_that_holds_it() {
        // SPD rings' shape: shading holds the shadow queries and the reflection rays'
        // tests (75 % inclusive, 1 % itself); the cylinder test costs 64 % itself.
        let stacks = samples(
            &[
                (&["row", "shading", "shadow", "cylinder test"], 400),
                (&["row", "shading", "cylinder test"], 140),
                (&["row", "cylinder test"], 100),
                (&["row", "shading"], 10),
                (&["row", "shading", "shadow"], 200),
                (&["row", "sphere test"], 150),
            ],
            0.001,
        );
        let profile = flat(&stacks, &CallCounts::new(), 1);
        assert_eq!(largest_inclusive(&profile).unwrap().name, "shading");
        let top = bottleneck(&profile).unwrap();
        assert_eq!(top.name, "cylinder test");
        assert_eq!((top.self_samples, top.inclusive_samples), (640, 640));
        // A noise row never headlines; whole-run frames neither.
        let stacks = samples(&[(&["root", "x"], 999), (&["other"], 1)], 0.001);
        let profile = flat(&stacks, &CallCounts::new(), 1);
        assert!(row(&profile, "other").noise);
        assert!(bottleneck(&profile).is_none());
    }

    #[test]
    fn text_keeps_gprof_layout_with_renders_noise_and_shares() {
        let text = four_renders().to_text();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "Flat profile:");
        assert_eq!(lines[1], "");
        assert_eq!(lines[2], "Each sample counts as 0.01 seconds.");
        assert_eq!(
            lines[3],
            "4 renders sampled; calls are per render, seconds for all 4 renders."
        );
        // "%5.5s %10.10s %8.8s %8.8s %8.8s %8.8s  %-8.8s": "  %  ", "cumulative",
        // "  self  ", 8 blanks, "  self  ", "  total ", 8 blanks.
        assert_eq!(
            lines[4],
            "  %   cumulative   self              self     total           "
        );
        // "%5.5s %9.9s  %8.8s %8.8s %8.8s %8.8s  %-8.8s": " time", "  seconds",
        // " seconds", "   calls", " us/call" twice, "name    ".
        assert_eq!(
            lines[5],
            " time   seconds   seconds    calls  us/call  us/call  name    "
        );
        let expected_rest = [
            " 50.00      0.50     0.50     1000   125.00   125.00  b",
            " 30.00      0.80     0.30       10  7500.00 20000.00  a",
            " 20.00      1.00     0.20                             c",
            "",
            "Below the noise floor (the 95 % interval of the self time reaches under half",
            "a sample, so it cannot be told from none); not listed above as 0.00:",
            "     calls  name",
            "         5  idle",
            "            main",
            "",
            "Shares of all 100 samples with 95 % intervals (Wilson score): inclusive = the",
            "function anywhere on the stack (once per sample), self = the function running.",
            "inclusive %   95 % interval      self %   95 % interval    name",
            "     100.00  ( 96.30, 100.00)     noise  (  0.00,   3.70)  main",
            "      80.00  ( 71.12,  86.66)     30.00  ( 21.89,  39.58)  a",
            "      50.00  ( 40.38,  59.62)     50.00  ( 40.38,  59.62)  b",
            "      20.00  ( 13.34,  28.88)     20.00  ( 13.34,  28.88)  c",
            "       0.00  (  0.00,   3.70)     noise  (  0.00,   3.70)  idle",
        ];
        assert_eq!(&lines[6..], expected_rest);
        let one = flat(&three_functions(), &CallCounts::new(), 1).to_text();
        assert!(
            one.contains("\n1 render sampled; calls are per render, seconds for that render.\n")
        );
    }

    #[test]
    fn a_recorded_run_says_per_run_not_render() {
        let mut profile = flat(&three_functions(), &CallCounts::new(), 1);
        profile.origin = Origin::Recorded;
        let text = profile.to_text();
        assert!(
            text.contains(
                "\n1 run of the program sampled; seconds are per run, no calls counted.\n"
            ),
            "{text}"
        );
        assert!(!text.contains("render"), "{text}");
    }

    #[test]
    fn flat_text_round_trips_through_parsers() {
        let profile = flat(
            &three_functions(),
            &counts(&[("a", 10), ("b", 123_456_789)]),
            3,
        );
        let text = profile.to_text();
        let parsed = parse_flat_text(&text).unwrap();
        let printed: Vec<&FlatRow> = profile.rows.iter().filter(|r| !r.noise).collect();
        assert_eq!(parsed.len(), printed.len());
        let to_printed = |x: f64| (x * 100.0).round() / 100.0;
        for (row, back) in printed.iter().zip(&parsed) {
            assert_eq!(back.name, row.name);
            assert_eq!(back.calls, row.calls); // includes a 9-digit count wider than %8lu
            assert!(close(back.percent, to_printed(row.percent)));
            assert!(close(
                back.cumulative_seconds,
                to_printed(row.cumulative_seconds)
            ));
            assert!(close(back.self_seconds, to_printed(row.self_seconds)));
            assert_eq!(back.self_per_call, row.self_per_call.map(to_printed));
            assert_eq!(back.total_per_call, row.total_per_call.map(to_printed));
        }
        let shares = parse_flat_shares(&text).unwrap();
        assert_eq!(shares.len(), profile.rows.len());
        for back in &shares {
            let row = row(&profile, &back.name);
            assert!(close(
                back.inclusive_percent,
                to_printed(row.inclusive_percent)
            ));
            assert_eq!(back.self_percent.is_none(), row.noise);
            let i = row.inclusive_interval;
            assert_eq!(
                back.inclusive_interval,
                (to_printed(i.low), to_printed(i.high))
            );
            let s = row.self_interval;
            assert_eq!(back.self_interval, (to_printed(s.low), to_printed(s.high)));
        }
        assert_eq!(parse_flat_noise(&text).unwrap().len(), 1); // main
        // JSON keeps every figure (floats to within their last digit).
        let json = serde_json::to_string(&profile).unwrap();
        let back: FlatProfile = serde_json::from_str(&json).unwrap();
        assert_eq!(
            (back.samples, back.renders, &back.unit),
            (100, 3, &profile.unit)
        );
        for (row, back) in profile.rows.iter().zip(&back.rows) {
            assert_eq!(
                (&back.name, back.calls, back.noise),
                (&row.name, row.calls, row.noise)
            );
            assert_eq!(
                (back.self_samples, back.inclusive_samples),
                (row.self_samples, row.inclusive_samples)
            );
            assert!(interval_close(
                back.inclusive_interval,
                row.inclusive_interval.low,
                row.inclusive_interval.high
            ));
            assert!(interval_close(
                back.self_interval,
                row.self_interval.low,
                row.self_interval.high
            ));
        }
    }
}
