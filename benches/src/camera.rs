//! Group `camera`: eye-ray generation for a whole 320x240 frame, one benchmark per
//! projection, built as the variants build them:
//! - `perspective` (baseline): [`Camera::ray`] per pixel, two `scale`, two `add`, one
//!   `normalize`;
//! - `orthographic` (`ortho`): the same call on an orthographic camera, no normalize;
//! - `bounded`: [`Camera::row_base`] once per row, then [`Camera::ray_from_eye`] per
//!   pixel (one `scale`, one `add`, one `normalize`), as the renderer walks it.
//!
//! The orthographic camera takes the default grid focus `|at - from|`; the renderer's
//! `ortho` passes the scene's depth instead (a private helper of the pipeline), which
//! changes the grid pitch only, not the work per ray.

use criterion::{Criterion, Throughput};
use std::hint::black_box;
use tracer::{Camera, NoCount, Projection, Sampling, View};

/// Frame size of every benchmark of the group.
pub const WIDTH: u32 = 320;
pub const HEIGHT: u32 = 240;

/// The view of the built-in `balls3` test-bench scene.
pub fn view() -> View {
    let scene = tracer::builtin_scenes::find("balls3")
        .map(|s| s.parse())
        .unwrap_or_else(|| panic!("the built-in scene balls3 is missing"))
        .unwrap_or_else(|e| panic!("{e}"));
    scene.view
}

/// A camera with `projection` for the group's frame, as the renderer sets it up.
pub fn camera(view: &View, projection: Projection) -> Camera {
    Camera::new(
        view,
        WIDTH,
        HEIGHT,
        Sampling::PixelCenters,
        projection,
        None,
        &mut NoCount,
    )
    .unwrap_or_else(|e| panic!("invalid camera: {e}"))
}

/// Every eye ray of the frame by [`Camera::ray`] (perspective or orthographic).
#[inline(never)]
pub fn plain_frame(camera: &Camera) {
    let (columns, rows) = camera.grid();
    for row in 0..rows {
        for column in 0..columns {
            black_box(camera.ray(column, row, &mut NoCount));
        }
    }
}

/// Every eye ray of the frame by the bounded row walk.
#[inline(never)]
pub fn bounded_frame(camera: &Camera) {
    let (columns, rows) = camera.grid();
    for row in 0..rows {
        let base = camera.row_base(row, &mut NoCount);
        for column in 0..columns {
            black_box(camera.ray_from_eye(column, base, &mut NoCount));
        }
    }
}

/// The `camera` group.
pub fn bench_camera(c: &mut Criterion) {
    let view = view();
    let perspective = camera(&view, Projection::Perspective);
    let orthographic = camera(&view, Projection::Orthographic);
    let bounded = camera(&view, Projection::EyeRows);
    let mut group = c.benchmark_group("camera");
    group.throughput(Throughput::Elements(u64::from(WIDTH * HEIGHT)));
    group.bench_function("perspective", |b| {
        b.iter(|| plain_frame(black_box(&perspective)))
    });
    group.bench_function("orthographic", |b| {
        b.iter(|| plain_frame(black_box(&orthographic)))
    });
    group.bench_function("bounded", |b| b.iter(|| bounded_frame(black_box(&bounded))));
    group.finish();
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_bounded_walk_gives_the_perspective_rays() {
        let view = view();
        let (perspective, bounded) = (
            camera(&view, Projection::Perspective),
            camera(&view, Projection::EyeRows),
        );
        assert_eq!(perspective.grid(), (WIDTH, HEIGHT));
        for row in [0, HEIGHT / 2, HEIGHT - 1] {
            let base = bounded.row_base(row, &mut NoCount);
            for column in [0, WIDTH / 3, WIDTH - 1] {
                assert_eq!(
                    bounded.ray_from_eye(column, base, &mut NoCount).plain(),
                    perspective.ray(column, row, &mut NoCount)
                );
            }
        }
    }
}
