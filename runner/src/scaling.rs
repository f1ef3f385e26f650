//! The growth study (`rtprof scaling`): each accelerator on SPD scenes generated at
//! growing size factors, from tens to a million primitives and more. For every point:
//! one counted render (rays, tests, nodes visited) and timed renders (tracing time per
//! ray, preprocessing = the structure's build), with the scene's and the structure's
//! bytes. A brute-force or SIMD render predicted longer than the budget is not run: its
//! point is extrapolated with the power law fitted on the measured ones, and marked.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use analysis::power_law::PowerLaw;
use results::scaling::{SCALING_SCHEMA, ScalingFit, ScalingPoint, ScalingStudy};
use tracer::{
    Count, Counts, NoCount, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, parse_nff,
    render_variant_until,
};

use crate::error::RunError;
use crate::machine::{build_info, command_line, machine, now_rfc3339};
use crate::progress::Progress;
use crate::staging::save;
use crate::timing::{self, TimingPolicy};

/// One family: an SPD program and the size factors to run.
#[derive(Clone, Debug, PartialEq)]
pub struct Family {
    pub program: &'static str,
    pub size_factors: Vec<u32>,
}

/// What to measure.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalingPlan {
    pub families: Vec<Family>,
    /// Variants, one per accelerator: `baseline`, `simd`, `bvh`.
    pub accelerators: Vec<String>,
    pub size: (u32, u32),
    /// Timed renders per point, at least.
    pub repeats: u32,
    /// More timed renders (up to [`crate::timing::MAX_REPEATS`]) until this many seconds
    /// of tracing are measured: a small scene's render of a few milliseconds is at the
    /// mercy of one interruption, and its point sets every ratio of the study.
    pub min_seconds: f64,
    /// Longest predicted render (seconds) that is run; longer ones are extrapolated.
    pub budget_seconds: f64,
}

impl ScalingPlan {
    /// The default study: SPD balls at size factors 1-6 (11 to 597,872 primitives), SPD
    /// shells (spheres only) at 1-13 in odd steps (362 to 1,474,562) and SPD tetra at
    /// 2-10 in even steps (16 to 1,048,576 triangles); `quick` keeps the small sizes.
    pub fn default_plan(quick: bool) -> Self {
        let family = |program, size_factors: &[u32]| Family {
            program,
            size_factors: size_factors.to_vec(),
        };
        let families = if quick {
            vec![family("balls", &[1, 2, 3]), family("tetra", &[2, 4, 6])]
        } else {
            vec![
                family("balls", &[1, 2, 3, 4, 5, 6]),
                family("shells", &[1, 3, 5, 7, 9, 11, 13]),
                family("tetra", &[2, 4, 6, 8, 10]),
            ]
        };
        ScalingPlan {
            families,
            accelerators: ["baseline", "simd", "bvh"].map(String::from).to_vec(),
            // 128x128: at 64x64 a render of a million primitives is short enough that
            // warming the caches with its freshly built tree is a fifth of its time.
            size: if quick { (16, 16) } else { (128, 128) },
            repeats: if quick { 1 } else { 3 },
            min_seconds: if quick { 0.0 } else { 0.25 },
            budget_seconds: if quick { 0.2 } else { 2.0 },
        }
    }

    /// Checks the plan before any work: known programs, size factors in range, variants.
    pub fn check(&self) -> Result<(), RunError> {
        for f in &self.families {
            for &n in &f.size_factors {
                spd::primitive_count(f.program, Some(n)).map_err(|e| RunError::Scene {
                    scene: format!("spd:{}:{n}", f.program),
                    message: e.to_string(),
                })?;
            }
        }
        for a in &self.accelerators {
            VariantSet::parse(a)?;
        }
        if self.repeats == 0 {
            return Err(RunError::Input(
                "scaling: repeats must be at least 1".into(),
            ));
        }
        if !(self.budget_seconds.is_finite() && self.budget_seconds > 0.0) {
            return Err(RunError::Input(format!(
                "--budget {}: give a positive number of seconds",
                self.budget_seconds
            )));
        }
        Ok(())
    }

    /// Checks the plan, then runs it on `threads` workers [default: one per core] and
    /// writes the study into `dir` (created first, so that a bad directory fails before
    /// the work).
    pub fn run_into(
        &self,
        dir: &Path,
        threads: Option<u16>,
        progress: &dyn Progress,
        stop: &AtomicBool,
    ) -> Result<(ScalingStudy, StudyFiles), RunError> {
        self.check()?;
        std::fs::create_dir_all(dir).map_err(|e| RunError::io("create directory", dir, &e))?;
        let pool = crate::pool::thread_pool(threads)?;
        let study = pool.install(|| run_scaling(self, progress, stop))?;
        let files = write_study(&study, dir)?;
        Ok((study, files))
    }

    /// Points to run (for a progress bar): families × size factors × accelerators.
    pub fn steps(&self) -> u64 {
        let sizes: usize = self.families.iter().map(|f| f.size_factors.len()).sum();
        (sizes * self.accelerators.len()) as u64
    }
}

/// Runs the study on the current thread pool.
pub fn run_scaling(
    plan: &ScalingPlan,
    progress: &dyn Progress,
    stop: &AtomicBool,
) -> Result<ScalingStudy, RunError> {
    plan.check()?;
    let created = now_rfc3339();
    let options = RenderOptions::new(
        plan.size.0,
        plan.size.1,
        Sampling::PixelCenters,
        ShadingMode::Color,
    );
    let mut points = Vec::new();
    progress.begin("scaling", plan.steps());
    for family in &plan.families {
        // The last measured render of each accelerator: (primitives, seconds).
        let mut last: Vec<Option<(u64, f64)>> = vec![None; plan.accelerators.len()];
        for &n in &family.size_factors {
            let name = format!("spd:{}:{n}", family.program);
            progress.message(&format!("{name}: generating"));
            let scene = load(family.program, n)?;
            let primitives = scene.primitive_count() as u64;
            for (a, accel) in plan.accelerators.iter().enumerate() {
                if stop.load(Ordering::SeqCst) {
                    progress.end();
                    return Err(RunError::Stopped);
                }
                let set = VariantSet::parse(accel)?;
                // Brute force and SIMD grow linearly in the primitives: predict from
                // the last measured render, and skip what would exceed the budget.
                let predicted = last[a].map(|(p, s)| s * primitives as f64 / p as f64);
                let skip = set.config().accel.tests_everything()
                    && predicted.is_some_and(|s| s > plan.budget_seconds);
                if skip {
                    points.push(extrapolation_slot(
                        family.program,
                        n,
                        primitives,
                        accel,
                        &scene,
                    ));
                } else {
                    progress.message(&format!("{name}: {accel} ({primitives} primitives)"));
                    let m = measure(&scene, &options, &set, plan, stop, &name)?;
                    last[a] = Some((primitives, m.render_seconds));
                    points.push(ScalingPoint {
                        family: family.program.to_string(),
                        size_factor: n,
                        primitives,
                        accelerator: accel.clone(),
                        ..m.point
                    });
                }
                progress.advance(1);
            }
        }
    }
    progress.end();
    let fits = fit_and_extrapolate(&mut points);
    Ok(ScalingStudy {
        schema: SCALING_SCHEMA.to_string(),
        created,
        command: command_line(),
        machine: machine(),
        build: build_info(),
        threads: rayon::current_num_threads() as u32,
        width: plan.size.0,
        height: plan.size.1,
        repeats: plan.repeats,
        min_seconds: plan.min_seconds,
        budget_seconds: plan.budget_seconds,
        points,
        fits,
    })
}

fn load(program: &str, size_factor: u32) -> Result<Scene, RunError> {
    let name = format!("spd:{program}:{size_factor}");
    let text = spd::generate(program, Some(size_factor)).map_err(|e| RunError::Scene {
        scene: name.clone(),
        message: e.to_string(),
    })?;
    parse_nff(&text, &name).map_err(|e| RunError::Input(e.to_string()))
}

/// A point not run: filled in by [`fit_and_extrapolate`].
fn extrapolation_slot(
    program: &str,
    size_factor: u32,
    primitives: u64,
    accel: &str,
    scene: &Scene,
) -> ScalingPoint {
    ScalingPoint {
        family: program.to_string(),
        size_factor,
        primitives,
        accelerator: accel.to_string(),
        measured: false,
        rays: None,
        seconds_per_ray: f64::NAN,
        tests_per_ray: None,
        nodes_per_ray: None,
        build_seconds: None,
        accelerator_bytes: None,
        scene_bytes: scene.memory_bytes() as u64,
    }
}

struct Measured {
    point: ScalingPoint,
    /// Median tracing seconds of one render (for predicting the next size).
    render_seconds: f64,
}

fn measure(
    scene: &Scene,
    options: &RenderOptions,
    set: &VariantSet,
    plan: &ScalingPlan,
    stop: &AtomicBool,
    name: &str,
) -> Result<Measured, RunError> {
    let fail = |e: tracer::RenderError| RunError::render(name, &e);
    let counted =
        render_variant_until::<Count>(scene, options, set, &|_| {}, stop).map_err(fail)?;
    let counts: Counts = counted.rendered.counts().unwrap_or_default();
    let policy = TimingPolicy::new(plan.repeats, plan.min_seconds);
    let timed = timing::measure(&policy, stop, || {
        render_variant_until::<NoCount>(scene, options, set, &|_| {}, stop).map_err(fail)
    })?;
    let render_seconds = timed.time.median;
    let accelerator_bytes = timed.last.accelerator_bytes;
    let rays = counts.rays.total();
    let per_ray = |x: u64| x as f64 / rays.max(1) as f64;
    let t = counts.tests;
    let tests = t.total();
    Ok(Measured {
        point: ScalingPoint {
            family: String::new(),
            size_factor: 0,
            primitives: 0,
            accelerator: String::new(),
            measured: true,
            rays: Some(rays),
            seconds_per_ray: render_seconds / rays.max(1) as f64,
            tests_per_ray: Some(per_ray(tests)),
            nodes_per_ray: Some(per_ray(counts.accel.nodes_visited)),
            build_seconds: Some(timed.preprocessing),
            accelerator_bytes: Some(accelerator_bytes as u64),
            scene_bytes: scene.memory_bytes() as u64,
        },
        render_seconds,
    })
}

impl Family {
    /// `balls:1-6` or `shells:1-13:2` (from 1 to 13 in steps of 2).
    pub fn parse(text: &str) -> Result<Family, String> {
        let bad =
            || format!("'{text}' is not a family: expected SPD:FROM-TO[:STEP], e.g. balls:1-6");
        let mut parts = text.split(':');
        let (Some(name), Some(range)) = (parts.next(), parts.next()) else {
            return Err(bad());
        };
        let step: u32 = match parts.next() {
            Some(s) => s.parse().map_err(|_| bad())?,
            None => 1,
        };
        let (from, to) = range.split_once('-').unwrap_or((range, range));
        let (from, to): (u32, u32) = (
            from.parse().map_err(|_| bad())?,
            to.parse().map_err(|_| bad())?,
        );
        if step == 0 || from > to || parts.next().is_some() {
            return Err(bad());
        }
        let program = spd::find(name).ok_or_else(|| {
            spd::SpdError::UnknownProgram {
                name: name.to_string(),
            }
            .to_string()
        })?;
        Ok(Family {
            program: program.name,
            size_factors: (from..=to).step_by(step as usize).collect(),
        })
    }
}

/// The files of a study written into a directory.
pub struct StudyFiles {
    /// scaling.json's text, as written.
    pub json: String,
    /// Whether scaling.svg was written (a study of one point has no chart).
    pub chart: bool,
}

impl StudyFiles {
    /// `DIR/{scaling.json, scaling.csv, scaling.md, scaling.svg}`, the files written.
    pub fn line(&self, dir: &Path) -> String {
        format!(
            "{}/{{scaling.json, scaling.csv, scaling.md{}}}",
            dir.display(),
            if self.chart { ", scaling.svg" } else { "" }
        )
    }
}

/// Writes the study into `dir` (created if missing): scaling.json, scaling.csv,
/// scaling.md and, when there is one, the log-log chart scaling.svg.
pub fn write_study(study: &ScalingStudy, dir: &Path) -> Result<StudyFiles, RunError> {
    std::fs::create_dir_all(dir).map_err(|e| RunError::io("create directory", dir, &e))?;
    let json = serde_json::to_string_pretty(study)
        .map_err(|e| RunError::Report(format!("cannot serialize scaling.json: {e}")))?
        + "\n";
    let chart = reports::charts::scaling_chart(study);
    save(dir, "scaling.json", json.as_bytes())?;
    save(
        dir,
        "scaling.csv",
        reports::scaling_text::to_csv(study).as_bytes(),
    )?;
    save(
        dir,
        "scaling.md",
        reports::scaling_text::to_markdown(study).as_bytes(),
    )?;
    if let Some(chart) = &chart {
        save(dir, "scaling.svg", chart.svg.as_bytes())?;
    }
    Ok(StudyFiles {
        json,
        chart: chart.is_some(),
    })
}

/// Fits each family × accelerator's measured points and fills its unmeasured ones.
pub fn fit_and_extrapolate(points: &mut [ScalingPoint]) -> Vec<ScalingFit> {
    let mut keys: Vec<(String, String)> = Vec::new();
    for p in points.iter() {
        let key = (p.family.clone(), p.accelerator.clone());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    let mut fits = Vec::new();
    for (family, accelerator) in keys {
        let mine = |p: &&ScalingPoint| p.family == family && p.accelerator == accelerator;
        let measured: Vec<&ScalingPoint> =
            points.iter().filter(mine).filter(|p| p.measured).collect();
        let time: Vec<(f64, f64)> = measured
            .iter()
            .map(|p| (p.primitives as f64, p.seconds_per_ray))
            .collect();
        let tests: Vec<(f64, f64)> = measured
            .iter()
            .filter_map(|p| Some((p.primitives as f64, p.tests_per_ray?)))
            .collect();
        let Some(time_law) = PowerLaw::fit(&time) else {
            continue;
        };
        let tests_law = PowerLaw::fit(&tests);
        for p in points.iter_mut() {
            if p.family == family && p.accelerator == accelerator && !p.measured {
                p.seconds_per_ray = time_law.at(p.primitives as f64);
                p.tests_per_ray = tests_law.map(|l| l.at(p.primitives as f64));
            }
        }
        fits.push(ScalingFit {
            family,
            accelerator,
            exponent: time_law.exponent,
            coefficient: time_law.coefficient,
            tests_exponent: tests_law.map(|l| l.exponent),
            points: time.len() as u32,
        });
    }
    fits
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(primitives: u64, accel: &str, seconds_per_ray: Option<f64>) -> ScalingPoint {
        ScalingPoint {
            family: "balls".into(),
            size_factor: 0,
            primitives,
            accelerator: accel.into(),
            measured: seconds_per_ray.is_some(),
            rays: None,
            seconds_per_ray: seconds_per_ray.unwrap_or(f64::NAN),
            tests_per_ray: seconds_per_ray.map(|_| primitives as f64),
            nodes_per_ray: None,
            build_seconds: None,
            accelerator_bytes: None,
            scene_bytes: 0,
        }
    }

    #[test]
    fn unmeasured_points_follow_the_fitted_law() {
        // Brute force: 1 ns per primitive per ray, measured at 10 and 100 primitives.
        let mut points = vec![
            point(10, "baseline", Some(1e-8)),
            point(100, "baseline", Some(1e-7)),
            point(10_000, "baseline", None),
            point(10, "bvh", Some(1e-8)),
            point(10_000, "bvh", Some(4e-8)),
        ];
        let fits = fit_and_extrapolate(&mut points);
        let brute = &fits[0];
        assert_eq!((brute.accelerator.as_str(), brute.points), ("baseline", 2));
        assert!((brute.exponent - 1.0).abs() < 1e-9);
        assert!((points[2].seconds_per_ray - 1e-5).abs() < 1e-12);
        assert!((points[2].tests_per_ray.unwrap_or(0.0) - 10_000.0).abs() < 1e-6);
        assert!(!points[2].measured);
        // bvh: 4x over 1000x the primitives, exponent log(4)/log(1000).
        assert!((fits[1].exponent - 4f64.ln() / 1000f64.ln()).abs() < 1e-9);
    }

    #[test]
    fn the_default_plan_reaches_a_million_primitives() {
        let plan = ScalingPlan::default_plan(false);
        plan.check().unwrap();
        let largest = plan
            .families
            .iter()
            .flat_map(|f| {
                f.size_factors
                    .iter()
                    .map(|&n| spd::primitive_count(f.program, Some(n)).unwrap())
            })
            .max()
            .unwrap();
        assert!(largest >= 1_000_000, "{largest}");
        let smallest = plan
            .families
            .iter()
            .map(|f| spd::primitive_count(f.program, Some(f.size_factors[0])).unwrap())
            .min()
            .unwrap();
        assert!(smallest < 100, "{smallest}");
    }

    #[test]
    fn a_quick_study_measures_and_fits() {
        let mut plan = ScalingPlan::default_plan(true);
        plan.families.truncate(1);
        plan.families[0].size_factors = vec![1, 2];
        plan.size = (8, 8);
        let never = AtomicBool::new(false);
        let study = run_scaling(&plan, &crate::progress::Silent, &never).unwrap();
        assert_eq!(study.points.len(), 2 * 3);
        // Brute force on balls:1 (10 spheres + the ground polygon): every primitive per
        // closest-hit query; shadow queries may stop early, so at most 11 per ray.
        let brute = &study.points[0];
        assert_eq!(brute.primitives, 11);
        let tests = brute.tests_per_ray.unwrap();
        assert!(tests > 1.0 && tests <= 11.0, "{tests}");
        assert_eq!(study.fits.len(), 3);
        let bvh = study
            .points
            .iter()
            .find(|p| p.accelerator == "bvh")
            .unwrap();
        assert!(bvh.accelerator_bytes.unwrap() > 0);
        assert!(bvh.nodes_per_ray.unwrap() > 0.0);
    }
}
