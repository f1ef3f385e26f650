//! The hardware job: the FPGA model's frame time and fit for a scene, the emulator's
//! image, and the software's time on the same job (baseline, diffuse-only gray, one
//! thread, like the thesis's software) under the one timing policy. Also the model's
//! tables 7 and 8 and the thesis design's fit on every device.

use std::sync::atomic::AtomicBool;

use analysis::{Comparison, RgbImage, compare};
use hwmodel::blocks::Pipeline;
use hwmodel::design::Design;
use hwmodel::device::{FitState, fit_design, largest_units};
use hwmodel::frame_timing::{FrameTiming, frame_timing};
use hwmodel::hw_scene::HwScene;
use hwmodel::library::Library;
use results::{DeviceUse, HardwareResult, HwRow, RtlClock, Upload};
use tracer::{
    NoCount, RenderOptions, Sampling, Scene, ShadingMode, VariantSet, render_variant_until,
};

use crate::error::RunError;
use crate::timing::{Measured, TimingPolicy, measure};

pub use hwmodel::frame_timing::THESIS_CLOCK_HZ;

/// The software's time on the hardware's job: `scene` at `size`, baseline variant,
/// diffuse-only gray shading, on `pool`.
pub fn software_time(
    scene: &Scene,
    name: &str,
    size: (u32, u32),
    pool: &rayon::ThreadPool,
    policy: &TimingPolicy,
    stop: &AtomicBool,
) -> Result<Measured<tracer::VariantRender<NoCount>>, RunError> {
    variant_time(
        scene,
        name,
        size,
        &VariantSet::default(),
        pool,
        policy,
        stop,
    )
}

/// The time of `set` on the hardware's job (diffuse-only gray at `size`) on `pool`.
pub fn variant_time(
    scene: &Scene,
    name: &str,
    (width, height): (u32, u32),
    set: &VariantSet,
    pool: &rayon::ThreadPool,
    policy: &TimingPolicy,
    stop: &AtomicBool,
) -> Result<Measured<tracer::VariantRender<NoCount>>, RunError> {
    let options = RenderOptions::new(
        width,
        height,
        Sampling::PixelCenters,
        ShadingMode::DiffuseOnly,
    );
    measure(policy, stop, || {
        pool.install(|| render_variant_until::<NoCount>(scene, &options, set, &|_| {}, stop))
            .map_err(|e| RunError::render(name, &e))
    })
}

/// The software peer the pipeline is also set against: rtprof's variant with every
/// structure (BVH, SIMD lanes, packets), which keeps baseline's picture.
pub const PEER_VARIANT: &str = "bvh+simd+packets";

/// The model and emulator on one scene, beside the software.
pub struct HardwareMeasurement {
    pub primitives: u64,
    pub timing: FrameTiming,
    /// The thesis design's fit on the thesis's device for this scene.
    pub fit_state: Option<FitState>,
    pub software: Measured<tracer::VariantRender<NoCount>>,
    /// [`PEER_VARIANT`] on the same job: on one thread, and on every thread of the
    /// suite's pool (with their number).
    pub peer_one_thread: Measured<tracer::VariantRender<NoCount>>,
    pub peer_all_threads: Measured<tracer::VariantRender<NoCount>>,
    pub peer_threads: usize,
    pub emulator_image: RgbImage,
    pub software_image: RgbImage,
    /// Emulator against software.
    pub comparison: Comparison,
}

/// Runs the hardware job on `scene` at `size` with the thesis design at 50 MHz on the
/// thesis's device (the one the library marks validated).
#[allow(clippy::too_many_arguments)] // the job's inputs: scene, size, two pools, policy, stop
pub fn run_hardware(
    scene: &Scene,
    hw: &HwScene,
    name: &str,
    size: (u32, u32),
    pool: &rayon::ThreadPool,
    all_threads: &rayon::ThreadPool,
    policy: &TimingPolicy,
    stop: &AtomicBool,
) -> Result<HardwareMeasurement, RunError> {
    let (width, height) = size;
    let lib = Library::cyclone_iv_e();
    let pipeline = Pipeline::build(&lib, &Design::thesis());
    let n = hw.primitive_count() as u64;
    let timing = frame_timing(&pipeline, n, width, height, THESIS_CLOCK_HZ);
    let fit_state = lib
        .validated_device()
        .map(|device| fit_design(&lib, device, &pipeline, n, width, height).state);
    // The emulator reads the stop flag before each row, as the renders do.
    let emulated = all_threads
        .install(|| hwmodel::emulator::render_until(hw, width, height, stop))
        .ok_or(RunError::Stopped)?;
    let emulator_image = RgbImage::new(width, height, emulated.to_rgb8())?;
    let software = software_time(scene, name, size, pool, policy, stop)?;
    let peer = VariantSet::parse(PEER_VARIANT)?;
    let peer_one_thread = variant_time(scene, name, size, &peer, pool, policy, stop)?;
    let peer_all_threads = variant_time(scene, name, size, &peer, all_threads, policy, stop)?;
    let frame = &software.last.rendered.frame;
    let software_image = RgbImage::new(frame.width, frame.height, frame.to_rgb8())?;
    let comparison = compare(&software_image, &emulator_image)?;
    Ok(HardwareMeasurement {
        primitives: n,
        timing,
        fit_state,
        software,
        peer_one_thread,
        peer_all_threads,
        peer_threads: all_threads.current_num_threads(),
        emulator_image,
        software_image,
        comparison,
    })
}

/// Tables 7 and 8 and the thesis design's fit on every device (7 primitives, 640x480),
/// and the synthesis of the thesis design's RTL if `rtprof hw synth` kept one on this
/// machine (`rtl::synth::recall`: only a synthesis of exactly this RTL).
pub fn hardware_tables() -> HardwareResult {
    let lib = Library::cyclone_iv_e();
    let t = hwmodel::table::tables(&lib, &Design::thesis());
    let mut devices = Vec::new();
    for family in Library::embedded() {
        let pipeline = Pipeline::build(&family, &Design::thesis());
        for device in &family.devices {
            let f = fit_design(&family, device, &pipeline, 7, 640, 480);
            devices.push(DeviceUse {
                device: device.name.clone(),
                validated: f.validated,
                le: f.used.le,
                le_capacity: device.le,
                mult: f.used.mult,
                mult_capacity: device.mult,
                soft_mult_elements: f.soft_mult_elements,
                mem_bits: f.used.mem_bits,
                mem_capacity: device.mem_bits,
                mem_blocks: f.mem_blocks,
                mem_block_capacity: f.mem_block_capacity,
                plls: f.plls,
                pll_capacity: device.plls,
                fits: f.fits,
                fit_state: Some(f.state),
                largest_units: largest_units(&family, device, &Design::thesis(), 7, 640, 480),
            });
        }
    }
    let thesis = Pipeline::build(&lib, &Design::thesis());
    let synthesis = rtl::synth::recall(&rtl::synth::cache_dir(), &lib, &thesis);
    let rtl_clock = Some(rtl_clock(synthesis.as_ref()));
    let primitives = hwmodel::optimizations::BENCH_PRIMITIVES;
    let bytes = rtl::system::uart::stream_bytes(
        primitives,
        u32::try_from(thesis.design.words_per_primitive()).unwrap_or(u32::MAX),
    );
    let baud = rtl::system::uart::DEFAULT_BAUD;
    HardwareResult {
        family: lib.family.clone(),
        ops: t.ops.iter().map(HwRow::from_model_row).collect(),
        blocks: t.blocks.iter().map(HwRow::from_model_row).collect(),
        devices,
        synthesis,
        rtl_clock,
        upload: Some(Upload {
            primitives,
            bytes,
            baud,
            seconds: rtl::system::uart::upload_seconds(
                usize::try_from(bytes).unwrap_or(usize::MAX),
                baud,
            ),
        }),
    }
}

/// The clock of rtprof's RTL of the thesis design: from the longest path of a kept
/// synthesis of exactly this RTL, else from the level goal the generator pipelines to
/// (the most LUT levels the delay rule allows at the thesis's clock).
fn rtl_clock(synthesis: Option<&results::Synthesis>) -> RtlClock {
    let rule = rtl::synth::fmax::CYCLONE_IV_E;
    match synthesis {
        Some(s) => RtlClock {
            mhz: s.total.fmax_mhz,
            levels: s.total.levels,
            synthesized: true,
            source: format!(
                "rtprof's RTL of the thesis design through {} ({}): its longest path, {} LUT levels, at {} ns a level and {} ns a register",
                s.tool, s.flow, s.total.levels, rule.level_ns, rule.register_ns
            ),
        },
        None => {
            let levels = rule.max_levels_at(rtl::synth::fmax::THESIS_CLOCK_MHZ);
            RtlClock {
                mhz: rule.fmax_mhz(levels),
                levels,
                synthesized: false,
                source: format!(
                    "the level goal rtprof's RTL generator pipelines every stage to ({levels} LUT levels), at {} ns a level and {} ns a register; not synthesized on this machine (`rtprof hw synth` measures it)",
                    rule.level_ns, rule.register_ns
                ),
            }
        }
    }
}
