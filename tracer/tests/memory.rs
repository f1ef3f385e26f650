//! The bytes rtprof reports for a render: the framebuffer (three f32 a pixel), the
//! BVH (32-byte nodes: two corners of three f32, offset, count and axis; 8-byte
//! primitive references) and the parsed scene.

use tracer::{Bvh, NoCount, RenderOptions, Sampling, ShadingMode, VariantSet, render_variant};

fn flake(depth: u32) -> tracer::Scene {
    let text = tracer::generators::sphereflake(depth).unwrap_or_else(|e| panic!("{e}"));
    tracer::parse_nff(&text, "flake").unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn framebuffer_holds_twelve_bytes_a_pixel() {
    let scene = flake(1);
    let options = RenderOptions::new(10, 7, Sampling::PixelCenters, ShadingMode::Color);
    let out = render_variant::<NoCount>(&scene, &options, &VariantSet::default(), &|_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.rendered.frame.memory_bytes(), 10 * 7 * 12);
    assert_eq!(out.accelerator_bytes, 0, "brute force builds nothing");
}

#[test]
fn bvh_bytes_are_its_nodes_and_primitive_references() {
    let scene = flake(3);
    let stats = Bvh::build(&scene).stats();
    // A binary tree: one interior node fewer than leaves.
    assert_eq!(stats.nodes, 2 * stats.leaves - 1);
    // Nodes of 32 bytes stored in pairs (the root's partner unused), 8 bytes a
    // primitive reference.
    assert_eq!(
        stats.bytes,
        (stats.nodes + 1) * 32 + scene.primitive_count() * 8
    );
    // The variant reports the same structure.
    let options = RenderOptions::new(4, 4, Sampling::PixelCenters, ShadingMode::Color);
    let bvh = VariantSet::parse("bvh").unwrap_or_else(|e| panic!("{e}"));
    let out = render_variant::<NoCount>(&scene, &options, &bvh, &|_| {})
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(out.accelerator_bytes, stats.bytes);
}

#[test]
fn scene_bytes_grow_by_one_sphere_per_sphere() {
    let small = flake(1);
    let large = flake(2);
    let sphere = std::mem::size_of::<tracer::primitives::Sphere>();
    let grown = large.memory_bytes() as i64 - small.memory_bytes() as i64;
    let capacity = (large.spheres.capacity() - small.spheres.capacity()) as i64;
    assert_eq!(grown, capacity * sphere as i64);
    assert!(large.spheres.capacity() >= 91);
}
