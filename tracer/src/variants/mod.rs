//! The optimization variants of the thesis's chapter 8.3, in one place:
//! - [`set`]: the named variants, their combinations ([`VariantSet`]) and what a
//!   combination chooses ([`VariantConfig`]: square root, intersection structure,
//!   projection, diffuse form, checkerboard sampling);
//! - [`dispatch`]: [`render_variant`], which turns those choices into types and a
//!   [`RenderMethod`](crate::RenderMethod) and renders;
//! - [`fast_sqrt`]: the bit-trick square roots of the `fast-sqrt*` variants and the
//!   counter adaptor that makes every root in the tracer use one;
//! - [`eye_space`]: the `bounded` variant's scene in eye-centred coordinates;
//! - [`diffuse`]: the sqrt-free diffuse forms of `no-rsqrt-shading`.
//!
//! The intersection structures of `simd` and `bvh` are the tracer's own
//! ([`crate::accel`]); the `ortho` and `bounded` eye rays are the camera's
//! ([`crate::camera`]).

pub mod diffuse;
pub mod dispatch;
pub mod eye_space;
pub mod fast_sqrt;
pub mod set;

pub use diffuse::DiffuseForm;
pub use dispatch::{
    RenderWith, VariantRender, render_variant, render_variant_until, render_variant_with,
};
pub use set::{Accelerator, SqrtMethod, Variant, VariantConfig, VariantError, VariantSet};
