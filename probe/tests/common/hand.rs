//! The C fixture's counts by hand (`tests/c/spheres.c`), independent of the fixture's
//! code: eye rays and sphere tests from the size (W·H and W·H·32 a frame), hits by an
//! f64 ray-sphere test of another form (closest approach, not the fixture's quadratic)
//! on the scene the fixture prints. A file of its own so that other tests
//! (`tests/record_probe.rs` of the workspace) check the same numbers with it.

#![allow(dead_code)] // each test file uses a part

/// The fixture's spheres.
pub const SPHERES: u64 = 32;

/// The scene the fixture prints (`spheres scene`: "sphere x y z r", one a line):
/// (centre, radius) per sphere.
pub fn parse_scene(text: &str) -> Vec<([f64; 3], f64)> {
    text.lines()
        .map(|l| {
            let v: Vec<f64> = l
                .split(' ')
                .skip(1)
                .map(|x| x.parse().unwrap_or_else(|e| panic!("{l}: {e}")))
                .collect();
            ([v[0], v[1], v[2]], v[3])
        })
        .collect()
}

/// Eye rays that hit a sphere, and ray-sphere pairs that hit, for a W x H image of
/// `spheres`: the camera of the fixture's description (origin, -z, pixel centres, 90
/// degrees across), each pair by its closest approach to the sphere's centre.
pub fn expected_hits(spheres: &[([f64; 3], f64)], width: u32, height: u32) -> (u64, u64) {
    let (mut rays_hit, mut hits) = (0, 0);
    let aspect = f64::from(height) / f64::from(width);
    for j in 0..height {
        for i in 0..width {
            let x = 2.0 * (f64::from(i) + 0.5) / f64::from(width) - 1.0;
            let y = (1.0 - 2.0 * (f64::from(j) + 0.5) / f64::from(height)) * aspect;
            let length = (x * x + y * y + 1.0).sqrt();
            let d = [x / length, y / length, -1.0 / length];
            let mut any = false;
            for (c, r) in spheres {
                let along = c[0] * d[0] + c[1] * d[1] + c[2] * d[2];
                let square = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
                let miss2 = square - along * along; // squared distance of closest approach
                assert!(
                    (miss2 - r * r).abs() > 1e-6,
                    "pixel ({i}, {j}) grazes a sphere: the count would depend on rounding"
                );
                // The far intersection in front of the eye (the eye is outside).
                if miss2 < r * r && along + (r * r - miss2).sqrt() > 1e-9 {
                    hits += 1;
                    any = true;
                }
            }
            rays_hit += u64::from(any);
        }
    }
    (rays_hit, hits)
}
