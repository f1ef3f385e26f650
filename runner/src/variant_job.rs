//! The variant job: variant sets on one scene, measured the one way rtprof measures:
//! a counted render of each first (exact counts; it also warms caches and the thread
//! pool up) and a clocked one (the time split by query, [`crate::ray_rates`]), then
//! the timed uncounted renders under the timing policy, interleaved in rounds with the
//! gate's yardsticks: the f64 reference renderer on the same scene at a smaller frame,
//! and the calibration kernel. The last timed frame is each variant's image.

use std::time::Instant;

use analysis::RgbImage;
use tracer::{Count, Counts, NoCount, VariantRender, VariantSet, render_variant_until};

use crate::calibration::time_kernel;
use crate::error::RunError;
use crate::outside::measure::{OutsideJobs, OutsideMeasurement, Prepared, prepare};
use crate::outside::run::OutsideRun;
use crate::ray_rates::{QueryShares, clocked_pass};
use crate::render_setup::RenderSetup;
use crate::timing::{
    KernelTimes, PhaseTimes, RenderJob, RoundJob, TimingPolicy, measure_interleaved,
};

/// A measured variant.
pub struct VariantMeasurement {
    pub variants: VariantSet,
    /// Tracing seconds of each timed render.
    pub samples: Vec<f64>,
    /// Process CPU seconds of each timed render (the gate's stable measure).
    pub cpu_samples: Vec<f64>,
    /// Median and interval of `samples`.
    pub time: analysis::Estimate,
    /// Median preprocessing seconds (reported apart from the time).
    pub preprocessing: f64,
    /// Exact counts of one render.
    pub counts: Counts,
    /// The picture.
    pub image: RgbImage,
    /// Bytes of the intersection structure the variant built (0: none).
    pub accelerator_bytes: usize,
    /// Bytes of the framebuffer (12 a pixel).
    pub framebuffer_bytes: usize,
    /// The clocked pass's split of the time by query (`None` if it failed).
    pub query_shares: Option<QueryShares>,
}

/// Every variant of [`RenderSetup::measure_all`], in the order asked, and the gate's
/// yardsticks timed between them.
pub struct VariantsMeasured {
    pub variants: Vec<Result<VariantMeasurement, RunError>>,
    /// Every outside tracer, in the order asked.
    pub outside: Vec<Result<OutsideMeasurement, RunError>>,
    /// The calibration kernel's times (one per round).
    pub calibration: Option<KernelTimes>,
    /// The f64 reference renderer's times at [`yardstick_size`] (one per round).
    pub yardstick: Option<((u32, u32), KernelTimes)>,
}

/// The yardstick's frame for a scene rendered at `width` × `height`: each side divided
/// by [`results::Yardstick::DIVISOR`] (at least 8 pixels, and never more than the frame).
pub fn yardstick_size(width: u32, height: u32) -> (u32, u32) {
    let side = |n: u32| (n / results::Yardstick::DIVISOR).max(8).min(n);
    (side(width), side(height))
}

/// A timed run: a render of rtprof's tracer or a run of an outside program.
enum Timed {
    Own(VariantRender<NoCount>),
    Outside(OutsideRun),
}

impl PhaseTimes for Timed {
    fn tracing(&self) -> std::time::Duration {
        match self {
            Timed::Own(r) => r.tracing,
            Timed::Outside(r) => std::time::Duration::from_secs_f64(r.seconds),
        }
    }
    fn preprocessing(&self) -> std::time::Duration {
        match self {
            Timed::Own(r) => r.preprocessing,
            // What an outside program spends before tracing is in its time or not,
            // as its definition's time source says; none is apart.
            Timed::Outside(_) => std::time::Duration::ZERO,
        }
    }
    fn cpu(&self) -> Option<std::time::Duration> {
        match self {
            Timed::Own(_) => None,
            Timed::Outside(r) => Some(std::time::Duration::from_secs_f64(r.cpu)),
        }
    }
}

impl RenderSetup<'_> {
    /// Counts and pictures every set of `sets`, timing them interleaved: one counted
    /// render each first (exact counts; it also warms caches and the pool up), then
    /// rounds of one uncounted render of each set still short of `policy`'s samples,
    /// with the gate's yardsticks at the start of each round (when `calibrate`): the f64
    /// reference renderer on the scene at [`yardstick_size`] and the calibration kernel. A set
    /// that fails is reported in its place; the others are measured. The outside
    /// tracers of `outside` are prepared (one untimed run each) and timed in the same
    /// rounds. `doing` hears what is being done and `told` the timed renders done and
    /// planned (for a progress display).
    pub fn measure_all(
        &self,
        sets: &[VariantSet],
        outside: &OutsideJobs<'_>,
        policy: &TimingPolicy,
        calibrate: bool,
        doing: &dyn Fn(&str),
        told: &dyn Fn(u64, u64),
    ) -> Result<VariantsMeasured, RunError> {
        let fail = |e: tracer::RenderError| RunError::render(self.name, &e);
        let counts: Vec<Result<Counts, RunError>> = sets
            .iter()
            .map(|set| {
                doing(&format!("counting {set}"));
                let counted = self
                    .counting_pool
                    .install(|| {
                        render_variant_until::<Count>(
                            self.scene,
                            self.options,
                            set,
                            &|_| {},
                            self.stop,
                        )
                    })
                    .map_err(fail)?;
                counted.rendered.counts().ok_or_else(|| RunError::Render {
                    context: self.name.to_string(),
                    message: "the counted render returned no counts".into(),
                })
            })
            .collect();
        let shares: Vec<Option<QueryShares>> = sets
            .iter()
            .zip(&counts)
            .map(|(set, counted)| {
                counted.as_ref().ok()?;
                doing(&format!("clocking {set}"));
                clocked_pass(self, set).ok()
            })
            .collect();
        let threads = self.pool.current_num_threads();
        let mut prepared: Vec<Result<Prepared, RunError>> = Vec::new();
        for def in outside.defs {
            doing(&format!("running {} once", def.name));
            match prepare(def, self.scene, self.options, threads, outside, self.stop) {
                Err(RunError::Stopped) => return Err(RunError::Stopped),
                other => prepared.push(other),
            }
        }
        // Only the sets whose counted render worked are timed.
        let timed: Vec<usize> = (0..sets.len()).filter(|&i| counts[i].is_ok()).collect();
        let mut jobs: Vec<RenderJob<'_, Timed>> = timed
            .iter()
            .map(|&i| {
                let set = &sets[i];
                Box::new(move || {
                    self.pool
                        .install(|| {
                            render_variant_until::<NoCount>(
                                self.scene,
                                self.options,
                                set,
                                &|_| {},
                                self.stop,
                            )
                        })
                        .map(Timed::Own)
                        .map_err(fail)
                }) as RenderJob<'_, _>
            })
            .collect();
        // And the outside tracers whose first run worked.
        for p in prepared.iter().flatten() {
            jobs.push(Box::new(move || p.run(self.stop).map(Timed::Outside)));
        }
        doing(&format!("timing {} variants", jobs.len()));
        let (width, height) = yardstick_size(self.options.width, self.options.height);
        let small = tracer::RenderOptions {
            width,
            height,
            per_sample: false,
            ..*self.options
        };
        // Converted once: a round times the render alone, as the variants' tracing.
        let converted = calibrate.then(|| reference::RefScene::new(self.scene));
        let mut each_round: Vec<RoundJob<'_>> = Vec::new();
        if let Some(converted) = &converted {
            each_round.push(Box::new(move || {
                let start = Instant::now();
                self.pool
                    .install(|| {
                        reference::render::render_until(converted, &small, &|_| {}, self.stop)
                    })
                    .map_err(|e| match e {
                        reference::ReferenceError::Cancelled => RunError::Stopped,
                        e => RunError::Render {
                            context: format!("{} (yardstick)", self.name),
                            message: e.to_string(),
                        },
                    })?;
                Ok(start.elapsed().as_secs_f64())
            }));
            each_round.push(Box::new(|| Ok(time_kernel(self.pool))));
        }
        let measured = measure_interleaved(policy, self.stop, jobs, each_round, told)?;
        let mut each_round = measured.each_round.into_iter();
        let yardstick = each_round.next().flatten().map(|t| ((width, height), t));
        let calibration = each_round.next().flatten();
        let mut renders = measured.renders;
        let outside_timings = renders.split_off(timed.len().min(renders.len()));
        let outside = outside_results(prepared, outside_timings)?;
        let mut timings = timed.into_iter().zip(renders);
        let mut variants = Vec::with_capacity(sets.len());
        for (i, ((set, counted), query_shares)) in sets.iter().zip(counts).zip(shares).enumerate() {
            let counts = match counted {
                Ok(c) => c,
                Err(e) => {
                    variants.push(Err(e));
                    continue;
                }
            };
            let timing = match timings.next() {
                Some((index, timing)) if index == i => timing,
                _ => Err(RunError::Stopped),
            };
            variants.push(timing.and_then(|m| {
                // The first jobs are the sets' renders: another kind is a bug.
                let Timed::Own(last) = m.last else {
                    return Err(RunError::Panicked);
                };
                let frame = &last.rendered.frame;
                let image = RgbImage::new(frame.width, frame.height, frame.to_rgb8())?;
                Ok(VariantMeasurement {
                    variants: set.clone(),
                    samples: m.samples,
                    cpu_samples: m.cpu_samples,
                    time: m.time,
                    preprocessing: m.preprocessing,
                    counts,
                    image,
                    accelerator_bytes: last.accelerator_bytes,
                    framebuffer_bytes: last.rendered.frame.memory_bytes(),
                    query_shares,
                })
            }));
        }
        Ok(VariantsMeasured {
            variants,
            outside,
            calibration,
            yardstick,
        })
    }
}

/// Each prepared outside tracer with its timed runs (`timings`: one per tracer whose
/// first run worked, in order).
fn outside_results(
    prepared: Vec<Result<Prepared, RunError>>,
    timings: Vec<Result<crate::timing::Measured<Timed>, RunError>>,
) -> Result<Vec<Result<OutsideMeasurement, RunError>>, RunError> {
    let mut timings = timings.into_iter();
    let mut out = Vec::with_capacity(prepared.len());
    for p in prepared {
        let p = match p {
            Ok(p) => p,
            Err(e) => {
                out.push(Err(e));
                continue;
            }
        };
        let measured = match timings.next() {
            Some(Ok(m)) => m,
            Some(Err(e)) => {
                out.push(Err(e));
                continue;
            }
            None => return Err(RunError::Stopped),
        };
        // The jobs after the sets' are the outside runs: another kind is a bug.
        let Timed::Outside(last) = measured.last else {
            return Err(RunError::Panicked);
        };
        out.push(Ok(OutsideMeasurement {
            name: results::VariantName::outside(&p.def.name)?,
            prepared: p,
            samples: measured.samples,
            cpu_samples: measured.cpu_samples,
            time: measured.time,
            image: last.image,
        }));
    }
    Ok(out)
}
