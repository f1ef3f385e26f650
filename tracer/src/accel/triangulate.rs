//! Ear clipping of planar outlines into triangles: Embree's triangle meshes and the
//! wide BVH's triangle lanes.
//!
//! rtprof's polygon test hits the plane of the first three vertices, then keeps the
//! hit when its projection onto two coordinate axes (the plane normal's largest
//! component dropped) lies inside the projected outline. The region a ray can hit is
//! therefore the projected outline lifted onto that plane, whatever the written
//! vertices' distance from it. [`lifted_triangles`] triangulates exactly that region:
//! ear clipping in the projection (which also handles concave outlines), then each
//! vertex moved along the dropped axis onto the plane. For a planar polygon this moves
//! vertices by rounding only.
//!
//! rtprof's BVH boxes polygons by their written vertices, which for a non-planar
//! polygon need not hold the lifted region; the boxes here are the lifted vertices'.

use crate::primitives::PlanarOutline;

/// An outline's vertices lifted onto its plane, and its triangles when ear clipping
/// reproduces the crossing test's region.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Lifted {
    pub vertices: Vec<[f32; 3]>,
    /// Indices into `vertices`, each triangle turning as the outline; `None` for a
    /// self-intersecting or zero-area outline (the caller keeps rtprof's test).
    pub triangles: Option<Vec<[u32; 3]>>,
    /// The written vertices projected onto `axes` (exactly the coordinates rtprof's
    /// crossing test compares), where the triangles were clipped.
    pub projected: Vec<[f64; 2]>,
    /// The two coordinate axes kept (the normal's largest component dropped).
    pub axes: [usize; 2],
}

/// The outline lifted onto its plane and triangulated.
pub(crate) fn lift(outline: &PlanarOutline) -> Lifted {
    let n = outline.normal.to_array().map(f64::from);
    let dropped = outline.normal.dominant_axis();
    let (a, b) = ((dropped + 1) % 3, (dropped + 2) % 3);
    let v0 = outline
        .vertices
        .first()
        .map_or([0.0; 3], |v| v.to_array().map(f64::from));
    let mut projected = Vec::with_capacity(outline.vertices.len());
    let mut lifted = Vec::with_capacity(outline.vertices.len());
    for v in &outline.vertices {
        let v = v.to_array().map(f64::from);
        projected.push([v[a], v[b]]);
        // On the plane n·(p - v0) = 0 with p's two kept coordinates; |n[dropped]| is
        // the largest component of a unit normal, at least 1/sqrt(3).
        let mut p = v;
        p[dropped] = v0[dropped] - (n[a] * (v[a] - v0[a]) + n[b] * (v[b] - v0[b])) / n[dropped];
        lifted.push(p.map(|x| x as f32));
    }
    Lifted {
        vertices: lifted,
        triangles: ear_clip(&projected),
        projected,
        axes: [a, b],
    }
}

/// `(q - o) × (r - o)`: twice the signed area of the triangle `o, q, r`.
fn cross(o: [f64; 2], q: [f64; 2], r: [f64; 2]) -> f64 {
    (q[0] - o[0]) * (r[1] - o[1]) - (q[1] - o[1]) * (r[0] - o[0])
}

/// Whether `p` lies in the closed triangle `a, b, c` of orientation `sign`.
fn in_triangle(p: [f64; 2], [a, b, c]: [[f64; 2]; 3], sign: f64) -> bool {
    cross(a, b, p) * sign >= 0.0 && cross(b, c, p) * sign >= 0.0 && cross(c, a, p) * sign >= 0.0
}

/// What clipping a vertex of the ring would do.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Ear {
    /// Not yet looked at since its neighbours last changed.
    Unknown,
    /// Collinear with or repeating a neighbour: it goes without a triangle.
    Collinear,
    /// An ear, with the squared length of the diagonal it cuts.
    Clip(f64),
    /// Reflex, or another vertex lies in its triangle.
    Not,
}

/// The ear status of vertex `b` between `a` and `c` on the ring (`next` walks it).
fn ear_at(points: &[[f64; 2]], next: &[usize], a: usize, b: usize, c: usize, sign: f64) -> Ear {
    let corners = [points[a], points[b], points[c]];
    let turn = cross(corners[0], corners[1], corners[2]) * sign;
    if turn == 0.0 {
        // Collinear or repeated: removing the vertex leaves the region as is.
        return Ear::Collinear;
    }
    if turn < 0.0 {
        return Ear::Not; // reflex
    }
    let mut j = next[c];
    while j != a {
        let p = points[j];
        if !corners.contains(&p) && in_triangle(p, corners, sign) {
            return Ear::Not;
        }
        j = next[j];
    }
    let (dx, dy) = (corners[2][0] - corners[0][0], corners[2][1] - corners[0][1]);
    Ear::Clip(dx * dx + dy * dy)
}

/// Ear clipping of a simple polygon (convex or concave, either orientation) into
/// triangles of indices into `points`, each with the outline's orientation. Collinear
/// and repeated vertices are dropped without a triangle. `None` when no ear is left
/// before the end, or when the triangles' area differs from the outline's: a
/// self-intersecting outline, whose crossing-test (even-odd) region ear clipping
/// cannot give.
pub(crate) fn ear_clip(points: &[[f64; 2]]) -> Option<Vec<[u32; 3]>> {
    let count = points.len();
    if count < 3 || u32::try_from(count).is_err() {
        return None;
    }
    let area2: f64 = (0..count)
        .map(|i| {
            let (p, q) = (points[i], points[(i + 1) % count]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum();
    if area2 == 0.0 || !area2.is_finite() {
        return None;
    }
    let sign = area2.signum();
    // The ring as a linked list, with each vertex's ear status cached: clipping an
    // ear changes only its two neighbours' turns, and removing a vertex never puts a
    // new vertex inside another ear.
    let mut prev: Vec<usize> = (0..count).map(|i| (i + count - 1) % count).collect();
    let mut next: Vec<usize> = (0..count).map(|i| (i + 1) % count).collect();
    let mut status = vec![Ear::Unknown; count];
    let (mut head, mut left) = (0usize, count);
    let mut triangles = Vec::with_capacity(count - 2);
    let mut clipped_area2 = 0.0;
    while left > 3 {
        // The ear of the shortest diagonal (the first in ring order on a tie): on a
        // convex run it clips every other vertex, then every other of the rest, so
        // the triangles nest like a tree's boxes instead of fanning out as slivers.
        let pick = |status: &mut [Ear]| {
            let mut best: Option<(usize, f64)> = None;
            let mut v = head;
            for _ in 0..left {
                if status[v] == Ear::Unknown {
                    status[v] = ear_at(points, &next, prev[v], v, next[v], sign);
                }
                match status[v] {
                    Ear::Collinear => return Some(v),
                    Ear::Clip(key) if best.is_none_or(|(_, k)| key < k) => best = Some((v, key)),
                    _ => {}
                }
                v = next[v];
            }
            best.map(|(v, _)| v)
        };
        let ear = pick(&mut status).or_else(|| {
            // Cached refusals are stale only for degenerate outlines (a repeated
            // vertex blocking an ear): look again with every status fresh.
            status.iter_mut().for_each(|s| *s = Ear::Unknown);
            pick(&mut status)
        });
        let b = ear?;
        let (a, c) = (prev[b], next[b]);
        if status[b] != Ear::Collinear {
            clipped_area2 += cross(points[a], points[b], points[c]) * sign;
            triangles.push([a, b, c].map(|i| i as u32));
        }
        next[a] = c;
        prev[c] = a;
        status[a] = Ear::Unknown;
        status[c] = Ear::Unknown;
        if head == b {
            head = c;
        }
        left -= 1;
    }
    let ring = [head, next[head], next[next[head]]];
    let last = [points[ring[0]], points[ring[1]], points[ring[2]]];
    let turn = cross(last[0], last[1], last[2]) * sign;
    if turn < 0.0 {
        return None;
    }
    if turn > 0.0 {
        clipped_area2 += turn;
        triangles.push([ring[0], ring[1], ring[2]].map(|i| i as u32));
    }
    // Every ear has the outline's orientation, so their areas add up to the outline's
    // exactly when they tile it (up to rounding).
    let tolerance = 1e-9 * area2.abs().max(f64::MIN_POSITIVE);
    ((clipped_area2 - area2.abs()).abs() <= tolerance).then_some(triangles)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vec3::Vec3;

    fn area(points: &[[f64; 2]], tris: &[[u32; 3]]) -> f64 {
        tris.iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| points[i as usize]);
                cross(a, b, c).abs() / 2.0
            })
            .sum()
    }

    #[test]
    fn concave_u_is_tiled_by_six_triangles() {
        let u = [
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 3.0],
            [2.0, 3.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        let tris = ear_clip(&u).unwrap_or_default();
        assert_eq!(tris.len(), 6);
        assert!((area(&u, &tris) - 7.0).abs() < 1e-12);
        // Clockwise input works too.
        let mut cw = u;
        cw.reverse();
        let tris = ear_clip(&cw).unwrap_or_default();
        assert!((area(&cw, &tris) - 7.0).abs() < 1e-12);
    }

    #[test]
    fn a_round_outline_is_cut_into_nested_triangles_not_a_fan() {
        // A regular 64-gon: any triangulation has 62 triangles. A fan from one vertex
        // (or ear clipping that sweeps round the outline) gives about 30 whose boxes
        // cover a quarter of the outline's box or more. Clipping the shortest diagonal
        // first halves the ring level by level: only the last two levels (a square's
        // two triangles and the four below them) are that large.
        let n = 64;
        let ring: Vec<[f64; 2]> = (0..n)
            .map(|i| {
                let a = f64::from(i) * std::f64::consts::TAU / f64::from(n);
                [a.cos(), a.sin()]
            })
            .collect();
        let tris = ear_clip(&ring).unwrap_or_default();
        assert_eq!(tris.len(), 62);
        assert!((area(&ring, &tris) - 32.0 * (std::f64::consts::TAU / 64.0).sin()).abs() < 1e-9);
        let box_area = |t: &[u32; 3]| {
            let p = t.map(|i| ring[i as usize]);
            let span = |k: usize| {
                let (lo, hi) = p.iter().fold((f64::MAX, f64::MIN), |(lo, hi), q| {
                    (lo.min(q[k]), hi.max(q[k]))
                });
                hi - lo
            };
            span(0) * span(1)
        };
        let large = tris.iter().filter(|t| box_area(t) >= 1.0).count();
        assert!(large <= 6, "{large} triangles cover a quarter of the box");
    }

    #[test]
    fn collinear_and_repeated_vertices_are_handled() {
        let square = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let tris = ear_clip(&square).unwrap_or_default();
        // Two triangles, or three when the collinear vertex is a fan's apex.
        assert!(tris.len() == 2 || tris.len() == 3, "{tris:?}");
        assert!((area(&square, &tris) - 4.0).abs() < 1e-12);
        let doubled = [[0.0, 0.0], [2.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        let tris = ear_clip(&doubled).unwrap_or_default();
        assert!((area(&doubled, &tris) - 4.0).abs() < 1e-12, "{tris:?}");
    }

    #[test]
    fn bow_tie_and_degenerate_outlines_are_refused() {
        assert_eq!(
            ear_clip(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]),
            None
        );
        assert_eq!(ear_clip(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]), None);
        // A pentagram: self-intersecting with a non-zero signed area.
        let star: Vec<[f64; 2]> = (0..5)
            .map(|i| {
                let a = f64::from(i) * 4.0 * std::f64::consts::PI / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        assert_eq!(ear_clip(&star), None);
    }

    #[test]
    fn non_planar_vertices_are_lifted_onto_the_plane_of_the_first_three() {
        // Plane z = 0 from the first three; the fourth vertex sits at z = 0.5.
        let outline = PlanarOutline::new(vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.5),
        ])
        .unwrap_or_else(|e| panic!("{e}"));
        let lifted = lift(&outline);
        assert_eq!(lifted.triangles.map(|t| t.len()), Some(2));
        assert_eq!(lifted.vertices[3], [0.0, 1.0, 0.0]);
    }
}
