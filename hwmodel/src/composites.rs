//! Composite operators: the vector operations of table 7, as subgraphs of IP cores.
//!
//! - dot product: three multipliers and an adder chain `(x + y) + z`: 5 + 7 + 7 = 19
//!   cycles (table 7: 19). The z product waits 7 cycles for `x + y`.
//! - vector × scalar: three multipliers with registered ports, 7 cycles (table 7: 7;
//!   see the `multiply_registered` row of the library for why).
//! - vector add/sub: three adders, 7 cycles (table 7: 7).
//! - normalize: `v · rsqrt(v·v)`: dot (19) + inverse square root (26) + three bare
//!   multipliers (5) = 50 cycles (table 7: 50); `v` waits 45 cycles for its scale.
//!
//! Table 7's standalone dot-product row holds more than these parts: 28 multiplier
//! elements (4 × 7) and 3947 LEs ≈ 4 multipliers + 3 adders (4·301 + 3·906 = 3922).
//! It is a four-lane dot product (x, y, z, w) with a balanced tree, same 19 cycles.
//! Every block of table 8 uses the three-lane form: normalize's 76 multiplier elements
//! are 34 (rsqrt) + 6 × 7, i.e. three multipliers in its dot product, not four.
//! [`dot4`] builds the four-lane form so the difference can be shown.

use crate::graph::{AddSubMode, Graph, NodeId};
use crate::library::OpKind;

/// Three node ids: x, y, z.
pub type Vec3Node = [NodeId; 3];

/// A vector input that changes with every item.
pub fn vector_input(g: &mut Graph, label: &str) -> Vec3Node {
    ["x", "y", "z"].map(|c| g.input(&format!("{label}.{c}")))
}

/// A vector held for `hold` cycles.
pub fn vector_input_held(g: &mut Graph, label: &str, hold: u32) -> Vec3Node {
    ["x", "y", "z"].map(|c| g.input_held(&format!("{label}.{c}"), 32, hold))
}

/// A vector frame constant.
pub fn vector_constant(g: &mut Graph, label: &str) -> Vec3Node {
    ["x", "y", "z"].map(|c| g.constant(&format!("{label}.{c}")))
}

/// Marks the three components as outputs.
pub fn vector_output(g: &mut Graph, v: Vec3Node) {
    for c in v {
        g.output(c);
    }
}

/// `a · b`, three lanes: 19 cycles.
pub fn dot(g: &mut Graph, a: Vec3Node, b: Vec3Node, label: &str) -> NodeId {
    let p = [0, 1, 2].map(|i| g.op(OpKind::Multiply, &[a[i], b[i]], &format!("{label}:prod{i}")));
    let xy = g.add(p[0], p[1], &format!("{label}:x+y"));
    g.add(xy, p[2], label)
}

/// `a · b` with four lanes and a balanced adder tree (table 7's standalone module).
pub fn dot4(g: &mut Graph, a: [NodeId; 4], b: [NodeId; 4], label: &str) -> NodeId {
    let p =
        [0, 1, 2, 3].map(|i| g.op(OpKind::Multiply, &[a[i], b[i]], &format!("{label}:prod{i}")));
    let lo = g.add(p[0], p[1], &format!("{label}:x+y"));
    let hi = g.add(p[2], p[3], &format!("{label}:z+w"));
    g.add(lo, hi, label)
}

/// `v × s` (registered multipliers): 7 cycles.
pub fn vector_scale(g: &mut Graph, v: Vec3Node, s: NodeId, label: &str) -> Vec3Node {
    [0, 1, 2].map(|i| {
        g.op(
            OpKind::MultiplyRegistered,
            &[v[i], s],
            &format!("{label}.{}", axis(i)),
        )
    })
}

/// `a + b` or `a − b` per component (`mode`; the same IP core): 7 cycles.
pub fn vector_add_sub(
    g: &mut Graph,
    mode: AddSubMode,
    a: Vec3Node,
    b: Vec3Node,
    label: &str,
) -> Vec3Node {
    [0, 1, 2].map(|i| g.add_sub(mode, a[i], b[i], &format!("{label}.{}", axis(i))))
}

/// `v / |v|` by the inverse square root: 50 cycles.
pub fn normalize(g: &mut Graph, v: Vec3Node, label: &str) -> Vec3Node {
    let len_sq = dot(g, v, v, &format!("{label}:|v|²"));
    let inv_len = g.op(OpKind::InvSqrt, &[len_sq], &format!("{label}:rsqrt"));
    [0, 1, 2].map(|i| {
        g.op(
            OpKind::Multiply,
            &[v[i], inv_len],
            &format!("{label}.{}", axis(i)),
        )
    })
}

/// Per-component select between two vectors by a flag, `flag ? b : a` (no latency).
pub fn vector_select(
    g: &mut Graph,
    flag: NodeId,
    a: Vec3Node,
    b: Vec3Node,
    label: &str,
) -> Vec3Node {
    [0, 1, 2].map(|i| g.select(flag, a[i], b[i], &format!("{label}.{}", axis(i))))
}

fn axis(i: usize) -> &'static str {
    ["x", "y", "z"][i]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::library::Library;

    fn standalone(build: impl Fn(&mut Graph)) -> crate::graph::Schedule {
        let mut g = Graph::new();
        build(&mut g);
        g.schedule(&Library::cyclone_iv_e())
    }

    #[test]
    fn dot_product_is_19_cycles_with_one_balancing_word() {
        let s = standalone(|g| {
            let a = vector_input(g, "a");
            let b = vector_input(g, "b");
            let d = dot(g, a, b, "a·b");
            g.output(d);
        });
        assert_eq!(s.latency, 5 + 7 + 7);
        // The z product waits 7 cycles for x + y: 7 × 32 register bits.
        assert_eq!(s.balancing.regs, 7 * 32);
        assert_eq!(s.operators.le, 3 * 301 + 2 * 906);
        assert_eq!(s.resources().mult, 21);
    }

    #[test]
    fn four_lane_dot_product_is_balanced_and_matches_table_7_multipliers() {
        let s = standalone(|g| {
            let a = [0, 1, 2, 3].map(|i| g.input(&format!("a{i}")));
            let b = [0, 1, 2, 3].map(|i| g.input(&format!("b{i}")));
            let d = dot4(g, a, b, "a·b");
            g.output(d);
        });
        assert_eq!(s.latency, 19);
        assert_eq!(s.balancing, Default::default());
        assert_eq!(s.resources().mult, 28);
        assert_eq!(s.resources().le, 4 * 301 + 3 * 906);
    }

    #[test]
    fn vector_scale_add_and_normalize_latencies_follow_table_7() {
        let scale = standalone(|g| {
            let v = vector_input(g, "v");
            let s = g.input("s");
            let r = vector_scale(g, v, s, "v·s");
            vector_output(g, r);
        });
        assert_eq!(scale.latency, 7);
        assert_eq!(scale.resources().mult, 21);
        let add = standalone(|g| {
            let a = vector_input(g, "a");
            let b = vector_input(g, "b");
            let r = vector_add_sub(g, AddSubMode::Add, a, b, "a+b");
            vector_output(g, r);
        });
        assert_eq!(add.latency, 7);
        assert_eq!(add.resources().le, 3 * 906);
        let norm = standalone(|g| {
            let v = vector_input(g, "v");
            let r = normalize(g, v, "n");
            vector_output(g, r);
        });
        // Table 7's 50 = 19 + 26 + 5 with ALTFP_INV_SQRT's 26; the library's inverse
        // square root is the RTL's (28, issue 38), which normalize carries.
        let inv_sqrt = Library::cyclone_iv_e().op(OpKind::InvSqrt).latency;
        assert_eq!(norm.latency, 19 + inv_sqrt + 5);
        assert_eq!(norm.resources().mult, 3 * 7 + 34 + 3 * 7);
        // v waits 19 + inv_sqrt cycles for its scale: three words in memory.
        assert_eq!(norm.balancing.mem_bits, 3 * 32 * u64::from(19 + inv_sqrt));
    }
}
