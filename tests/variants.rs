//! The optimization variants against the baseline on the SPD scenes balls and rings:
//! which must keep the picture and the ray counts, and what the others change.

use analysis::{RgbImage, compare};
use std::path::PathBuf;
use tracer::{
    BruteForce, Bvh, BvhBuilder, Camera, Count, Counts, Frame, Intersector, NoCount, PrimKind,
    PrimRef, Projection, Ray, RenderOptions, Sampling, Scene, ShadingMode, Stat, VariantSet,
    WideBvh, load_nff, render_variant, vec3::Vec3,
};

fn spd(name: &str) -> Scene {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../shared/spd")
        .join(format!("{name}.nff"));
    load_nff(&path).unwrap_or_else(|e| panic!("{e} (shared/ must sit beside the project)"))
}

fn render(scene: &Scene, variants: &str, options: &RenderOptions) -> (Frame, Counts) {
    let set = VariantSet::parse(variants).unwrap_or_else(|e| panic!("{e}"));
    let out = render_variant::<Count>(scene, options, &set, &|_| {})
        .unwrap_or_else(|e| panic!("{variants}: {e}"));
    let counts = out.rendered.counts().unwrap_or_default();
    (out.rendered.frame, counts)
}

fn image(frame: &Frame) -> RgbImage {
    RgbImage::new(frame.width, frame.height, frame.to_rgb8()).unwrap_or_else(|e| panic!("{e}"))
}

fn small(sampling: Sampling, mode: ShadingMode) -> RenderOptions {
    RenderOptions::new(36, 30, sampling, mode)
}

#[test]
fn bvh_simd_and_bounded_keep_the_baseline_picture_and_ray_counts() {
    for name in ["balls", "rings"] {
        let scene = spd(name);
        let options = small(Sampling::PixelCenters, ShadingMode::Color);
        let (base_frame, base) = render(&scene, "baseline", &options);
        assert!(
            base.rays.primary_hit > 0 && base.rays.shadow > 0,
            "{name}: {base:?}"
        );
        for variant in ["bvh", "simd", "bounded", "bvh,bounded"] {
            let (frame, counts) = render(&scene, variant, &options);
            let m = compare(&image(&base_frame), &image(&frame)).unwrap_or_else(|e| panic!("{e}"));
            assert!(m.rms <= 0.5, "{name} {variant}: RMS {}", m.rms);
            assert_eq!(counts.rays, base.rays, "{name} {variant}");
        }
    }
}

#[test]
fn wide_bvh_keeps_the_baseline_picture_and_ray_counts_on_all_twelve_spd_scenes() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/spd");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| {
            let name = e.ok()?.file_name().to_string_lossy().into_owned();
            Some(name.strip_suffix(".nff")?.to_string())
        })
        .collect();
    names.sort();
    assert_eq!(names.len(), 12, "{names:?}");
    let options = RenderOptions::new(24, 20, Sampling::PixelCenters, ShadingMode::Color);
    for name in &names {
        let scene = spd(name);
        let (base_frame, base) = render(&scene, "baseline", &options);
        let (bvh_frame, _) = render(&scene, "bvh", &options);
        let (frame, counts) = render(&scene, "bvh+simd", &options);
        let m = compare(&image(&base_frame), &image(&frame)).unwrap_or_else(|e| panic!("{e}"));
        assert!(m.rms <= 0.5, "{name}: RMS {}", m.rms);
        assert_eq!(counts.rays, base.rays, "{name}");
        if scene.polygons.len() + scene.patches.len() <= 1 {
            // Quadrics and at most a floor: the same tests on the same leaves as the
            // binary tree, the same floats.
            assert_eq!(frame, bvh_frame, "{name}: bvh+simd differs from bvh");
        } else {
            // Outlines as triangles: the polygon's plane test gives the same distance,
            // the edges differ only by rounding at silhouettes.
            assert!(counts.tests.triangle.tests > 0, "{name}");
            // Every outline of the SPD scenes is triangulated, the gears' 144-gon faces
            // included: no polygon test is left.
            assert_eq!(counts.tests.polygon.tests, 0, "{name}");
            assert_eq!(counts.tests.patch.tests, 0, "{name}");
            let m = compare(&image(&bvh_frame), &image(&frame)).unwrap_or_else(|e| panic!("{e}"));
            assert!(m.rms <= 0.5, "{name}: RMS {} against bvh", m.rms);
        }
        assert!(counts.accel.nodes_visited > 0 && counts.accel.lanes_issued > 0);
        // Packets of eye rays (and of their shadow rays) find each ray's own closest hit
        // and blockers: the same frame and rays. Their box and leaf work differs (a
        // packet's order is not each ray's own), so only its presence is checked here;
        // the per-ray counts are checked in `tracer::accel::bvh::packet`.
        let (packet_frame, packets) = render(&scene, "bvh+simd+packets", &options);
        assert_eq!(packet_frame, frame, "{name}: packets differ from bvh+simd");
        assert_eq!(packets.rays, counts.rays, "{name}");
        assert!(packets.accel.nodes_visited > 0 && packets.accel.lanes_issued > 0);
    }
}

#[test]
fn secondary_ray_packets_keep_each_rays_picture_and_counts_in_every_mode_and_depth() {
    // Reflection and refraction rays traced a level at a time in packets: mount has
    // transmitters (refraction, total internal reflection), gears and balls mirrors. The
    // gray mode takes the luminance of the whole sample only; a shallower tree stops the
    // packets early. Each must give the single-ray picture and rays exactly.
    for name in ["mount", "gears", "balls"] {
        let scene = spd(name);
        for (mode, depth) in [
            (ShadingMode::Gray, 5),
            (ShadingMode::Color, 2),
            (ShadingMode::Color, 3),
        ] {
            let mut options = RenderOptions::new(32, 24, Sampling::PixelCenters, mode);
            options.max_depth = depth;
            let (frame, counts) = render(&scene, "bvh+simd", &options);
            let (packet_frame, packets) = render(&scene, "bvh+simd+packets", &options);
            assert_eq!(packet_frame, frame, "{name} {mode:?} depth {depth}");
            assert_eq!(packets.rays, counts.rays, "{name} {mode:?} depth {depth}");
            assert!(counts.rays.reflection > 0, "{name}: the scene has mirrors");
            if name == "mount" && depth > 2 {
                assert!(counts.rays.refraction > 0, "mount refracts");
            }
        }
    }
}

#[test]
fn every_accelerator_breaks_a_tie_in_scene_order_as_brute_force_does() {
    // This eye ray of gears at 256x256 (pixel 115, 128) meets a gear's face (polygon 1)
    // and a tooth's side (polygon 147) at the same distance, on their shared edge. Brute
    // force tests in scene order and keeps the first of equal hits; the wide BVH meets
    // the side's triangles first, and must still answer polygon 1.
    let scene = spd("gears");
    let ray = Ray {
        origin: Vec3::new(-1.1, -2.1, 2.6),
        dir: Vec3::new(0.2758737, 0.6141141, -0.7394306),
    };
    let polygon = |index| PrimRef {
        kind: PrimKind::Polygon,
        index,
    };
    let t_at =
        |index: usize| scene.polygons[index].intersect(&ray, 0.0, f32::INFINITY, &mut NoCount);
    let (face, side) = (t_at(1), t_at(147));
    assert!(
        face.is_some() && face == side,
        "not a tie: {face:?} {side:?}"
    );
    let brute = BruteForce::new(&scene).closest_hit(&ray, 0.0, &mut NoCount);
    let bvh = Bvh::build(&scene).closest_hit(&ray, 0.0, &mut NoCount);
    let wide = WideBvh::build_with(&scene, BvhBuilder::default());
    let mut hits = [None];
    wide.closest_hits(&[ray], &mut hits, &mut [NoCount]);
    assert_eq!(brute.map(|h| h.prim), Some(polygon(1)));
    assert_eq!(bvh, brute);
    assert_eq!(wide.closest_hit(&ray, 0.0, &mut NoCount), brute);
    assert_eq!(hits[0], brute, "packet path");
}

#[test]
fn bvh_moves_the_work_from_primitive_tests_to_node_visits() {
    let scene = spd("balls");
    let options = small(Sampling::PixelCenters, ShadingMode::Color);
    let (_, base) = render(&scene, "baseline", &options);
    let (_, bvh) = render(&scene, "bvh", &options);
    assert_eq!(base.accel.nodes_visited, 0);
    assert!(bvh.accel.nodes_visited > 0 && bvh.accel.leaves_visited > 0);
    // 7381 spheres per query by brute force; a few per query through the tree.
    assert!(
        bvh.tests.sphere.tests * 100 < base.tests.sphere.tests,
        "{} vs {}",
        bvh.tests.sphere.tests,
        base.tests.sphere.tests
    );
    assert!(bvh.accel.nodes_visited > bvh.tests.sphere.tests / 4);
}

#[test]
fn ortho_eye_rays_need_no_normalization() {
    for name in ["balls", "rings"] {
        let scene = spd(name);
        let (w, h) = (24, 20);
        let normalizations = |projection| {
            let mut c = Count::default();
            let camera = Camera::new(
                &scene.view,
                w,
                h,
                Sampling::PixelCenters,
                projection,
                None,
                &mut c,
            )
            .unwrap_or_else(|e| panic!("{e}"));
            let setup = c.get(Stat::Normalize);
            for row in 0..h {
                for column in 0..w {
                    camera.ray(column, row, &mut c);
                }
            }
            c.get(Stat::Normalize) - setup
        };
        assert_eq!(normalizations(Projection::Perspective), u64::from(w * h));
        assert_eq!(normalizations(Projection::Orthographic), 0, "{name}");
        // Whole render: every normalization left belongs to shading.
        let options = small(Sampling::PixelCenters, ShadingMode::Color);
        let (_, ortho) = render(&scene, "ortho", &options);
        assert_eq!(ortho.rays.primary, 36 * 30);
    }
}

#[test]
fn pixel_avg_traces_half_the_eye_rays() {
    for name in ["balls", "rings"] {
        let scene = spd(name);
        let options = small(Sampling::PixelCenters, ShadingMode::Color);
        let (frame, counts) = render(&scene, "pixel-avg", &options);
        assert_eq!(counts.rays.primary, 36 * 30 / 2, "{name}");
        assert!(frame.is_finite());
        // SPD corners: a 37x31 grid, odd in both directions, traces the ceiling half.
        let spd_options = small(Sampling::SpdCorners, ShadingMode::Color);
        let (_, counts) = render(&scene, "pixel-avg", &spd_options);
        assert_eq!(counts.rays.primary, (37u64 * 31).div_ceil(2));
    }
}

#[test]
fn no_rsqrt_shading_takes_no_root_in_the_sphere_diffuse_term() {
    for name in ["balls", "rings"] {
        let scene = spd(name);
        // The hardware's diffuse-only shading: eye ray, hit body, diffuse term.
        let options = small(Sampling::PixelCenters, ShadingMode::DiffuseOnly);
        let (_, base) = render(&scene, "baseline", &options);
        let (_, free) = render(&scene, "no-rsqrt-shading", &options);
        assert_eq!(free.rays, base.rays);
        // Same eye rays and tests, so every root left is an intersection root.
        assert_eq!(free.ops.sqrt, base.ops.sqrt, "{name}");
        // Lambert normalizes the normal and the light vector of each sphere hit; the
        // squared form neither.
        let saved = base.ops.normalize - free.ops.normalize;
        assert!(saved > 0 && saved % 2 == 0, "{name}: {saved}");
        assert!(free.ops.normalize >= free.rays.primary);
    }
}

#[test]
fn approximate_variants_render_finite_pictures() {
    let scene = spd("rings");
    let options = small(Sampling::PixelCenters, ShadingMode::Color);
    for variant in [
        "fast-sqrt",
        "fast-sqrt-tuned",
        "fast-sqrt-newton",
        "ortho",
        "pixel-avg",
        "no-rsqrt-shading",
        "bvh,fast-sqrt,ortho,pixel-avg,no-rsqrt-shading",
    ] {
        let set = VariantSet::parse(variant).unwrap_or_else(|e| panic!("{e}"));
        let out = render_variant::<NoCount>(&scene, &options, &set, &|_| {})
            .unwrap_or_else(|e| panic!("{variant}: {e}"));
        assert!(out.rendered.frame.is_finite(), "{variant}");
    }
}
