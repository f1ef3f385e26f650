//! `reference`: an independent Whitted renderer in f64, the ground truth that the f32
//! tracer and its variants are judged by.
//!
//! It reads the tracer's parsed [`tracer::Scene`] (its numbers converted to f64, the
//! derived f32 values such as axes, lengths and plane normals recomputed from the
//! numbers as written) and renders it by the same rules as the tracer (camera, sampling,
//! shading modes, Whitted shading to depth 5, the self-intersection offset), but with
//! its own maths: every intersection test, the camera and the shading are written here
//! from the formulas, in f64, in forms that do not cancel for small or far objects
//! (Haines et al., *Ray Tracing Gems* ch. 7, and the perpendicular forms for cylinders
//! and cones, [`primitives`]). Its queries walk its own hierarchy of f64 boxes
//! ([`bvh`]), which only culls: the picture is the brute-force walk's over every
//! primitive ([`Walk::BruteForce`]), bit for bit (tested). It shares no code with the
//! tracer's renderer; the output is the tracer's [`tracer::Frame`], so the image
//! metrics compare the two directly.
//! `docs/reference.md` has the maths and the cost.
//!
//! ```
//! use tracer::{RenderOptions, Sampling, ShadingMode};
//! let scene = tracer::parse_nff(
//!     "v\nfrom 0 0 -4\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 8 8\n\
//!      l 2 2 -5\nf 1 0 0 1 0 1 0 1\ns 0 0 0 1\n",
//!     "doc.nff",
//! ).unwrap();
//! let options = RenderOptions::new(8, 8, Sampling::PixelCenters, ShadingMode::Color);
//! let frame = reference::render(&scene, &options, &|_| {}).unwrap();
//! assert_eq!(frame.pixels.len(), 64);
//! ```

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]
// `!(x > y)` is written on purpose: unlike `x <= y` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bvh;
pub mod camera;
pub mod error;
pub mod primitives;
pub mod quadratic;
pub mod ray;
pub mod render;
pub mod scene;
pub mod shading;

pub use error::ReferenceError;
pub use render::render;
pub use scene::RefScene;
pub use shading::Walk;
