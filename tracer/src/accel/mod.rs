//! Closest-hit and occlusion queries over a scene. Brute force is the thesis's software
//! reference; acceleration structures implement the same trait.

mod brute_force;

pub use brute_force::BruteForce;

use crate::counter::Counter;
use crate::ray::{Hit, Ray};

/// Answers the two queries a Whitted tracer asks of its scene.
pub trait Intersector: Sync {
    /// The closest intersection beyond `t_min` (counts one `calls.intersect`).
    fn closest_hit<C: Counter>(&self, ray: &Ray, t_min: f32, c: &mut C) -> Option<Hit>;

    /// Whether anything lies in `(t_min, t_max)` (a shadow ray; counts one
    /// `calls.intersect`). May stop at the first blocker.
    fn occluded<C: Counter>(&self, ray: &Ray, t_min: f32, t_max: f32, c: &mut C) -> bool;
}
