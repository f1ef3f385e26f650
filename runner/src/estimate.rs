//! How long a brute-force render will take, said before it starts. Without an
//! acceleration structure every ray tests every primitive, so a render of a big scene
//! can run for minutes where `bvh` takes a second. The estimate times a tiny probe
//! render of the same scene and variants on one thread and scales it by the samples
//! traced and the worker threads: a rough figure, enough to warn.

use std::time::Duration;

use tracer::{NoCount, RenderOptions, Sampling, Scene, VariantSet, render_variant};

use crate::error::RunError;
use crate::pool::Workers;

/// Scenes with fewer primitives than this render fast enough by brute force.
pub const MANY_PRIMITIVES: usize = 1_000;

/// Estimates shorter than this are not worth a note.
pub const WORTH_A_NOTE: Duration = Duration::from_secs(5);

/// The probe render's size, pixels.
pub const PROBE_SIZE: (u32, u32) = (8, 6);

/// The expected time of one brute-force render.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BruteForceEstimate {
    pub primitives: usize,
    pub width: u32,
    pub height: u32,
    pub seconds: f64,
}

impl BruteForceEstimate {
    /// One line for the user when the render will take longer than [`WORTH_A_NOTE`]:
    /// `note: brute force over 8,000 primitives at 640×480: about 2 min; --variant bvh
    /// is usually far faster`.
    pub fn note(&self) -> Option<String> {
        (self.seconds > WORTH_A_NOTE.as_secs_f64()).then(|| {
            format!(
                "note: brute force over {} primitives at {}: {}; --variant bvh is usually far faster",
                reports::format::count(self.primitives as u64),
                reports::format::size(self.width, self.height),
                reports::format::rough_duration(self.seconds)
            )
        })
    }
}

/// Samples a render traces: one per pixel, or the SPD's pixel corners.
pub fn samples(options: &RenderOptions) -> u64 {
    let (w, h) = (u64::from(options.width), u64::from(options.height));
    match options.sampling {
        Sampling::PixelCenters => w * h,
        Sampling::SpdCorners => (w + 1) * (h + 1),
    }
}

/// A probe's one-thread time scaled to a render: the probe's cost per sample times the
/// render's samples, shared by `threads` workers.
pub fn scale(probe_seconds: f64, probe_samples: u64, samples: u64, threads: usize) -> f64 {
    let per_sample = probe_seconds / probe_samples.max(1) as f64;
    per_sample * samples as f64 / threads.max(1) as f64
}

/// The time a render of `scene` with `options` and `variants` on `threads` workers
/// (default: one per core) will take, when it is a brute-force render (no `bvh`) of at
/// least [`MANY_PRIMITIVES`] primitives; `None` otherwise (nothing is rendered then),
/// and when the probe cannot render (the render itself will say why).
pub fn brute_force(
    scene: &Scene,
    options: &RenderOptions,
    variants: &VariantSet,
    threads: Option<u16>,
) -> Result<Option<BruteForceEstimate>, RunError> {
    let primitives = scene.primitive_count();
    let (w, h) = (u64::from(options.width), u64::from(options.height));
    // A render the limits refuse gets no estimate: its error is the message.
    let refused = options.limits.check_size(w, h).is_err()
        || options.limits.check_ray_depth(options.max_depth).is_err();
    if refused || !variants.config().accel.tests_everything() || primitives < MANY_PRIMITIVES {
        return Ok(None);
    }
    let probe = RenderOptions {
        width: PROBE_SIZE.0,
        height: PROBE_SIZE.1,
        ..*options
    };
    let one = Workers::new(Some(1))?;
    let probed = one.install(|| render_variant::<NoCount>(scene, &probe, variants, &|_| {}));
    let Ok(out) = probed else {
        return Ok(None);
    };
    let threads = threads.map_or_else(rayon::current_num_threads, usize::from);
    Ok(Some(BruteForceEstimate {
        primitives,
        width: options.width,
        height: options.height,
        seconds: scale(
            out.tracing.as_secs_f64(),
            samples(&probe),
            samples(options),
            threads,
        ),
    }))
}

/// Says on `progress` how long a long brute-force render will take ([`brute_force`]),
/// before it starts; says nothing otherwise.
pub fn note_if_slow(
    scene: &Scene,
    options: &RenderOptions,
    variants: &VariantSet,
    threads: Option<u16>,
    progress: &dyn crate::progress::Progress,
) -> Result<(), RunError> {
    if let Some(note) = brute_force(scene, options, variants, threads)?.and_then(|e| e.note()) {
        progress.note(&note);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use tracer::ShadingMode;

    #[test]
    fn scaling_is_cost_per_sample_times_samples_over_threads() {
        // 48 probe samples in 0.012 s: 0.25 ms each; 640×480 = 307,200 samples
        // = 76.8 s on one thread, 19.2 s on four.
        let s = scale(0.012, 48, 640 * 480, 4);
        assert!((s - 19.2).abs() < 1e-9, "{s}");
        assert!((scale(0.012, 48, 640 * 480, 1) - 76.8).abs() < 1e-9);
    }

    #[test]
    fn spd_corners_trace_one_more_row_and_column() {
        let mut o = RenderOptions::new(8, 6, Sampling::PixelCenters, ShadingMode::Color);
        assert_eq!(samples(&o), 48);
        o.sampling = Sampling::SpdCorners;
        assert_eq!(samples(&o), 63);
    }

    #[test]
    fn the_note_names_primitives_size_and_time_only_past_five_seconds() {
        let e = BruteForceEstimate {
            primitives: 8_000,
            width: 640,
            height: 480,
            seconds: 125.0,
        };
        assert_eq!(
            e.note().as_deref(),
            Some(
                "note: brute force over 8,000 primitives at 640×480: about 2 min; \
                 --variant bvh is usually far faster"
            )
        );
        let quick = BruteForceEstimate { seconds: 4.9, ..e };
        assert_eq!(quick.note(), None);
        assert_eq!(reports::format::rough_duration(30.4), "about 30 s");
        assert_eq!(reports::format::rough_duration(3.0 * 3600.0), "about 3 h");
    }

    #[test]
    fn small_scenes_and_bvh_are_not_estimated() {
        let scene = tracer::builtin_scenes::find("balls1")
            .unwrap()
            .parse()
            .unwrap();
        let options = RenderOptions::for_scene(&scene);
        assert!(scene.primitive_count() < MANY_PRIMITIVES);
        let base = VariantSet::parse("baseline").unwrap();
        assert_eq!(brute_force(&scene, &options, &base, Some(1)).unwrap(), None);
    }

    #[test]
    fn a_big_brute_force_scene_is_probed_and_bvh_is_not() {
        // Depth 4: 1 + 9 + 81 + 729 + 6,561 = 7,381 spheres.
        let scene =
            tracer::parse_nff(&tracer::generators::sphereflake(4).unwrap(), "flake").unwrap();
        let options = RenderOptions::new(640, 480, Sampling::PixelCenters, ShadingMode::Color);
        let base = VariantSet::parse("baseline").unwrap();
        let e = brute_force(&scene, &options, &base, Some(2))
            .unwrap()
            .unwrap();
        assert_eq!((e.primitives, e.width, e.height), (7_381, 640, 480));
        assert!(e.seconds > 0.0 && e.seconds.is_finite(), "{e:?}");
        let too_big = RenderOptions::new(99_999, 480, Sampling::PixelCenters, ShadingMode::Color);
        assert_eq!(brute_force(&scene, &too_big, &base, Some(2)).unwrap(), None);
        let bvh = VariantSet::parse("bvh").unwrap();
        assert_eq!(brute_force(&scene, &options, &bvh, Some(2)).unwrap(), None);
    }
}
