//! What the suite records about a scene beside its times: the SPD's published ray
//! counts when it was rendered as they were, the memory its renders held, and where a
//! render stands under the machine's roofline.

use results::{CodeKind, Efficiency, MachinePeak};
use tracer::{RenderOptions, Scene};

use crate::error::RunError;
use crate::scenes::SceneSpec;
use crate::variant_job::VariantMeasurement;

/// The SPD's published ray counts for `spec`, when it was rendered as they were: a
/// classic SPD scene at its size factor, 512 × 512 corner rays, depth 5.
pub(crate) fn published_rays(
    spec: &SceneSpec,
    options: &RenderOptions,
) -> Option<results::PublishedRays> {
    use spd::published::{FRAME, MAX_DEPTH, TOLERANCE, published};
    let Some(crate::scene_input::SceneInput::Spd {
        program,
        size_factor,
    }) = spec.input
    else {
        return None;
    };
    let as_published = spec.spd_sampling
        && size_factor == program.default_size_factor
        && (options.width, options.height) == FRAME
        && options.max_depth == MAX_DEPTH;
    let p = published(program.name).filter(|_| as_published)?;
    Some(results::PublishedRays {
        source: "SPD 3.14 Readme.txt (Haines): 513 x 513 corner rays, depth 5".into(),
        primary: p.eye_rays,
        primary_hit: p.eye_hits,
        reflection: p.reflection_rays,
        refraction: p.refraction_rays,
        shadow: p.shadow_rays,
        tolerance: TOLERANCE,
    })
}

/// A render of `counts` that took `seconds` as a point under `peak`'s roofs, held to
/// the compute roof of its `code`.
pub(crate) fn efficiency(
    counts: &tracer::Counts,
    scene: &Scene,
    (simd, code): (bool, CodeKind),
    seconds: f64,
    peak: &MachinePeak,
) -> Efficiency {
    let flops = tracer::work_model::flops(counts);
    let bytes = tracer::work_model::bytes_touched(counts, scene, simd);
    let intensity = flops as f64 / bytes.max(1) as f64;
    let achieved = if seconds > 0.0 {
        flops as f64 / seconds / 1e9
    } else {
        0.0
    };
    let roof = peak.roof(code, intensity).gflops;
    Efficiency {
        flops,
        bytes_moved: bytes,
        arithmetic_intensity: intensity,
        achieved_gflops: achieved,
        roof_gflops: Some(roof),
        fraction_of_roof: (roof > 0.0).then(|| achieved / roof),
    }
}

/// What the scene's renders held: the scene, the largest structure a variant built and
/// the framebuffer.
pub(crate) fn memory_use(
    scene: &Scene,
    measured: &[Result<VariantMeasurement, RunError>],
) -> Option<results::MemoryUse> {
    let ok: Vec<_> = measured.iter().filter_map(|m| m.as_ref().ok()).collect();
    let framebuffer = ok.iter().map(|m| m.framebuffer_bytes).max()? as u64;
    let accelerator = ok.iter().map(|m| m.accelerator_bytes).max().unwrap_or(0) as u64;
    let bvh = ok
        .iter()
        .find(|m| m.variants.config().accel == tracer::Accelerator::Bvh)
        .map(|m| m.accelerator_bytes as f64 / scene.primitive_count().max(1) as f64);
    let scene_bytes = scene.memory_bytes() as u64;
    Some(results::MemoryUse {
        scene_bytes,
        accelerator_bytes: accelerator,
        framebuffer_bytes: framebuffer,
        peak_bytes: scene_bytes + accelerator + framebuffer,
        bvh_bytes_per_primitive: bvh,
    })
}
