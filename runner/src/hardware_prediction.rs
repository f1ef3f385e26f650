//! The hardware prediction of `rtprof hw time`: the modelled pipeline's frame time, fit
//! and utilization for a scene on a device, with a what-if design beside the thesis's,
//! and optionally the measured software on the same job. As data (serialized for
//! `--json`) and as the text table the command prints.

use std::sync::atomic::AtomicBool;

use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::device::{
    Fit, FitState, fit_design, headroom_percent, largest_units, largest_units_within_headroom,
};
use hwmodel::frame_timing::{FrameTiming, frame_timing};
use hwmodel::hw_scene::HwScene;
use hwmodel::library::{DeviceSpec, Library};
use serde::Serialize;
use tracer::Scene;

use crate::error::RunError;
use crate::hardware_job::software_time;
use crate::pool::thread_pool;
use crate::timing::TimingPolicy;

/// One design's prediction for a scene.
#[derive(Serialize)]
pub struct Prediction {
    pub design: String,
    #[serde(flatten)]
    pub timing: FrameTiming,
    /// Every resource within the device (on paper; `fit_state` adds the headroom).
    pub fits: bool,
    /// `fits`, `fits_on_paper` (above the routing headroom: warned) or `does_not_fit`.
    pub fit_state: FitState,
    pub utilization: hwmodel::device::Utilization,
    #[serde(rename = "fit")]
    pub detail: Fit,
    /// The largest number of intersection units that fits this device (on paper).
    pub largest_units: Option<u32>,
    /// The largest number of intersection units within the routing headroom.
    pub largest_units_within_headroom: Option<u32>,
}

/// Measured software time of the same job.
#[derive(Serialize)]
pub struct Software {
    /// Tracing seconds (median and 95 % interval); preprocessing is apart.
    pub seconds: f64,
    pub low: f64,
    pub high: f64,
    pub preprocessing_seconds: f64,
    pub threads: u16,
    pub repeats: u32,
    /// Software seconds / hardware seconds.
    pub speedup: f64,
}

#[derive(Serialize)]
pub struct TimeReport {
    pub scene: String,
    pub device: String,
    pub device_validated: bool,
    #[serde(flatten)]
    pub prediction: Prediction,
    /// The thesis's design on the same scene, when a what-if changed it.
    pub thesis_design: Option<Prediction>,
    pub software: Option<Software>,
    /// Primitives the hardware cannot hold that were left out (--ignore-unsupported).
    pub ignored: Option<String>,
}

/// The frame time and fit of `design` for `primitives` on `device`.
pub fn predict(
    lib: &Library,
    device: &DeviceSpec,
    design: &Design,
    primitives: u64,
    (width, height): (u32, u32),
    clock_hz: f64,
) -> Prediction {
    let pipeline = Pipeline::build(lib, design);
    let timing = frame_timing(&pipeline, primitives, width, height, clock_hz);
    let f = fit_design(lib, device, &pipeline, primitives, width, height);
    Prediction {
        design: design.label(),
        timing,
        fits: f.fits,
        fit_state: f.state,
        utilization: f.utilization.clone(),
        detail: f,
        largest_units: largest_units(lib, device, design, primitives, width, height),
        largest_units_within_headroom: largest_units_within_headroom(
            lib, device, design, primitives, width, height,
        ),
    }
}

/// What `rtprof hw time` asks.
pub struct TimeRequest {
    /// The scene's name in the report.
    pub name: String,
    pub design: Design,
    pub size: (u32, u32),
    pub clock_hz: f64,
    /// Time the spheres and cylinders alone when the scene has other primitives.
    pub ignore_unsupported: bool,
    /// Also measure the software: (threads, timed renders).
    pub software: Option<(u16, u32)>,
}

/// The prediction for `scene` on `device`, with the thesis's design beside a what-if
/// and the software's time when asked.
pub fn time_report(
    scene: &Scene,
    lib: &Library,
    device: &DeviceSpec,
    req: &TimeRequest,
) -> Result<TimeReport, RunError> {
    let (primitives, ignored) = match HwScene::from_scene(scene) {
        Ok(hw) => (hw.primitive_count() as u64, None),
        Err(e) if req.ignore_unsupported => {
            let n = scene.spheres.len() + scene.cylinders.len();
            (n as u64, Some(e.to_string()))
        }
        Err(e) => {
            return Err(RunError::Input(format!(
                "{}: {e} (pass --ignore-unsupported to time its spheres and cylinders alone)",
                req.name
            )));
        }
    };
    let predict_for =
        |design: &Design| predict(lib, device, design, primitives, req.size, req.clock_hz);
    let prediction = predict_for(&req.design);
    let thesis_design = (!req.design.is_thesis()).then(|| predict_for(&Design::thesis()));
    let software = match req.software {
        Some((threads, repeats)) => Some(measure_software(
            scene,
            &req.name,
            req.size,
            threads,
            repeats,
            prediction.timing.seconds,
        )?),
        None => None,
    };
    Ok(TimeReport {
        scene: req.name.clone(),
        device: device.name.clone(),
        device_validated: lib.validated && device.validated,
        prediction,
        thesis_design,
        software,
        ignored,
    })
}

/// The software's tracing time on the hardware's job (baseline, diffuse-only gray) at
/// `size` on `threads` threads, `repeats` timed renders, against `hw_seconds`.
pub fn measure_software(
    scene: &Scene,
    name: &str,
    size: (u32, u32),
    threads: u16,
    repeats: u32,
    hw_seconds: f64,
) -> Result<Software, RunError> {
    let pool = thread_pool(Some(threads))?;
    let never = AtomicBool::new(false);
    // `repeats` renders at least; no minimum time, so the count is what was asked.
    let policy = TimingPolicy::new(repeats, 0.0);
    let measured = software_time(scene, name, size, &pool, &policy, &never)?;
    let est = measured.time;
    Ok(Software {
        seconds: est.median,
        low: est.low,
        high: est.high,
        preprocessing_seconds: measured.preprocessing,
        threads,
        repeats: measured.samples.len() as u32,
        speedup: est.median / hw_seconds,
    })
}

fn pct(x: f64) -> String {
    format!("{:.1} %", x * 100.0)
}

fn format_prediction_column(p: &Prediction) -> Vec<String> {
    let f = &p.detail;
    vec![
        p.design.clone(),
        p.timing.units.to_string(),
        p.timing.cycles_per_pixel.to_string(),
        p.timing.fill_cycles.to_string(),
        p.timing.cycles.to_string(),
        format!(
            "{:.6} s ({:.1} fps)",
            p.timing.seconds,
            1.0 / p.timing.seconds
        ),
        format!("{} ({})", f.used.le, pct(f.utilization.le)),
        format!(
            "{} ({}){}",
            f.used.mult,
            pct(f.utilization.mult),
            if f.soft_mult_elements > 0 {
                format!(" + {} in logic", f.soft_mult_elements)
            } else {
                String::new()
            }
        ),
        format!("{} ({})", f.used.mem_bits, pct(f.utilization.mem_bits)),
        format!(
            "{} of {} ({})",
            f.mem_blocks,
            f.mem_block_capacity,
            pct(f.utilization.mem_blocks)
        ),
        format!("{} ({})", f.plls, pct(f.utilization.plls)),
        match f.state {
            FitState::Fits => f.state.label().to_string(),
            FitState::FitsOnPaper => format!(
                "{} ({})",
                f.state.label(),
                f.above_headroom
                    .iter()
                    .map(|r| format!("{r} > {} %", headroom_percent(r)))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            FitState::DoesNotFit => format!("{} ({} over)", f.state.label(), f.over.join(", ")),
        },
        p.largest_units
            .map_or_else(|| "none".to_string(), |k| k.to_string()),
        p.largest_units_within_headroom
            .map_or_else(|| "none".to_string(), |k| k.to_string()),
    ]
}

impl TimeReport {
    /// The report as the text table `rtprof hw time` prints.
    pub fn to_text(&self) -> String {
        let r = self;
        let p = &r.prediction;
        let mut out = format!(
            "{}: {} primitives, {}x{} at {} MHz on {}{}\n",
            r.scene,
            p.timing.primitives,
            p.timing.width,
            p.timing.height,
            p.timing.clock_hz / 1e6,
            r.device,
            if r.device_validated {
                ""
            } else {
                " (unvalidated)"
            }
        );
        if let Some(ignored) = &r.ignored {
            out += &format!("left out: {ignored}\n");
        }
        let labels = [
            "design",
            "units K",
            "cycles per pixel",
            "fill cycles",
            "cycles",
            "frame time",
            "LEs",
            "9-bit multipliers",
            "memory bits",
            "RAM blocks",
            "PLLs",
            "fits",
            "largest K that fits",
            "largest K in headroom",
        ];
        let mut columns = Vec::new();
        if let Some(t) = &r.thesis_design {
            columns.push(format_prediction_column(t));
        }
        columns.push(format_prediction_column(p));
        for (i, label) in labels.iter().enumerate() {
            out += &format!("  {label:<22}");
            for c in &columns {
                out += &format!(" {:<34}", c[i]);
            }
            out += "\n";
        }
        if let Some(t) = &r.thesis_design {
            out += &format!(
                "  what-if vs thesis: {:.2}x the frame rate, {:+.1} % LEs\n",
                t.timing.seconds / p.timing.seconds,
                (p.detail.used.le as f64 / t.detail.used.le as f64 - 1.0) * 100.0
            );
        }
        for q in r.thesis_design.iter().chain([p]) {
            if let Some(warning) = q.detail.headroom_warning() {
                out += &format!("  warning: {}: {warning}\n", q.design);
            }
        }
        if p.detail.soft_mult_elements > 0 {
            out += &format!(
                "  multiplier rule: {} elements beyond the device's {} are built in logic ({} LEs)\n",
                p.detail.soft_mult_elements, p.detail.used.mult, p.detail.soft_mult_le
            );
        }
        if let Some(s) = &r.software {
            out += &format!(
                "  software (baseline, diffuse-only gray, {} thread{}): {:.4} s [{:.4}, {:.4}] → hardware speed-up {:.2}x{}\n",
                s.threads,
                if s.threads == 1 { "" } else { "s" },
                s.seconds,
                s.low,
                s.high,
                s.speedup,
                if s.speedup < 1.0 {
                    " (the software is faster)"
                } else {
                    ""
                }
            );
        }
        out
    }
}
