//! Phases of ray tracing for a program rtprof did not write: rules that give function
//! names (or their source files) a phase, and the breakdown of a profile by them.
//!
//! A sample's phase is that of the **innermost** frame of its stack that a rule matches
//! (inlined frames are frames of their own), so a test called from the traversal is the
//! test's, and the traversal's own code is the traversal's. A frame takes the first rule,
//! in file order, that matches it. Samples no frame of which matches are
//! [`UNCLASSIFIED`], and the breakdown says which innermost frames they had, so the user
//! can write the rule that is missing. The built-in rules are `phase_rules.toml` beside
//! this file; `rtprof record --phases FILE` reads another file of the same form.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use regex::{Regex, RegexBuilder};
use serde::{Deserialize, Serialize};

use super::StackSamples;
use super::share_interval::{ShareInterval, Z_95, wilson_interval};

/// The built-in rules (their file is the documentation of their form).
pub const BUILTIN_RULES: &str = include_str!("phase_rules.toml");
/// Where the built-in rules come from, as the outputs name them.
pub const BUILTIN_ORIGIN: &str = "rtprof's built-in phase rules";
/// The phase of samples no rule matched.
pub const UNCLASSIFIED: &str = "other (no rule matched)";
/// The phase of the probe's samples taken outside any phase the program marked.
pub const OUTSIDE: &str = "outside any phase";
/// Unclassified samples' innermost frames listed, at most.
const UNCLASSIFIED_LISTED: usize = 12;

/// A rules file that cannot be used: where and why.
#[derive(Debug, thiserror::Error)]
pub enum PhaseRulesError {
    #[error("cannot read {path}: {message}")]
    Read { path: String, message: String },
    #[error("{path}:{line}: {message}")]
    Invalid {
        path: String,
        line: usize,
        message: String,
    },
}

/// The file's form (serde): `[[rule]]` tables.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RulesFile {
    rule: Vec<RuleEntry>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RuleEntry {
    phase: toml::Spanned<String>,
    #[serde(default)]
    symbol: Vec<toml::Spanned<String>>,
    #[serde(default)]
    file: Vec<toml::Spanned<String>>,
}

/// One rule: a phase and the patterns that give a frame to it.
#[derive(Clone, Debug)]
pub struct PhaseRule {
    pub phase: String,
    /// The rule's line in its file.
    pub line: usize,
    symbols: Vec<Regex>,
    files: Vec<Regex>,
}

impl PhaseRule {
    /// The patterns as the file writes them: `symbol ~ a | b; file ~ c`.
    pub fn patterns(&self) -> String {
        let join = |r: &[Regex]| r.iter().map(Regex::as_str).collect::<Vec<_>>().join(" | ");
        let mut parts = Vec::new();
        if !self.symbols.is_empty() {
            parts.push(format!("symbol ~ {}", join(&self.symbols)));
        }
        if !self.files.is_empty() {
            parts.push(format!("file ~ {}", join(&self.files)));
        }
        parts.join("; ")
    }

    fn matches(&self, name: &str, file: Option<&str>) -> bool {
        self.symbols.iter().any(|r| r.is_match(name))
            || file.is_some_and(|f| self.files.iter().any(|r| r.is_match(f)))
    }
}

/// An ordered list of rules and where it was read from.
#[derive(Clone, Debug)]
pub struct PhaseRules {
    /// `rtprof's built-in phase rules`, or the file's path.
    pub origin: String,
    pub rules: Vec<PhaseRule>,
}

/// How many samples fell to one phase.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PhaseShare {
    pub phase: String,
    pub samples: u64,
    /// Share of all samples (0-1) and its 95 % Wilson interval.
    pub share: f64,
    pub interval: ShareInterval,
    /// CPU seconds: samples × seconds per sample.
    pub seconds: f64,
}

/// How many samples one rule classified (its phase's samples are the sum over its rules).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RuleUse {
    /// 1-based, in file order.
    pub rule: usize,
    pub line: usize,
    pub phase: String,
    pub patterns: String,
    pub samples: u64,
    /// The functions it matched as the innermost matching frame, most samples first.
    pub functions: Vec<(String, u64)>,
}

/// Where a breakdown's phases come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PhaseSource {
    /// Rules on the names of the sampled stacks' frames.
    #[default]
    Rules,
    /// The program's own phase marks, sampled inside it by rtprof's probe.
    Probe,
}

/// A profile by phase: the rules' (or the probe's) answer to "where does the time go".
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PhaseBreakdown {
    /// Where the phases come from; older record.json files have only rules.
    #[serde(default)]
    pub source: PhaseSource,
    pub origin: String,
    pub samples: u64,
    /// Most samples first; the unclassified samples last, as [`UNCLASSIFIED`].
    pub phases: Vec<PhaseShare>,
    pub rules: Vec<RuleUse>,
    /// Samples no rule matched (for the probe: outside any phase), and their innermost
    /// frames (most samples first; none for the probe).
    pub unclassified: u64,
    pub unclassified_frames: Vec<(String, u64)>,
}

impl PhaseBreakdown {
    /// Share of the samples a rule classified (0-1).
    pub fn classified_share(&self) -> f64 {
        if self.samples == 0 {
            0.0
        } else {
            1.0 - self.unclassified as f64 / self.samples as f64
        }
    }

    /// The share of one phase (0 when it has no samples).
    pub fn share_of(&self, phase: &str) -> f64 {
        self.phases
            .iter()
            .find(|p| p.phase == phase)
            .map_or(0.0, |p| p.share)
    }

    /// The name of the row of samples in no phase: [`UNCLASSIFIED`] for rules,
    /// [`OUTSIDE`] for the probe.
    pub fn rest(&self) -> &'static str {
        match self.source {
            PhaseSource::Rules => UNCLASSIFIED,
            PhaseSource::Probe => OUTSIDE,
        }
    }

    /// Whether `phase` is the row of samples in no phase (not a phase of the work).
    pub fn is_rest(&self, phase: &str) -> bool {
        phase == self.rest()
    }

    /// A breakdown of samples already counted by phase: the probe's, whose sampler
    /// read each thread's innermost phase. `counted` gives each phase's samples (self:
    /// with it innermost; a name given twice is summed), `outside` the samples in no
    /// phase; `origin` says where they come from.
    pub fn from_counted(
        origin: &str,
        counted: &[(String, u64)],
        outside: u64,
        seconds_per_sample: f64,
    ) -> Self {
        let mut per_phase: BTreeMap<&str, u64> = BTreeMap::new();
        for (name, n) in counted {
            *per_phase.entry(name).or_default() += n;
        }
        let total = per_phase.values().sum::<u64>() + outside;
        PhaseBreakdown {
            source: PhaseSource::Probe,
            origin: origin.to_string(),
            samples: total,
            phases: shares(total, per_phase, (OUTSIDE, outside), seconds_per_sample),
            rules: Vec::new(),
            unclassified: outside,
            unclassified_frames: Vec::new(),
        }
    }
}

/// Each phase's share of `total` samples, most samples first, the row of samples in no
/// phase (`rest`) last; phases without samples are left out.
fn shares(
    total: u64,
    per_phase: BTreeMap<&str, u64>,
    rest: (&str, u64),
    seconds_per_sample: f64,
) -> Vec<PhaseShare> {
    let share = |phase: &str, n: u64| PhaseShare {
        phase: phase.to_string(),
        samples: n,
        share: if total == 0 {
            0.0
        } else {
            n as f64 / total as f64
        },
        interval: wilson_interval(n, total, Z_95),
        seconds: n as f64 * seconds_per_sample,
    };
    let mut phases: Vec<PhaseShare> = per_phase
        .into_iter()
        .filter(|&(_, n)| n > 0)
        .map(|(phase, n)| share(phase, n))
        .collect();
    phases.sort_by(|a, b| b.samples.cmp(&a.samples).then(a.phase.cmp(&b.phase)));
    if rest.1 > 0 {
        phases.push(share(rest.0, rest.1));
    }
    phases
}

/// The 1-based line of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    1 + text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

impl PhaseRules {
    /// rtprof's built-in rules.
    pub fn builtin() -> Result<Self, PhaseRulesError> {
        Self::parse(BUILTIN_RULES, BUILTIN_ORIGIN)
    }

    /// Reads a rules file.
    pub fn load(path: &Path) -> Result<Self, PhaseRulesError> {
        let origin = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| PhaseRulesError::Read {
            path: origin.clone(),
            message: e.to_string(),
        })?;
        Self::parse(&text, &origin)
    }

    /// Parses rules from `text` (`origin` names it in errors): each pattern a regular
    /// expression, searched case-insensitively.
    pub fn parse(text: &str, origin: &str) -> Result<Self, PhaseRulesError> {
        let invalid = |offset: usize, message: String| PhaseRulesError::Invalid {
            path: origin.to_string(),
            line: line_of(text, offset),
            message,
        };
        let file: RulesFile = toml::from_str(text).map_err(|e| {
            let offset = e.span().map_or(0, |s| s.start);
            invalid(offset, e.message().to_string())
        })?;
        let compile = |p: &toml::Spanned<String>| {
            RegexBuilder::new(p.get_ref())
                .case_insensitive(true)
                .build()
                .map_err(|e| invalid(p.span().start, format!("bad pattern: {e}")))
        };
        let mut rules = Vec::new();
        for entry in &file.rule {
            let line = line_of(text, entry.phase.span().start);
            let phase = entry.phase.get_ref().trim().to_string();
            if phase.is_empty() {
                return Err(invalid(entry.phase.span().start, "empty phase name".into()));
            }
            if entry.symbol.is_empty() && entry.file.is_empty() {
                return Err(invalid(
                    entry.phase.span().start,
                    format!("rule for \"{phase}\" has no `symbol` or `file` pattern"),
                ));
            }
            rules.push(PhaseRule {
                phase,
                line,
                symbols: entry.symbol.iter().map(compile).collect::<Result<_, _>>()?,
                files: entry.file.iter().map(compile).collect::<Result<_, _>>()?,
            });
        }
        if rules.is_empty() {
            return Err(invalid(0, "no [[rule]] in the file".into()));
        }
        Ok(PhaseRules {
            origin: origin.to_string(),
            rules,
        })
    }

    /// The first rule that matches a function (and its source file, when known).
    pub fn rule_of(&self, name: &str, file: Option<&str>) -> Option<usize> {
        self.rules.iter().position(|r| r.matches(name, file))
    }

    /// The samples by phase; `sources` gives functions' source files for `file` rules.
    pub fn classify(
        &self,
        samples: &StackSamples,
        sources: &BTreeMap<String, String>,
    ) -> PhaseBreakdown {
        let mut rule_of: HashMap<&str, Option<usize>> = HashMap::new();
        let mut by_rule: Vec<BTreeMap<&str, u64>> = vec![BTreeMap::new(); self.rules.len()];
        let mut unclassified: BTreeMap<&str, u64> = BTreeMap::new();
        for stack in &samples.stacks {
            let hit = stack.frames.iter().rev().find_map(|frame| {
                let rule = *rule_of.entry(frame).or_insert_with(|| {
                    self.rule_of(frame, sources.get(frame.as_str()).map(String::as_str))
                });
                rule.map(|r| (r, frame.as_str()))
            });
            match hit {
                Some((rule, frame)) => *by_rule[rule].entry(frame).or_default() += stack.count,
                None => {
                    let leaf = stack.frames.last().map_or("[no frame]", String::as_str);
                    *unclassified.entry(leaf).or_default() += stack.count;
                }
            }
        }
        let total = samples.total();
        let mut per_phase: BTreeMap<&str, u64> = BTreeMap::new();
        let rules: Vec<RuleUse> = self
            .rules
            .iter()
            .zip(&by_rule)
            .enumerate()
            .map(|(i, (rule, functions))| {
                let samples = functions.values().sum();
                *per_phase.entry(&rule.phase).or_default() += samples;
                RuleUse {
                    rule: i + 1,
                    line: rule.line,
                    phase: rule.phase.clone(),
                    patterns: rule.patterns(),
                    samples,
                    functions: most_first(functions, usize::MAX),
                }
            })
            .collect();
        let unclassified_samples: u64 = unclassified.values().sum();
        PhaseBreakdown {
            source: PhaseSource::Rules,
            origin: self.origin.clone(),
            samples: total,
            phases: shares(
                total,
                per_phase,
                (UNCLASSIFIED, unclassified_samples),
                samples.seconds_per_sample,
            ),
            rules,
            unclassified: unclassified_samples,
            unclassified_frames: most_first(&unclassified, UNCLASSIFIED_LISTED),
        }
    }
}

/// Counts by name, most first (ties by name), at most `limit`.
fn most_first(counts: &BTreeMap<&str, u64>, limit: usize) -> Vec<(String, u64)> {
    let mut v: Vec<(String, u64)> = counts.iter().map(|(k, &n)| (k.to_string(), n)).collect();
    v.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    v.truncate(limit);
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::profile::Stack;

    fn samples(stacks: &[(&str, u64)]) -> StackSamples {
        StackSamples {
            stacks: stacks
                .iter()
                .map(|(s, n)| Stack {
                    frames: s.split(';').map(str::to_string).collect(),
                    count: *n,
                })
                .collect(),
            seconds_per_sample: 0.001,
        }
    }

    #[test]
    fn the_innermost_matching_frame_gives_the_phase() {
        let rules = PhaseRules::builtin().unwrap();
        // RTIOW's names: the sphere test under the BVH walk, a helper of the test
        // (`hit_record::set_face_normal`, matched by no rule) under the test, the box
        // test of the walk, shading's random numbers, libc's write under main.
        let s = samples(&[
            (
                "main;camera::render;camera::ray_color;bvh_node::hit;sphere::hit",
                30,
            ),
            (
                "main;camera::ray_color;bvh_node::hit;sphere::hit;hit_record::set_face_normal",
                10,
            ),
            ("main;camera::ray_color;bvh_node::hit;aabb::hit", 40),
            (
                "main;camera::ray_color;lambertian::scatter;random_double",
                15,
            ),
            ("main;__GI__IO_fwrite", 5),
        ]);
        let b = rules.classify(&s, &BTreeMap::new());
        assert_eq!(b.samples, 100);
        // By hand: sphere 30 + 10, traversal 40, shading 15, 5 unclassified.
        assert_eq!(b.share_of("sphere test"), 0.40);
        assert_eq!(b.share_of("traversal"), 0.40);
        assert_eq!(b.share_of("shading"), 0.15);
        assert_eq!(b.unclassified, 5);
        assert_eq!(b.share_of(UNCLASSIFIED), 0.05);
        assert_eq!(b.phases.last().unwrap().phase, UNCLASSIFIED);
        assert_eq!(
            b.unclassified_frames,
            vec![("__GI__IO_fwrite".to_string(), 5)]
        );
        assert!((b.classified_share() - 0.95).abs() < 1e-12);
        // Seconds are samples × seconds per sample.
        let sphere = b.phases.iter().find(|p| p.phase == "sphere test").unwrap();
        assert!((sphere.seconds - 0.040).abs() < 1e-12);
        assert!(sphere.interval.contains(0.40) && sphere.interval.low > 0.30);
        // Each rule's samples add up to its phase's.
        let traversal: u64 = b
            .rules
            .iter()
            .filter(|r| r.phase == "traversal")
            .map(|r| r.samples)
            .sum();
        assert_eq!(traversal, 40);
    }

    #[test]
    fn the_builtin_rules_name_common_tracers_functions() {
        let rules = PhaseRules::builtin().unwrap();
        let phase = |name: &str| {
            rules
                .rule_of(name, None)
                .map(|r| rules.rules[r].phase.as_str())
        };
        for (name, want) in [
            // rtprof's own tracer (the cross-check against its phase probe)
            (
                "tracer::primitives::sphere::Sphere::intersect",
                Some("sphere test"),
            ),
            (
                "tracer::primitives::cylinder::Cylinder::intersect",
                Some("cylinder test"),
            ),
            ("tracer::accel::bvh::Bvh::traverse", Some("traversal")),
            (
                "tracer::accel::brute_force::BruteForce::closest",
                Some("traversal"),
            ),
            ("tracer::shading::Shader::shade", Some("shading")),
            ("tracer::camera::Camera::ray", Some("camera ray")),
            ("tracer::nff::Parser::parse", Some("scene set-up")),
            ("tracer::image_io::write_image", Some("image output")),
            // helpers inside a test: no rule, so the test's frame gives the phase
            ("tracer::primitives::sphere_may_hit", None),
            ("hit_record::set_face_normal", None),
            // RTIOW
            ("sphere::hit", Some("sphere test")),
            ("bvh_node::hit", Some("traversal")),
            ("aabb::hit", Some("traversal")),
            ("hittable_list::hit", Some("traversal")),
            ("camera::ray_color", Some("shading")),
            ("camera::get_ray", Some("camera ray")),
            ("quad::hit", Some("other primitive tests")),
            ("write_color", Some("image output")),
            ("bvh_node::bvh_node", Some("scene set-up")),
            // pbrt-like and Embree names
            ("pbrt::Triangle::Intersect", Some("triangle test")),
            ("rtcIntersect1", Some("traversal")),
            ("random_double", None),
            ("main", None),
        ] {
            assert_eq!(phase(name), want, "{name}");
        }
    }

    #[test]
    fn counted_samples_make_a_breakdown_with_the_outside_row_last() {
        let counted = [
            ("closest hit".to_string(), 60),
            ("camera ray".to_string(), 10),
            ("shading".to_string(), 0),
            ("bvh build".to_string(), 5),
            ("camera ray".to_string(), 5),
        ];
        let b = PhaseBreakdown::from_counted("the probe", &counted, 20, 0.004);
        // By hand: 60 + 15 + 5 + 20 outside = 100 samples.
        assert_eq!(b.samples, 100);
        assert_eq!(b.source, PhaseSource::Probe);
        let names: Vec<&str> = b.phases.iter().map(|p| p.phase.as_str()).collect();
        assert_eq!(names, ["closest hit", "camera ray", "bvh build", OUTSIDE]);
        assert_eq!(b.share_of("camera ray"), 0.15);
        assert!((b.phases[0].seconds - 0.24).abs() < 1e-12);
        assert_eq!(b.unclassified, 20);
        assert!((b.classified_share() - 0.8).abs() < 1e-12);
        assert!(b.is_rest(OUTSIDE) && !b.is_rest(UNCLASSIFIED));
        assert!(b.rules.is_empty());
        // Nothing sampled: no rows, no division by zero.
        let empty = PhaseBreakdown::from_counted("the probe", &[], 0, 0.0);
        assert!(empty.phases.is_empty() && empty.classified_share() == 0.0);
    }

    #[test]
    fn file_rules_use_the_source_file_and_order_decides() {
        let rules = PhaseRules::parse(
            "[[rule]]\nphase = \"mine\"\nfile = ['kernels/.*\\.cu$']\n\
             [[rule]]\nphase = \"later\"\nsymbol = ['^k']\n",
            "rules.toml",
        )
        .unwrap();
        let sources = BTreeMap::from([("kern".to_string(), "src/kernels/a.cu".to_string())]);
        let b = rules.classify(&samples(&[("main;kern", 3), ("main;k2", 1)]), &sources);
        assert_eq!(b.share_of("mine"), 0.75);
        assert_eq!(b.share_of("later"), 0.25);
        assert_eq!(b.rules[0].line, 2);
        assert_eq!(b.rules[1].line, 5);
    }

    #[test]
    fn bad_rules_files_say_where() {
        for (text, line, says) in [
            (
                "[[rule]]\nphase = \"x\"\nsymbol = ['(']\n",
                3,
                "bad pattern",
            ),
            ("[[rule]]\nphase = \"x\"\n", 2, "no `symbol` or `file`"),
            (
                "[[rule]]\nphase = \"x\"\nsymbols = ['a']\n",
                3,
                "unknown field",
            ),
            ("[[rule]]\nphase = \"\"\nsymbol = ['a']\n", 2, "empty phase"),
            ("rule = 3\n", 1, "invalid type"),
            ("", 1, "missing field"),
        ] {
            let e = PhaseRules::parse(text, "my.toml").unwrap_err().to_string();
            assert!(e.starts_with(&format!("my.toml:{line}: ")), "{e}");
            assert!(e.contains(says), "{e}");
        }
        let e = PhaseRules::load(Path::new("/nonexistent/rules.toml")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("cannot read /nonexistent/rules.toml")
        );
    }
}
