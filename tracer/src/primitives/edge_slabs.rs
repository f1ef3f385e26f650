//! Edge slabs: the crossing test of an outline with many vertices without walking
//! every edge. Only an edge whose end points lie on both sides of the query point's
//! `v` can toggle the crossing parity, so the outline's `v` range is cut into slabs and
//! each slab lists the edges that reach into it; a query walks its slab's edges only.
//! The gear faces of SPD `gears` have 144 vertices, of which a point's slab holds a
//! handful.
//!
//! The result is the full walk's, bit for bit: the slab of `v` holds every edge with
//! `min v < v ≤ max v` (the slab index grows with `v`), each such edge runs the same
//! arithmetic as in the full walk, and the other edges of the slab toggle nothing.

/// Outlines with fewer vertices walk every edge (the slab lookup would cost more).
pub const MIN_VERTICES: usize = 16;

/// The edges of an outline sorted into slabs of `v`.
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeSlabs {
    /// The lowest and highest `v` of the outline.
    lo: f32,
    hi: f32,
    /// Slabs per unit of `v`.
    scale: f32,
    /// Slab `s` holds `edges[start[s]..start[s + 1]]`.
    start: Vec<u32>,
    /// Edge `i` joins vertex `i - 1` (vertex `n - 1` for `i = 0`) to vertex `i`.
    edges: Vec<u32>,
}

impl EdgeSlabs {
    /// Sorts the edges of `projected` into slabs (about one slab per two edges);
    /// `None` for small or degenerate outlines.
    pub fn new(projected: &[[f32; 2]]) -> Option<Self> {
        let n = projected.len();
        if n < MIN_VERTICES {
            return None;
        }
        let (lo, hi) = projected
            .iter()
            .fold((f32::INFINITY, f32::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[1]), hi.max(p[1]))
            });
        let slabs = (n / 2).clamp(1, 256);
        let scale = slabs as f32 / (hi - lo);
        if !(scale.is_finite() && scale > 0.0) {
            return None;
        }
        let mut out = Self {
            lo,
            hi,
            scale,
            start: vec![0; slabs + 1],
            edges: Vec::new(),
        };
        let spans: Vec<(usize, usize)> = (0..n)
            .map(|i| {
                let (a, b) = (projected[(i + n - 1) % n][1], projected[i][1]);
                (out.slab(a.min(b)), out.slab(a.max(b)))
            })
            .collect();
        // Counting sort: sizes, offsets, then the edges in their slabs.
        let mut sizes = vec![0u32; slabs];
        for &(first, last) in &spans {
            for size in &mut sizes[first..=last] {
                *size += 1;
            }
        }
        for (s, size) in sizes.iter().enumerate() {
            out.start[s + 1] = out.start[s] + size;
        }
        let mut next = out.start.clone();
        out.edges = vec![0; out.start[slabs] as usize];
        for (i, &(first, last)) in spans.iter().enumerate() {
            for at in &mut next[first..=last] {
                out.edges[*at as usize] = i as u32;
                *at += 1;
            }
        }
        Some(out)
    }

    /// The slab of `v` (clamped to the outline's range; never decreasing in `v`).
    fn slab(&self, v: f32) -> usize {
        let slabs = self.start.len() - 1;
        (((v - self.lo) * self.scale).max(0.0) as usize).min(slabs - 1)
    }

    /// The edges that may cross the line `v = q[1]`: none when `q` lies outside the
    /// outline's `v` range (then every end point is on one side).
    #[inline]
    pub fn edges_near(&self, v: f32) -> &[u32] {
        if !(v > self.lo && v <= self.hi) {
            return &[];
        }
        let s = self.slab(v);
        &self.edges[self.start[s] as usize..self.start[s + 1] as usize]
    }

    /// Bytes on the heap.
    pub fn heap_bytes(&self) -> usize {
        (self.start.capacity() + self.edges.capacity()) * std::mem::size_of::<u32>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::primitives::PlanarOutline;
    use crate::vec3::Vec3;

    /// A star-shaped outline of `n` vertices in the z = 0 plane with random radii
    /// (concave), a few vertices sharing one `v` (horizontal edges).
    fn star(n: usize, seed: u32) -> PlanarOutline {
        let mut state = seed;
        let mut next = move || {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1u32 << 24) as f32
        };
        let vertices = (0..n)
            .map(|i| {
                let angle = i as f32 / n as f32 * std::f32::consts::TAU;
                let r = 1.0 + 2.0 * next();
                let y = if i % 7 == 3 { 0.5 } else { r * angle.sin() };
                Vec3::new(r * angle.cos(), y, 0.0)
            })
            .collect();
        PlanarOutline::new(vertices).unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn slabs_give_the_full_walks_answer_everywhere() {
        let mut state = 5u32;
        let mut next = move || {
            state = state.wrapping_mul(22_695_477).wrapping_add(1);
            (state >> 8) as f32 / (1u32 << 24) as f32 * 8.0 - 4.0
        };
        for (n, seed) in [(16, 1), (17, 2), (40, 3), (144, 4), (400, 5)] {
            let outline = star(n, seed);
            let mut inside = 0;
            for _ in 0..4000 {
                let q = [next(), next()];
                let fast = outline.contains(q);
                assert_eq!(fast, outline.contains_by_every_edge(q), "{n} {q:?}");
                inside += usize::from(fast);
            }
            // Points on the vertices' own v (the half-open rule), on the range's ends.
            for v in [0.5, -3.0, 3.0, 0.0] {
                for u in [-2.0, 0.0, 0.3, 2.5] {
                    let q = [u, v];
                    assert_eq!(outline.contains(q), outline.contains_by_every_edge(q));
                }
            }
            assert!(
                inside > 400,
                "{n}: the random points must fall inside too: {inside}"
            );
        }
    }

    #[test]
    fn small_outlines_have_no_slabs_and_every_edge_sits_in_the_slabs_it_spans() {
        assert!(EdgeSlabs::new(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]).is_none());
        // A flat outline (all v equal) has no slab width: walked in full.
        assert!(EdgeSlabs::new(&[[0.0, 1.0]; 20]).is_none());
        let square: Vec<[f32; 2]> = (0..16)
            .map(|i| {
                let t = i as f32 / 4.0;
                match i / 4 {
                    0 => [t, 0.0],
                    1 => [1.0, t - 1.0],
                    2 => [3.0 - t, 1.0],
                    _ => [0.0, 4.0 - t],
                }
            })
            .collect();
        let slabs = EdgeSlabs::new(&square).unwrap_or_else(|| panic!("16 vertices"));
        // 8 slabs of height 1/8: the two vertical sides' 8 edges (each 1/4 high) lie in
        // 2 or 3 slabs; the 8 horizontal edges in the first or last slab.
        assert_eq!(slabs.start.len(), 9);
        let near = slabs.edges_near(0.5);
        assert!(near.len() >= 2 && near.len() <= 4, "{near:?}");
        assert!(slabs.edges_near(-0.1).is_empty() && slabs.edges_near(1.1).is_empty());
        assert!(
            slabs.edges_near(0.0).is_empty(),
            "v = lo: every vertex is above"
        );
    }
}
