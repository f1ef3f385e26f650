//! The thesis's pipeline blocks (ch. 6) as dataflow graphs of operators.
//!
//! Nothing here is fitted to table 8: each block is the maths of ch. 1.3 and the block
//! descriptions of ch. 6, built from the composites and IP cores, scheduled and summed.
//! Where the thesis leaves a structural choice open, the reading taken is stated at the
//! builder, with the latency the other reading would give (docs/hardware-model.md).
//!
//! Inputs that change with every primitive (the primitive's words, the ray while other
//! primitives stream past it) are ordinary inputs and get delay lines; frame constants
//! (eye, light, camera steps, literals 0, 1, 2, 4, 255, ∞) are never delayed.

use serde::Serialize;

use crate::composites::{
    Vec3Node, dot, normalize, vector_add_sub, vector_constant, vector_input, vector_input_held,
    vector_output, vector_scale, vector_select,
};
use crate::design::{Design, MinDistance};
use crate::graph::{AddSubMode, FRAME_CONSTANT, Graph, NodeId, Schedule};
use crate::hw_scene::HwPrimitive;
use crate::library::{Library, OpKind, Resources};

/// Address bits of the scene memory (the minimum-distance block keeps the nearest
/// primitive's address: its 173 registers are 5 words + 13 bits).
pub const ADDRESS_BITS: u32 = 13;

/// Names of the scene-memory words the rsqrt-free shading adds after the primitive's
/// nine (`HwPrimitive::WORD_NAMES`): brightest point M, 1/(2r²), 1/r.
pub const SHADING_FIELDS: [&str; 5] = ["M.x", "M.y", "M.z", "1/(2r²)", "1/r"];

/// The name of scene-memory word `field`.
pub fn field_name(field: usize) -> &'static str {
    match field.checked_sub(HwPrimitive::WORDS) {
        None => HwPrimitive::WORD_NAMES[field],
        Some(extra) => SHADING_FIELDS.get(extra).copied().unwrap_or("?"),
    }
}

/// One block: its graph and schedule.
#[derive(Clone, Debug)]
pub struct Block {
    /// `primary_ray`, `intersection`, `min_distance`, `shading` or `min_tree`.
    pub name: &'static str,
    pub graph: Graph,
    pub schedule: Schedule,
}

impl Block {
    fn new(name: &'static str, graph: Graph, lib: &Library) -> Self {
        let schedule = graph.schedule(lib);
        Self {
            name,
            graph,
            schedule,
        }
    }

    pub fn latency(&self) -> u32 {
        self.schedule.latency
    }

    pub fn resources(&self) -> Resources {
        self.schedule.resources()
    }
}

/// Latency and resources of one block, as plain data.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BlockFigures {
    pub name: String,
    pub latency: u32,
    pub le: u64,
    pub comb: u64,
    pub regs: u64,
    pub mem_bits: u64,
    pub mult: u64,
}

impl BlockFigures {
    pub fn of(name: &str, latency: u32, r: Resources) -> Self {
        Self {
            name: name.to_string(),
            latency,
            le: r.le,
            comb: r.comb,
            regs: r.regs,
            mem_bits: r.mem_bits,
            mult: r.mult,
        }
    }
}

/// The four blocks of a design (one intersection unit and minimum distance; the
/// device total multiplies them by the number of units).
#[derive(Clone, Debug)]
pub struct Pipeline {
    pub design: Design,
    pub primary_ray: Block,
    pub intersection: Block,
    pub min_distance: Block,
    pub shading: Block,
    /// The comparator tree joining K units' minima (`None` for one unit).
    pub min_tree: Option<Block>,
}

impl Pipeline {
    /// Each table block's operators and delay lines, as `rtprof hw table --detail`
    /// prints them.
    pub fn detail_text(&self) -> String {
        let p = self;
        let mut out = String::new();
        for b in p.table_blocks() {
            let s = &b.schedule;
            out += &format!("\n{}: {} cycles\n  operators:", b.name, s.latency);
            for (op, n) in &s.op_counts {
                out += &format!(" {}×{n}", op.key());
            }
            out += "\n  delay lines (bits × cycles):";
            if s.delay_lines.is_empty() {
                out += " none";
            }
            for l in &s.delay_lines {
                out += &format!(
                    "\n    {:<28} {:>3} × {:>3}{}",
                    l.producer,
                    l.bits,
                    l.cycles,
                    if l.in_memory { "  (memory)" } else { "" }
                );
            }
            out += "\n";
        }
        out
    }

    /// Builds and schedules every block of `design`.
    pub fn build(lib: &Library, design: &Design) -> Self {
        Self {
            design: *design,
            primary_ray: Block::new("primary_ray", primary_ray(design), lib),
            intersection: Block::new("intersection", intersection(design), lib),
            min_distance: Block::new("min_distance", min_distance(design), lib),
            shading: Block::new("shading", shading(design), lib),
            min_tree: (design.units > 1)
                .then(|| Block::new("min_tree", min_tree(design.units), lib)),
        }
    }

    /// Every block in the order a pixel crosses them: primary ray, intersection,
    /// minimum distance, the comparator tree (K > 1), shading.
    pub fn blocks_in_order(&self) -> Vec<&Block> {
        [
            Some(&self.primary_ray),
            Some(&self.intersection),
            Some(&self.min_distance),
            self.min_tree.as_ref(),
            Some(&self.shading),
        ]
        .into_iter()
        .flatten()
        .collect()
    }

    /// The four table-8 blocks in order.
    pub fn table_blocks(&self) -> [&Block; 4] {
        [
            &self.primary_ray,
            &self.intersection,
            &self.min_distance,
            &self.shading,
        ]
    }

    /// Cycles from a pixel entering the primary-ray block to its gray value leaving
    /// shading, after its last primitive entered the intersection unit.
    pub fn fill_cycles(&self) -> u64 {
        let tree = self.min_tree.as_ref().map_or(0, Block::latency);
        u64::from(
            self.primary_ray.latency()
                + self.intersection.latency()
                + self.min_distance.latency()
                + tree
                + self.shading.latency(),
        )
    }
}

/// Primary ray (thesis 6.1.3, fig. 20): `dir = normalize(row_base + j · column_step)`
/// with `row_base = scan_line − i · row_step` held in a row register.
///
/// The row term changes once per 640 pixels (1920·n cycles), so it is computed for the
/// next row while the current one runs and does not sit on the per-pixel path: 7 + 7 +
/// 50 = 64 cycles (table 8: 62 = 5 + 7 + 50, the same structure with bare multipliers).
/// Computing both terms per pixel would give 7 + 7 + 7 + 50 = 71. Resources: two vector
/// × scalar, two vector add/sub and a normalize, which is table 8's multiplier count
/// exactly (2·21 + 76 = 118). `ortho`: the origin moves by the same sums and the
/// direction is a frame constant: no normalize.
pub fn primary_ray(design: &Design) -> Graph {
    let mut g = Graph::new();
    let scan_line = vector_constant(&mut g, "scan_line");
    let row_step = vector_constant(&mut g, "row_step");
    let column_step = vector_constant(&mut g, "column_step");
    let i = g.constant("i");
    let j = g.input("j");
    let down = vector_scale(&mut g, row_step, i, "i·row_step");
    let row = vector_add_sub(
        &mut g,
        AddSubMode::Sub,
        scan_line,
        down,
        "scan_line−i·row_step",
    );
    let row_base = row.map(|c| g.row_register(c, "row_base"));
    let across = vector_scale(&mut g, column_step, j, "j·column_step");
    let point = vector_add_sub(
        &mut g,
        AddSubMode::Add,
        row_base,
        across,
        "row_base+j·column_step",
    );
    if design.ortho {
        // The origin is the moving point; the direction is the view direction.
        vector_output(&mut g, point);
    } else {
        let dir = normalize(&mut g, point, "normalize(dir)");
        vector_output(&mut g, dir);
    }
    g
}

/// Intersection test (6.1.4, fig. 21-24, 26): Voc = O − C; sphere a, b, c; cylinder
/// a, b, c; selector; quadratic solver (smaller positive root, ∞ when none); hit body.
///
/// The dot products R·Voc, Voc·Voc and r² serve both the sphere and the cylinder
/// calculators (the same values; a designer wires them to both). ×2 and ×4 are
/// multipliers (IP cores, as the thesis builds every operation). A negative
/// discriminant needs no comparator: its square root is NaN and NaN compares false, so
/// both roots fail the `> 0` test and the output is ∞. Hit body: P = O + d·R, m =
/// (P − Cb)·V, `0 < m < Mmax` (6.1.6 computes m from the impact point); it also passes
/// P, m and the primitive's address on to the minimum-distance block.
pub fn intersection(design: &Design) -> Graph {
    let mut g = Graph::new();
    let ray = if design.ortho {
        // One direction for every ray: a frame constant.
        vector_constant(&mut g, "R")
    } else {
        vector_input(&mut g, "R")
    };
    let eye = if design.ortho {
        vector_input(&mut g, "O")
    } else {
        vector_constant(&mut g, "O")
    };
    let centre = vector_input(&mut g, "C");
    let radius = g.input("r");
    let axis = vector_input(&mut g, "V");
    let m_max = g.input("Mmax");
    let kind = g.input_held("type", 1, 0);
    let address = g.input_held("address", ADDRESS_BITS, 0);
    let zero = g.literal("0", 0.0);
    let zero_bit = g.literal_bits("0 (bit)", 1, 0);
    let one = g.literal("1", 1.0);
    let two = g.literal("2", 2.0);
    let four = g.literal("4", 4.0);
    let infinity = g.literal("∞", f32::INFINITY);

    let voc = vector_add_sub(&mut g, AddSubMode::Sub, eye, centre, "Voc");
    let r_voc = dot(&mut g, ray, voc, "R·Voc");
    let voc_voc = dot(&mut g, voc, voc, "Voc·Voc");
    let r_v = dot(&mut g, ray, axis, "R·V");
    let voc_v = dot(&mut g, voc, axis, "Voc·V");
    let r_sq = g.op(OpKind::Multiply, &[radius, radius], "r²");

    // Sphere: a = 1 (|R| = 1), b = 2 R·Voc, c = Voc·Voc − r².
    let b_sphere = g.op(OpKind::Multiply, &[r_voc, two], "b sphere");
    let c_sphere = g.sub(voc_voc, r_sq, "c sphere");
    // Cylinder: a = 1 − (R·V)², b = 2(R·Voc − (R·V)(Voc·V)), c = Voc·Voc − (Voc·V)² − r².
    let rv_sq = g.op(OpKind::Multiply, &[r_v, r_v], "(R·V)²");
    let a_cyl = g.sub(one, rv_sq, "a cylinder");
    let rv_vocv = g.op(OpKind::Multiply, &[r_v, voc_v], "(R·V)(Voc·V)");
    let b_half = g.sub(r_voc, rv_vocv, "b/2 cylinder");
    let b_cyl = g.op(OpKind::Multiply, &[b_half, two], "b cylinder");
    let vocv_sq = g.op(OpKind::Multiply, &[voc_v, voc_v], "(Voc·V)²");
    let c_part = g.sub(voc_voc, vocv_sq, "Voc·Voc−(Voc·V)²");
    let c_cyl = g.sub(c_part, r_sq, "c cylinder");

    // Selector (type 1: cylinder).
    let a = g.select(kind, one, a_cyl, "a");
    let b = g.select(kind, b_sphere, b_cyl, "b");
    let c = g.select(kind, c_sphere, c_cyl, "c");

    // Quadratic solver: roots (−b ∓ √disc) / 2a, the sign of −b is a wire.
    let b_sq = g.op(OpKind::Multiply, &[b, b], "b²");
    let ac = g.op(OpKind::Multiply, &[a, c], "ac");
    let ac4 = g.op(OpKind::Multiply, &[ac, four], "4ac");
    let disc = g.sub(b_sq, ac4, "b²−4ac");
    let sqrt_op = if design.fast_sqrt {
        OpKind::FastSqrt
    } else {
        OpKind::Sqrt
    };
    let root = g.op(sqrt_op, &[disc], "√disc");
    let two_a = g.op(OpKind::Multiply, &[a, two], "2a");
    let near_num = g.add_sub(AddSubMode::NegSub, b, root, "−b−√disc");
    let far_num = g.add_sub(AddSubMode::NegAdd, b, root, "−b+√disc");
    let near = g.op(OpKind::Divide, &[near_num, two_a], "t near");
    let far = g.op(OpKind::Divide, &[far_num, two_a], "t far");
    let near_ok = g.less(zero, near, "t near > 0");
    let far_ok = g.less(zero, far, "t far > 0");
    let far_or_none = g.select(far_ok, infinity, far, "t far or ∞");
    let d = g.select(near_ok, far_or_none, near, "d");

    // Hit body.
    let along = vector_scale(&mut g, ray, d, "d·R");
    let point = vector_add_sub(&mut g, AddSubMode::Add, eye, along, "P");
    let from_base = vector_add_sub(&mut g, AddSubMode::Sub, point, centre, "P−Cb");
    let m = dot(&mut g, from_base, axis, "m");
    let above = g.less(zero, m, "m > 0");
    let below = g.less(m, m_max, "m < Mmax");
    let inside = g.select(above, zero_bit, below, "0 < m < Mmax");
    let body = g.select(inside, infinity, d, "d in body");
    let distance = g.select(kind, d, body, "distance");

    g.output(distance);
    vector_output(&mut g, point);
    g.output(m);
    g.output(address);
    g
}

/// Minimum distance (6.1.5, fig. 25): compare the incoming distance with the kept one
/// (3 cycles) and load distance, P, m and the primitive's address into the registers
/// (1 cycle): 4 cycles. Its inputs are held 3 cycles by the pacing, so they need no
/// delay lines (this is why the iterator issues one pixel every 3n cycles). With the
/// integer compare ([`MinDistance::IntegerCompare`]) the compare lies within the
/// register's cycle: 1 cycle, inputs held 1, one primitive a cycle.
pub fn min_distance(design: &Design) -> Graph {
    let hold = design.cycles_per_primitive();
    let mut g = Graph::new();
    let distance = g.input_held("distance", 32, hold);
    let point = vector_input_held(&mut g, "P", hold);
    let m = g.input_held("m", 32, hold);
    let address = g.input_held("address", ADDRESS_BITS, hold);
    // The kept distance is the register's own output: stable until it is replaced.
    let kept = g.constant("kept distance");
    let closer = match design.min_distance {
        MinDistance::FloatCompare => g.less(distance, kept, "closer"),
        MinDistance::IntegerCompare => g.less_int(distance, kept, "closer"),
    };
    let keep = |g: &mut Graph, v: NodeId, bits: u32, label: &str| {
        g.op_bits(OpKind::Register, &[v, closer], bits, label)
    };
    let outputs = [
        keep(&mut g, distance, 32, "distance reg"),
        keep(&mut g, point[0], 32, "P.x reg"),
        keep(&mut g, point[1], 32, "P.y reg"),
        keep(&mut g, point[2], 32, "P.z reg"),
        keep(&mut g, m, 32, "m reg"),
        keep(&mut g, address, ADDRESS_BITS, "address reg"),
    ];
    for o in outputs {
        g.output(o);
    }
    g
}

/// Shading (6.1.7, fig. 27): read the nearest primitive's words (centre or base C, axis
/// V, type) from the scene memory by the kept address; L = light − P; the normal
/// "from the impact point": P − C for a sphere, and for a cylinder the component of
/// P − C across the axis, (P − C) − ((P − C)·V)·V; normalize both; N·L; background
/// when it is negative or nothing was hit, else ×255 and to an 8-bit integer.
///
/// Reading: the cylinder normal is recomputed from P (as 6.1.7 describes), not from the
/// m kept by the minimum-distance block. That path is 2 + 7 + 19 + 7 + 7 + 50 + 19 +
/// 5 + 6 = 122 cycles with table 7's normalize (table 8: 121; 124 with the library's
/// inverse square root since issue 38); with the kept m it would be about 104 (−14 %),
/// with 3 fewer multipliers (201 instead of 222: table 8 has 201).
///
/// `no_rsqrt_shading` (light at infinity, direction L̂ a frame constant): spheres use
/// cos θ = 1 − |P − M|²/(2r²) with M = C + rL̂ and 1/(2r²) precomputed per primitive;
/// cylinders scale their normal by the precomputed 1/r.
pub fn shading(design: &Design) -> Graph {
    let mut g = Graph::new();
    let distance = g.input("distance");
    let point = vector_input(&mut g, "P");
    let address = g.input_held("address", ADDRESS_BITS, 0);
    let light = vector_constant(&mut g, "light");
    let zero = g.literal("0", 0.0);
    let zero_bit = g.literal_bits("0 (bit)", 1, 0);
    let one = g.literal("1", 1.0);
    let c255 = g.literal("255", 255.0);
    let infinity = g.literal("∞", f32::INFINITY);
    let background = g.input_held("background", 8, FRAME_CONSTANT);

    let read = |g: &mut Graph, field: usize, bits: u32| {
        g.ram_read(address, field as u32, bits, field_name(field))
    };
    let centre = [0, 1, 2].map(|f| read(&mut g, f, 32));
    let axis = [4, 5, 6].map(|f| read(&mut g, f, 32));
    let kind = read(&mut g, 8, 1);

    let from_centre = vector_add_sub(&mut g, AddSubMode::Sub, point, centre, "P−C");
    let m = dot(&mut g, from_centre, axis, "(P−C)·V");
    let on_axis = vector_scale(&mut g, axis, m, "m·V");
    let across = vector_add_sub(&mut g, AddSubMode::Sub, from_centre, on_axis, "(P−C)−m·V");

    let diffuse = if design.no_rsqrt_shading {
        let brightest = [9, 10, 11].map(|f| read(&mut g, f, 32));
        let inv_two_r_sq = read(&mut g, 12, 32);
        let inv_r = read(&mut g, 13, 32);
        let light_dir = vector_constant(&mut g, "L̂");
        let to_brightest = vector_add_sub(&mut g, AddSubMode::Sub, point, brightest, "P−M");
        let dist_sq = dot(&mut g, to_brightest, to_brightest, "|P−M|²");
        let scaled = g.op(OpKind::Multiply, &[dist_sq, inv_two_r_sq], "|P−M|²/(2r²)");
        let sphere_cos = g.sub(one, scaled, "cos sphere");
        let unit_normal = vector_scale(&mut g, across, inv_r, "N/r");
        let cylinder_cos = dot(&mut g, unit_normal, light_dir, "N̂·L̂");
        g.select(kind, sphere_cos, cylinder_cos, "N·L")
    } else {
        let to_light = vector_add_sub(&mut g, AddSubMode::Sub, light, point, "L");
        let normal = vector_select(&mut g, kind, from_centre, across, "N");
        let unit_light = normalize(&mut g, to_light, "normalize(L)");
        let unit_normal = normalize(&mut g, normal, "normalize(N)");
        dot(&mut g, unit_normal, unit_light, "N·L")
    };

    let hit = g.less(distance, infinity, "hit");
    let lit = g.less(zero, diffuse, "N·L > 0");
    let visible = g.select(hit, zero_bit, lit, "hit and lit");
    let scaled = g.op(OpKind::Multiply, &[diffuse, c255], "×255");
    let gray = g.op_bits(OpKind::Convert, &[scaled], 8, "gray");
    let pixel = g.select(visible, background, gray, "pixel");
    g.output(pixel);
    g
}

/// K units' minima joined by a balanced tree of comparator stages (compare + registers
/// for distance, P, m and address): ⌈log2 K⌉ levels of 4 cycles, K − 1 stages.
pub fn min_tree(units: u32) -> Graph {
    let mut g = Graph::new();
    let mut level: Vec<(NodeId, Vec3Node, NodeId, NodeId)> = (0..units)
        .map(|k| {
            let d = g.input(&format!("distance{k}"));
            let p = vector_input(&mut g, &format!("P{k}"));
            let m = g.input(&format!("m{k}"));
            let a = g.input_held(&format!("address{k}"), ADDRESS_BITS, 0);
            (d, p, m, a)
        })
        .collect();
    while level.len() > 1 {
        let mut next = Vec::with_capacity(level.len().div_ceil(2));
        for pair in level.chunks(2) {
            match pair {
                [a, b] => {
                    // b replaces a only when strictly closer: ties keep the lower unit,
                    // whose primitives come first in memory.
                    let closer = g.less(b.0, a.0, "closer");
                    let pick = |g: &mut Graph, x: NodeId, y: NodeId| {
                        let s = g.select(closer, x, y, "pick");
                        let bits = g.nodes()[s].bits;
                        g.op_bits(OpKind::Register, &[s], bits, "pick reg")
                    };
                    let d = pick(&mut g, a.0, b.0);
                    let p = [0, 1, 2].map(|i| pick(&mut g, a.1[i], b.1[i]));
                    let m = pick(&mut g, a.2, b.2);
                    let addr = pick(&mut g, a.3, b.3);
                    next.push((d, p, m, addr));
                }
                [a] => next.push(*a),
                _ => {}
            }
        }
        level = next;
    }
    if let Some((d, p, m, a)) = level.pop() {
        g.output(d);
        vector_output(&mut g, p);
        g.output(m);
        g.output(a);
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tree_of_k_units_has_k_minus_1_comparators_and_log_depth() {
        let lib = Library::cyclone_iv_e();
        for (k, depth) in [(2u32, 1u32), (3, 2), (4, 2), (5, 3), (8, 3)] {
            let s = min_tree(k).schedule(&lib);
            assert_eq!(s.count(OpKind::Compare), k - 1, "K={k}");
            assert_eq!(s.latency, depth * (3 + 1), "K={k}");
        }
    }

    #[test]
    fn ortho_drops_the_normalize_and_fast_sqrt_the_sqrt_core() {
        let lib = Library::cyclone_iv_e();
        let thesis = Pipeline::build(&lib, &Design::thesis());
        let ortho = Pipeline::build(
            &lib,
            &Design {
                ortho: true,
                ..Design::thesis()
            },
        );
        assert_eq!(thesis.primary_ray.schedule.count(OpKind::InvSqrt), 1);
        assert_eq!(ortho.primary_ray.schedule.count(OpKind::InvSqrt), 0);
        // Normalize: dot product, inverse square root, scale.
        assert_eq!(
            thesis.primary_ray.latency() - ortho.primary_ray.latency(),
            19 + lib.op(OpKind::InvSqrt).latency + 5
        );
        let fast = Pipeline::build(
            &lib,
            &Design {
                fast_sqrt: true,
                ..Design::thesis()
            },
        );
        assert_eq!(fast.intersection.schedule.count(OpKind::Sqrt), 0);
        assert_eq!(
            thesis.intersection.latency() - fast.intersection.latency(),
            16 - 1
        );
    }

    #[test]
    fn rsqrt_free_shading_has_no_inverse_square_root() {
        let lib = Library::cyclone_iv_e();
        let p = Pipeline::build(
            &lib,
            &Design {
                no_rsqrt_shading: true,
                ..Design::thesis()
            },
        );
        assert_eq!(p.shading.schedule.count(OpKind::InvSqrt), 0);
        let thesis = Pipeline::build(&lib, &Design::thesis());
        assert_eq!(thesis.shading.schedule.count(OpKind::InvSqrt), 2);
        assert!(p.shading.latency() < thesis.shading.latency());
    }
}
