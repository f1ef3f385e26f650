//! `tracer`: an instrumented Whitted ray tracer for NFF scenes.
//!
//! It parses NFF scenes ([`nff`]), builds primitives ([`primitives`]), shoots eye rays
//! ([`camera`]), answers intersection queries ([`accel`]), shades under the SPD rules
//! ([`shading`]) and renders in parallel ([`mod@render`]). Every vector operation, square
//! root, power, intersection test and ray is counted exactly through the [`counter`]
//! layer, whose counters are declared once in its table ([`counter::table`]); with
//! [`NoCount`] the counting compiles away, so one binary renders counted and uncounted.
//! The optimization variants (their set, dispatch, fast square roots, eye-space walk and
//! diffuse forms) live in [`variants`]; [`render_variant`] renders with any of them.
//! This crate depends on no other workspace crate.
//!
//! ```
//! use tracer::{render, BruteForce, Count, RenderMethod, RenderOptions};
//! let scene = tracer::parse_nff(
//!     "v\nfrom 0 0 -4\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 8 8\n\
//!      l 2 2 -5\nf 1 0 0 1 0 1 0 1\ns 0 0 0 1\n",
//!     "doc.nff",
//! ).unwrap();
//! let accel = BruteForce::new(&scene);
//! let options = RenderOptions::for_scene(&scene);
//! let out = render::<Count, _>(&scene, &accel, &options, &RenderMethod::default(), &|_| {}).unwrap();
//! let counts = out.counts().unwrap();
//! assert_eq!(counts.rays.primary, 64);
//! assert_eq!(counts.tests.sphere.tests, counts.calls.intersect); // one sphere per query
//! ```

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]
// `!(x > y)` is written on purpose throughout: unlike `x <= y` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Tests compute expected values independently, outside the counting layer (the
// non-test build is still checked by clippy --all-targets).
#![cfg_attr(test, allow(clippy::disallowed_methods))]

pub mod accel;
pub mod builtin_scenes;
pub mod camera;
pub mod color;
pub mod counter;
pub mod fuzz_check;
pub mod generators;
mod huge_pages;
pub mod image_io;
pub mod nff;
pub mod nff_writer;
pub mod pixel_stats;
pub mod pov_writer;
pub mod primitives;
pub mod ray;
pub mod render;
pub mod scene;
pub mod shading;
pub mod tachyon_writer;
pub mod variants;
pub mod vec3;
pub mod work_model;

pub use accel::{
    BruteForce, Bvh, BvhBuilder, BvhShape, BvhStats, Intersector, Simd, WideBvh, WideBvhStats,
};
#[cfg(feature = "embree")]
pub use accel::{Embree, EmbreeCode, EmbreeError, EmbreeMode, EmbreePackets, NativeWidths};
pub use camera::{Camera, Projection, Sampling};
pub use color::Rgb;
pub use counter::{
    COUNTERS, Count, Counter, CounterDef, Counts, NoCount, Phase, Phased, RayCounts, Stat,
    phase_calls, phase_names, phase_stack_key,
};
pub use nff::{
    Limit, LimitError, Limits, LoadError, NffError, load_nff, load_nff_with_limits, parse_nff,
};
pub use nff_writer::{scene_to_nff, write_scene};
pub use pixel_stats::SampleStats;
pub use pov_writer::scene_to_pov;
pub use ray::{Hit, HitBound, PrimKind, PrimRef, Ray};
pub use render::{
    Frame, NEVER_STOP, RenderError, RenderMethod, RenderOptions, Rendered, render, render_until,
};
pub use scene::{Light, Material, Scene, SurfaceTerms, View};
pub use shading::{MAX_DEPTH, RayLog, ShadingMode};
pub use tachyon_writer::{scene_to_tachyon, scene_to_tachyon_at};
pub use variants::{
    Accelerator, DiffuseForm, RenderWith, SqrtMethod, Variant, VariantConfig, VariantError,
    VariantRender, VariantSet, render_variant, render_variant_until, render_variant_with,
};
pub use vec3::Vec3;
