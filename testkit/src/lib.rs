//! `testkit`: fixtures for tests of the results and their reports, kept out of
//! library code. [`sample_results`] is a realistic synthetic suite run;
//! [`write_sample_files`] writes the images and texts it refers to; [`far_sphere`] makes
//! the small far spheres that f32 intersection tests get wrong, with their analytic pixel
//! counts. Used only as a dev-dependency.

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod far_sphere;
pub mod files;
pub mod sample;
pub mod temp_dir;

pub use files::{TINY_PNG, referenced_files, write_sample_files};
pub use sample::{SAMPLE_VARIANTS, sample_results};
pub use temp_dir::TempDir;
