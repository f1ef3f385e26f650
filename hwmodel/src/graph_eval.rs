//! Evaluates a block's dataflow graph on values: what the RTL generated from the same
//! graph computes for one item, in [`crate::float_policy`]'s arithmetic.
//!
//! The scheduler reads a graph for its timing; this reads it for its meaning (the
//! node [`Detail`]s and operand order), so that the graphs the model times and the RTL
//! is generated from are checked to compute the picture: [`render`] drives the block
//! graphs pixel by pixel like the pipeline does and must give the emulator's image bit
//! for bit (tests below, and on the 21 test-bench scenes in `tests/`). It is also the
//! reference for the what-if designs the emulator does not model.
//!
//! Every value is a `u32`: a float's bit pattern, a flag (0/1), an address or a gray
//! level. Registers are evaluated as wires: sequencing (the minimum-distance block's
//! kept value, the row register's once-per-row load) is the caller's.

use std::collections::HashMap;

use thiserror::Error;

use crate::blocks::{Block, Pipeline};
use crate::emulator::{self, HwImage, PrimaryRays};
use crate::float_policy as fp;
use crate::graph::{AddSubMode, Detail, Graph, NodeKind};
use crate::hw_scene::{HwPrimitive, HwScene};
use crate::library::OpKind;

/// Why a graph cannot be evaluated.
#[derive(Debug, Error, PartialEq, Eq)]
pub enum EvalError {
    /// An input (or a non-literal constant) was given no value.
    #[error("graph input `{0}` has no value")]
    MissingInput(String),
    /// An operator the evaluator does not know how to compute.
    #[error("node `{label}`: {problem}")]
    Malformed {
        label: String,
        problem: &'static str,
    },
    /// A design the picture cannot be computed for.
    #[error("{0}")]
    Unsupported(&'static str),
}

/// A scene-memory word source for `ram_read` nodes: `(address, field) → word`.
pub trait SceneMemory {
    fn word(&self, address: u32, field: u32) -> u32;
}

/// The scene memory of `scene`'s primitives (words 0..9, [`HwPrimitive::to_words`],
/// then the rsqrt-free shading terms, [`shading_words`]).
pub struct SceneWords<'a> {
    pub primitives: &'a [HwPrimitive],
    pub light: [f32; 3],
}

impl SceneMemory for SceneWords<'_> {
    fn word(&self, address: u32, field: u32) -> u32 {
        let Some(p) = self.primitives.get(address as usize) else {
            return 0;
        };
        let field = field as usize;
        match field.checked_sub(HwPrimitive::WORDS) {
            None => p.to_words()[field],
            Some(extra) => shading_words(p, self.light)
                .get(extra)
                .map_or(0, |v| v.to_bits()),
        }
    }
}

/// The rsqrt-free shading's per-primitive terms (fields 9..14): the brightest point
/// `M = C + r·L̂` (L̂ the unit direction to the light at infinity, here from the
/// origin), `1/(2r²)` and `1/r`, as the scene loader would precompute them.
pub fn shading_words(p: &HwPrimitive, light: [f32; 3]) -> [f32; 5] {
    let unit = light_direction(light);
    let r = p.radius;
    [
        fp::add(p.center[0], fp::mul(r, unit[0])),
        fp::add(p.center[1], fp::mul(r, unit[1])),
        fp::add(p.center[2], fp::mul(r, unit[2])),
        fp::div(1.0, fp::mul(fp::mul(r, r), 2.0)),
        fp::div(1.0, r),
    ]
}

/// The unit direction towards a light at infinity placed at `light`.
pub fn light_direction(light: [f32; 3]) -> [f32; 3] {
    let len_sq = fp::add(
        fp::add(fp::mul(light[0], light[0]), fp::mul(light[1], light[1])),
        fp::mul(light[2], light[2]),
    );
    let inv = fp::inv_sqrt(len_sq);
    light.map(|c| fp::mul(c, inv))
}

/// Evaluates `graph` for one item: its outputs. `inputs` gives every input and named
/// constant by label (vector components as `label.x` …); literals carry their own
/// value.
pub fn evaluate(
    graph: &Graph,
    inputs: &HashMap<String, u32>,
    memory: &dyn SceneMemory,
) -> Result<Vec<u32>, EvalError> {
    let value = evaluate_nodes(graph, inputs, memory)?;
    Ok(graph.outputs().iter().map(|&o| value[o]).collect())
}

/// One clock edge of a block whose outputs are registers with an enable (the minimum
/// distance block): output `k` takes its register's input when the enable evaluated
/// to 1 and keeps `kept[k]` otherwise. `values` are [`evaluate_nodes`]'s.
pub fn clock_output_registers(graph: &Graph, values: &[u32], kept: &mut [u32]) {
    for (slot, &o) in kept.iter_mut().zip(graph.outputs()) {
        let node = &graph.nodes()[o];
        let load = match (node.kind, node.inputs.as_slice()) {
            (NodeKind::Op(OpKind::Register), [_, enable]) => values[*enable] & 1 == 1,
            _ => true,
        };
        if load {
            *slot = values[o];
        }
    }
}

/// Every node's value for one item (a register's is its input: see the module doc).
pub fn evaluate_nodes(
    graph: &Graph,
    inputs: &HashMap<String, u32>,
    memory: &dyn SceneMemory,
) -> Result<Vec<u32>, EvalError> {
    let nodes = graph.nodes();
    let mut value = vec![0u32; nodes.len()];
    for (id, node) in nodes.iter().enumerate() {
        let arg = |k: usize| -> Result<u32, EvalError> {
            node.inputs
                .get(k)
                .map(|&i| value[i])
                .ok_or_else(|| EvalError::Malformed {
                    label: node.label.clone(),
                    problem: "too few operands",
                })
        };
        let f = |k: usize| arg(k).map(f32::from_bits);
        let bits = |x: f32| x.to_bits();
        value[id] = match (node.kind, node.detail) {
            (NodeKind::Input { .. }, Detail::Literal(v)) => v,
            (NodeKind::Input { .. }, _) => *inputs
                .get(&node.label)
                .ok_or_else(|| EvalError::MissingInput(node.label.clone()))?,
            (NodeKind::RowRegister, _) => arg(0)?,
            (NodeKind::Op(op), detail) => match op {
                OpKind::AddSub => {
                    let (a, b) = (f(0)?, f(1)?);
                    bits(match detail {
                        Detail::AddSub(AddSubMode::Sub) => fp::sub(a, b),
                        Detail::AddSub(AddSubMode::NegAdd) => fp::add(-a, b),
                        Detail::AddSub(AddSubMode::NegSub) => fp::sub(-a, b),
                        _ => fp::add(a, b),
                    })
                }
                OpKind::Multiply | OpKind::MultiplyRegistered => bits(fp::mul(f(0)?, f(1)?)),
                OpKind::Divide => bits(fp::div(f(0)?, f(1)?)),
                OpKind::Sqrt => bits(fp::sqrt(f(0)?)),
                OpKind::FastSqrt => bits(fp::fast_sqrt(f(0)?)),
                OpKind::InvSqrt => bits(fp::inv_sqrt(f(0)?)),
                OpKind::Compare => u32::from(fp::lt(f(0)?, f(1)?)),
                OpKind::IntCompare => u32::from(fp::lt_bits(f(0)?, f(1)?)),
                OpKind::Convert => u32::from(fp::to_u8(f(0)?)),
                OpKind::Mux => {
                    if arg(0)? & 1 == 1 {
                        arg(2)?
                    } else {
                        arg(1)?
                    }
                }
                OpKind::Register => arg(0)?,
                OpKind::RamRead => match detail {
                    Detail::Field(field) => memory.word(arg(0)?, field),
                    _ => {
                        return Err(EvalError::Malformed {
                            label: node.label.clone(),
                            problem: "memory read without a field",
                        });
                    }
                },
            },
        };
    }
    Ok(value)
}

/// The minimum-distance registers before any primitive: distance ∞, P, m, address.
const NO_HIT: [u32; 6] = [0x7F80_0000, 0, 0, 0, 0, 0];

/// Input values for a graph, by label.
#[derive(Default)]
struct Inputs(HashMap<String, u32>);

impl Inputs {
    fn set(&mut self, label: &str, v: u32) -> &mut Self {
        self.0.insert(label.to_string(), v);
        self
    }
    fn float(&mut self, label: &str, v: f32) -> &mut Self {
        self.set(label, v.to_bits())
    }
    fn vector(&mut self, label: &str, v: [f32; 3]) -> &mut Self {
        for (c, x) in ["x", "y", "z"].iter().zip(v) {
            self.float(&format!("{label}.{c}"), x);
        }
        self
    }
    fn vector_bits(&mut self, label: &str, v: &[u32]) -> &mut Self {
        for (c, &x) in ["x", "y", "z"].iter().zip(v) {
            self.set(&format!("{label}.{c}"), x);
        }
        self
    }
}

fn run(block: &Block, inputs: &Inputs, memory: &dyn SceneMemory) -> Result<Vec<u32>, EvalError> {
    evaluate(&block.graph, &inputs.0, memory)
}

/// The frame constants the pipeline's blocks read, for one scene and screen size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameConstants {
    pub rays: PrimaryRays,
    pub light: [f32; 3],
    /// The background's gray level.
    pub background: u8,
}

impl FrameConstants {
    pub fn new(scene: &HwScene, width: u32, height: u32) -> Self {
        Self {
            rays: PrimaryRays::new(scene, width, height),
            light: scene.light,
            background: emulator::to_gray8(scene.background_gray),
        }
    }
}

/// The image `pipeline` computes for `scene`, by evaluating its block graphs pixel by
/// pixel in the pipeline's order: the primary ray, every primitive through its unit's
/// intersection test, each unit's minimum distance (a strictly smaller distance
/// replaces the kept one), the tree joining the units, shading. Units take contiguous
/// chunks of ⌈n/K⌉ primitives, the first chunk to unit 0.
pub fn render(
    pipeline: &Pipeline,
    scene: &HwScene,
    width: u32,
    height: u32,
) -> Result<HwImage, EvalError> {
    let k = FrameConstants::new(scene, width, height);
    let memory = SceneWords {
        primitives: &scene.primitives,
        light: scene.light,
    };
    let design = &pipeline.design;
    if design.ortho {
        return Err(EvalError::Unsupported(
            "the orthographic design's camera (origins on the image plane) is not modelled \
             by the emulator's scene set-up",
        ));
    }
    let light_dir = light_direction(scene.light);
    let units = design.units.max(1) as usize;
    let chunk = scene.primitives.len().div_ceil(units).max(1);
    let mut pixels = Vec::with_capacity(width as usize * height as usize);
    for row in 0..height {
        for column in 0..width {
            let mut ray_in = Inputs::default();
            ray_in
                .vector("scan_line", k.rays.scan_line)
                .vector("row_step", k.rays.pixel_height)
                .vector("column_step", k.rays.pixel_width)
                .float("i", fp::from_int(row as i32))
                .float("j", fp::from_int(column as i32));
            let ray = run(&pipeline.primary_ray, &ray_in, &memory)?;
            let mut minima = Vec::with_capacity(units);
            for unit in scene.primitives.chunks(chunk) {
                // distance, P.x, P.y, P.z, m, address
                let mut kept = NO_HIT;
                for (p, primitive) in unit.iter().enumerate() {
                    let address = (minima.len() * chunk + p) as u32;
                    let mut hit_in = Inputs::default();
                    hit_in
                        .vector_bits("R", &ray)
                        .vector("O", scene.eye)
                        .vector("C", primitive.center)
                        .float("r", primitive.radius)
                        .vector("V", primitive.axis)
                        .float("Mmax", primitive.m_max)
                        .set("type", primitive.kind.type_bit())
                        .set("address", address);
                    let hit = run(&pipeline.intersection, &hit_in, &memory)?;
                    let mut md_in = Inputs::default();
                    md_in
                        .set("distance", hit[0])
                        .vector_bits("P", &hit[1..4])
                        .set("m", hit[4])
                        .set("address", hit[5])
                        .set("kept distance", kept[0]);
                    let graph = &pipeline.min_distance.graph;
                    let values = evaluate_nodes(graph, &md_in.0, &memory)?;
                    clock_output_registers(graph, &values, &mut kept);
                }
                minima.push(kept);
            }
            let nearest = match &pipeline.min_tree {
                None => minima.first().copied().unwrap_or(NO_HIT),
                Some(tree) => {
                    let mut tree_in = Inputs::default();
                    for unit in 0..units {
                        let m = minima.get(unit).copied().unwrap_or(NO_HIT);
                        tree_in
                            .set(&format!("distance{unit}"), m[0])
                            .vector_bits(&format!("P{unit}"), &m[1..4])
                            .set(&format!("m{unit}"), m[4])
                            .set(&format!("address{unit}"), m[5]);
                    }
                    let out = run(tree, &tree_in, &memory)?;
                    let mut n = [0u32; 6];
                    n.copy_from_slice(&out[..6]);
                    n
                }
            };
            let mut shade_in = Inputs::default();
            shade_in
                .set("distance", nearest[0])
                .vector_bits("P", &nearest[1..4])
                .set("address", nearest[5])
                .vector("light", scene.light)
                .vector("L̂", light_dir)
                .set("background", u32::from(k.background));
            let gray = run(&pipeline.shading, &shade_in, &memory)?;
            pixels.push(gray.first().copied().unwrap_or(0) as u8);
        }
    }
    Ok(HwImage {
        width,
        height,
        pixels,
    })
}
