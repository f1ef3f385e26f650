//! Where and how a scene is rendered: the scene, its options, the thread pools and
//! the stop flag, shared by every job that renders (variants, clocked passes,
//! references, pixel maps, the BVH study).

use std::sync::atomic::AtomicBool;

use tracer::{RenderOptions, Scene};

/// Where and how to render.
pub struct RenderSetup<'a> {
    pub scene: &'a Scene,
    /// The scene's name in messages.
    pub name: &'a str,
    pub options: &'a RenderOptions,
    pub pool: &'a rayon::ThreadPool,
    /// The pool of the counted renders: counts are the same on any number of threads,
    /// so a scene timed on one thread is still counted on all of them.
    pub counting_pool: &'a rayon::ThreadPool,
    pub stop: &'a AtomicBool,
}
