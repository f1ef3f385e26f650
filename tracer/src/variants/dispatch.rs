//! The variants' dispatch: renders a scene with a set of variants. It prepares the
//! scene (eye offsets for `bounded`), builds the intersection structure, and runs the
//! renderer with the chosen square root (a counter type), structure (an intersector
//! type) and [`RenderMethod`] (projection, diffuse form, checkerboard). Everything the
//! command line, the suite and the benchmarks render goes through [`render_variant`].

use crate::accel::{BruteForce, Bvh, BvhStats, Intersector, Simd, WideBvh};
use crate::camera::Projection;
use crate::counter::{Count, Counter, NoCount, Phased, QueryClock};
use crate::render::{
    NEVER_STOP, RenderError, RenderMethod, RenderOptions, Rendered, SampleMemory, render_into,
};
use crate::scene::Scene;
use crate::variants::eye_space::with_eye_offsets;
use crate::variants::fast_sqrt::{
    BitTrickSqrt, NewtonBitTrickSqrt, SquareRoot, TunedBitTrickSqrt, WithSqrt,
};
use crate::variants::set::{Accelerator, SqrtMethod, VariantSet};
use crate::vec3::Vec3;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

/// A finished variant render with its phase timings.
#[derive(Clone, Debug)]
pub struct VariantRender<C> {
    pub rendered: Rendered<C>,
    /// Scene preparation and structure build (camera space, SIMD lanes, BVH).
    pub preprocessing: Duration,
    /// The render itself.
    pub tracing: Duration,
    /// The BVH's figures when the `bvh` variant ran.
    pub bvh: Option<BvhStats>,
    /// Bytes of the intersection structure (0 for brute force, which builds none).
    pub accelerator_bytes: usize,
}

/// Renders `scene` with `variants`; `options` are the caller's (size, sampling, shading
/// mode, depth, limits), everything else comes from the variants.
///
/// The renderer for each of this crate's counters is compiled once, in this crate (see
/// [`RenderWith`]), however many crates call it.
pub fn render_variant<C: RenderWith>(
    scene: &Scene,
    options: &RenderOptions,
    variants: &VariantSet,
    progress: &(dyn Fn(u64) + Sync),
) -> Result<VariantRender<C>, RenderError> {
    C::render_variant(scene, options, variants, progress, &NEVER_STOP)
}

/// [`render_variant`] that stops when `stop` is set (checked before each sample row):
/// it then returns [`RenderError::Cancelled`], never a partial frame.
pub fn render_variant_until<C: RenderWith>(
    scene: &Scene,
    options: &RenderOptions,
    variants: &VariantSet,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
) -> Result<VariantRender<C>, RenderError> {
    C::render_variant(scene, options, variants, progress, stop)
}

/// A counter [`render_variant`] renders with.
///
/// Why a trait: a generic function is compiled again in every crate that instantiates it
/// (optimized builds share no instantiations between crates), and the renderer with all
/// its variants is most of the tracer's code, so the runner, the binary, the web app and
/// the benchmarks each compiled their own copies, which were most of their build time.
/// Each counter of this crate implements it with a non-generic function, compiled here
/// once with the tracer's own codegen settings; a counter defined elsewhere (a test's)
/// implements it by calling [`render_variant_with`].
pub trait RenderWith: Counter {
    /// [`render_variant_until`] with this counter.
    fn render_variant(
        scene: &Scene,
        options: &RenderOptions,
        variants: &VariantSet,
        progress: &(dyn Fn(u64) + Sync),
        stop: &AtomicBool,
    ) -> Result<VariantRender<Self>, RenderError>;
}

/// Implements [`RenderWith`] for this crate's counters. `inline(never)`: inlined into a
/// caller, the call would instantiate the renderer in the caller's crate again.
macro_rules! render_with_compiled_here {
    ($($counter:ty),*) => {$(
        impl RenderWith for $counter {
            #[inline(never)]
            fn render_variant(
                scene: &Scene,
                options: &RenderOptions,
                variants: &VariantSet,
                progress: &(dyn Fn(u64) + Sync),
                stop: &AtomicBool,
            ) -> Result<VariantRender<Self>, RenderError> {
                render_variant_with::<Self>(scene, options, variants, progress, stop)
            }
        }
    )*};
}

render_with_compiled_here!(NoCount, Count, Phased, QueryClock);

/// The renderer behind [`render_variant`], generic over any counter: for counters defined
/// outside this crate (their [`RenderWith`] calls it).
pub fn render_variant_with<C: Counter>(
    scene: &Scene,
    options: &RenderOptions,
    variants: &VariantSet,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
) -> Result<VariantRender<C>, RenderError> {
    let config = variants.config();
    let start = Instant::now();
    let moved;
    let scene = if config.projection == Projection::EyeRows {
        moved = with_eye_offsets(scene);
        &moved
    } else {
        scene
    };
    let method = RenderMethod {
        projection: config.projection,
        diffuse: config.diffuse,
        checkerboard: config.checkerboard,
        packets: config.packets,
        ortho_focus: (config.projection == Projection::Orthographic)
            .then(|| scene_depth(scene))
            .flatten(),
    };
    let job = Job {
        scene,
        options,
        method: &method,
        progress,
        stop,
        start,
    };
    match config.accel {
        Accelerator::BruteForce => job.with_sqrt(&BruteForce::new(scene), config.sqrt, None),
        Accelerator::Simd => {
            let simd = Simd::new(scene);
            let mut out = job.with_sqrt(&simd, config.sqrt, None)?;
            out.accelerator_bytes = simd.memory_bytes();
            Ok(out)
        }
        Accelerator::Bvh => {
            let bvh = Bvh::build_with(scene, options.bvh_builder);
            let stats = bvh.stats();
            let mut out = job.with_sqrt(&bvh, config.sqrt, Some(stats))?;
            out.accelerator_bytes = stats.bytes;
            Ok(out)
        }
        Accelerator::WideBvh => {
            let wide = WideBvh::build_with(scene, options.bvh_builder);
            let mut out = job.with_sqrt(&wide, config.sqrt, None)?;
            out.accelerator_bytes = wide.stats().bytes;
            Ok(out)
        }
        Accelerator::Embree | Accelerator::EmbreeNative | Accelerator::EmbreePackets => {
            job.embree(config.sqrt, config.accel)
        }
    }
}

/// How far ahead of the eye the scene's centre lies (the centre of the box around the
/// primitives' defining points): where the orthographic grid should span the
/// perspective view, so `ortho` frames the scene as `baseline` does even when the
/// NFF look-at point is close to the eye (as in rings.nff).
fn scene_depth(scene: &Scene) -> Option<f32> {
    let mut points = Vec::new();
    points.extend(scene.spheres.iter().map(|s| s.center));
    points.extend(scene.cylinders.iter().flat_map(|c| [c.base, c.apex]));
    points.extend(scene.cones.iter().flat_map(|c| [c.base, c.apex]));
    points.extend(
        scene
            .polygons
            .iter()
            .flat_map(|p| p.outline.vertices.iter().copied()),
    );
    points.extend(
        scene
            .patches
            .iter()
            .flat_map(|p| p.outline.vertices.iter().copied()),
    );
    let first = points.first()?.to_array();
    let (mut lo, mut hi) = (first, first);
    for p in &points {
        for (axis, v) in p.to_array().into_iter().enumerate() {
            lo[axis] = lo[axis].min(v);
            hi[axis] = hi[axis].max(v);
        }
    }
    let centre = Vec3::new(
        0.5 * (lo[0] + hi[0]),
        0.5 * (lo[1] + hi[1]),
        0.5 * (lo[2] + hi[2]),
    );
    let c = &mut NoCount;
    let ahead = c.sub(scene.view.at, scene.view.from);
    if !(c.dot(ahead, ahead) > 0.0) {
        return None;
    }
    let forward = c.normalize(ahead);
    let to_centre = c.sub(centre, scene.view.from);
    let depth = c.dot(to_centre, forward);
    (depth > 0.0 && depth.is_finite()).then_some(depth)
}

struct Job<'a> {
    scene: &'a Scene,
    options: &'a RenderOptions,
    method: &'a RenderMethod,
    progress: &'a (dyn Fn(u64) + Sync),
    stop: &'a AtomicBool,
    start: Instant,
}

impl Job<'_> {
    /// The `embree` variants (`accel` says which): Embree builds its tree
    /// (preprocessing) and answers the queries; camera and shading are rtprof's.
    #[cfg(feature = "embree")]
    fn embree<C: Counter>(
        &self,
        sqrt: SqrtMethod,
        accel: Accelerator,
    ) -> Result<VariantRender<C>, RenderError> {
        use crate::accel::{Embree, EmbreeMode, EmbreePackets};
        let failed = |e| RenderError::Accelerator(format!("Embree: {e}"));
        if accel == Accelerator::EmbreePackets {
            let embree = EmbreePackets::new(self.scene).map_err(failed)?;
            let mut out = self.with_sqrt(&embree, sqrt, None)?;
            out.accelerator_bytes = embree.memory_bytes();
            return Ok(out);
        }
        let mode = if accel == Accelerator::EmbreeNative {
            EmbreeMode::Native
        } else {
            EmbreeMode::Exact
        };
        let embree = Embree::with_mode(self.scene, mode).map_err(failed)?;
        let mut out = self.with_sqrt(&embree, sqrt, None)?;
        out.accelerator_bytes = embree.memory_bytes();
        Ok(out)
    }

    #[cfg(not(feature = "embree"))]
    fn embree<C: Counter>(
        &self,
        _sqrt: SqrtMethod,
        _accel: Accelerator,
    ) -> Result<VariantRender<C>, RenderError> {
        Err(RenderError::Accelerator(
            "this rtprof was built without Embree: install libembree-dev and build with \
             `cargo build --release --features embree` to run the embree variant"
                .into(),
        ))
    }

    fn with_sqrt<C: Counter, I: Intersector>(
        &self,
        accel: &I,
        sqrt: SqrtMethod,
        bvh: Option<BvhStats>,
    ) -> Result<VariantRender<C>, RenderError> {
        match sqrt {
            SqrtMethod::Std => self.run::<C, I>(accel, bvh),
            SqrtMethod::BitTrick => self.run_with::<C, BitTrickSqrt, I>(accel, bvh),
            SqrtMethod::TunedBitTrick => self.run_with::<C, TunedBitTrickSqrt, I>(accel, bvh),
            SqrtMethod::NewtonBitTrick => self.run_with::<C, NewtonBitTrickSqrt, I>(accel, bvh),
        }
    }

    fn run<C: Counter, I: Intersector>(
        &self,
        accel: &I,
        bvh: Option<BvhStats>,
    ) -> Result<VariantRender<C>, RenderError> {
        // The frame's memory is setup (as the outside programs' frames are), taken
        // before the trace clock starts.
        let samples = SampleMemory::for_render(self.options)?;
        let preprocessing = self.start.elapsed();
        let start = Instant::now();
        let rendered = render_into::<C, I>(
            self.scene,
            accel,
            self.options,
            self.method,
            self.progress,
            self.stop,
            samples,
        )?;
        Ok(VariantRender {
            rendered,
            preprocessing,
            tracing: start.elapsed(),
            bvh,
            accelerator_bytes: 0,
        })
    }

    fn run_with<C: Counter, S: SquareRoot, I: Intersector>(
        &self,
        accel: &I,
        bvh: Option<BvhStats>,
    ) -> Result<VariantRender<C>, RenderError> {
        let out = self.run::<WithSqrt<C, S>, I>(accel, bvh)?;
        let Rendered {
            frame,
            counter,
            rays,
            samples,
        } = out.rendered;
        Ok(VariantRender {
            rendered: Rendered {
                frame,
                counter: counter.inner,
                rays,
                samples,
            },
            preprocessing: out.preprocessing,
            tracing: out.tracing,
            bvh: out.bvh,
            accelerator_bytes: out.accelerator_bytes,
        })
    }
}
