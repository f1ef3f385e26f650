//! `spd`: Eric Haines's Standard Procedural Databases (SPD 3.14), generated in Rust.
//!
//! The SPD is a set of small C programs, each making one scene from a size factor. This
//! crate ports them (from the public repository `erich666/StandardProceduralDatabases`)
//! and writes their NFF through [`tracer::nff_writer`], so that every command can use
//! `spd:NAME[:SIZE_FACTOR]` without the files. The output is the C's with raytracer
//! format 1 (NFF) and `-c` (curved primitives kept): the same entities in the same
//! order, the numbers computed in f64 in the C's order of operations and printed as
//! the shortest decimal of their f32 (the C prints `%g`, 6 significant digits).
//!
//! Layout: [`vector`] (the `libvec` port), [`random`] (`lib_gauss_rand`),
//! [`transform_stack`] (`libtx`), [`output`] and [`tessellate`] (the `lib_output_*`
//! NFF side), then one module per program.

// What user input can reach returns an error: no unwrap, expect or panic outside tests
// (unit tests are cfg(test); integration tests, benches and examples are other crates).
#![cfg_attr(
    not(test),
    deny(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]

pub mod output;
pub mod published;
pub mod random;
pub mod tessellate;
pub mod transform_stack;
pub mod vector;

mod balls;
mod gears;
mod jacks;
mod lattice;
mod mount;
mod rings;
mod sample;
mod shells;
mod sombrero;
mod teapot;
mod teapot_data;
mod tetra;
mod tree;

use output::Output;
use tracer::{Limits, Scene, SurfaceTerms};

/// One SPD program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Program {
    /// `balls`, `gears`, …
    pub name: &'static str,
    /// The SPD's default size factor.
    pub default_size_factor: u32,
    /// Largest size factor accepted (memory and time stay reasonable: at most a few
    /// million primitives).
    pub max_size_factor: u32,
    /// One line: what the scene is.
    pub summary: &'static str,
}

/// A size factor out of range or an unknown program.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SpdError {
    #[error("unknown SPD scene '{name}' (known: {})", names().join(", "))]
    UnknownProgram { name: String },
    #[error("spd:{name} size factor {size_factor} is out of range: use {min} to {max}")]
    SizeFactor {
        name: &'static str,
        size_factor: u32,
        min: u32,
        max: u32,
    },
    /// The generated text did not parse (within the limits given to
    /// [`generate_scene`]).
    #[error("{message}")]
    Parse { message: String },
}

/// The names of every program, in catalogue order.
pub fn names() -> Vec<&'static str> {
    PROGRAMS.iter().map(|p| p.name).collect()
}

/// The program called `name`.
pub fn find(name: &str) -> Option<&'static Program> {
    PROGRAMS.iter().find(|p| p.name == name)
}

/// The classic seven SPD scenes (the ones with published ray statistics).
pub const CLASSIC: [&str; 7] = [
    "balls", "gears", "mount", "rings", "teapot", "tetra", "tree",
];

/// Every program, alphabetical. Each module's documentation gives its primitive count
/// as a function of the size factor.
pub const PROGRAMS: &[Program] = &[
    Program {
        name: "balls",
        default_size_factor: 4,
        // 597,871 spheres (n = 7 would be 5.4 million).
        max_size_factor: 6,
        summary: "sphereflake: 1 + 9 + 81 + ... spheres over a ground polygon",
    },
    Program {
        name: "gears",
        default_size_factor: 4,
        // 598,017 polygons, most of them 144-vertex faces or rectangles (~85 MB).
        max_size_factor: 16,
        summary: "n^3 meshing gears (144-vertex concave faces), some transmitting",
    },
    Program {
        name: "jacks",
        default_size_factor: 1,
        // 2,696,337 primitives.
        max_size_factor: 7,
        summary: "recursive jacks: crossed cylinders with spheres, 8 smaller ones per level",
    },
    Program {
        name: "lattice",
        default_size_factor: 12,
        // 274,625 spheres + 811,200 cylinders.
        max_size_factor: 64,
        summary: "cubic lattice of shiny spheres joined by matte cylinders",
    },
    Program {
        name: "mount",
        default_size_factor: 6,
        // 2,097,152 triangles.
        max_size_factor: 10,
        summary: "fractal mountain of triangles with 4 glass spheres",
    },
    Program {
        name: "rings",
        default_size_factor: 7,
        // 664,200 spheres + 664,200 cylinders.
        max_size_factor: 40,
        summary: "pyramid of dodecahedral rings: spheres and cylinders before a wall",
    },
    Program {
        name: "sample",
        default_size_factor: 1,
        // The SPD ignores the size factor.
        max_size_factor: 1,
        summary: "three tessellated tori, a cone and a disc",
    },
    Program {
        name: "shells",
        default_size_factor: 5,
        // 1,474,561 spheres.
        max_size_factor: 13,
        summary: "Pickover sea shell: a spiral of overlapping spheres",
    },
    Program {
        name: "sombrero",
        default_size_factor: 1,
        // 2,093,058 triangles.
        max_size_factor: 6,
        summary: "height field of a damped ripple, as triangles",
    },
    Program {
        name: "teapot",
        default_size_factor: 6,
        // 1,047,552 patches + 16,384 squares.
        max_size_factor: 128,
        summary: "Utah teapot as smooth triangles on a checkerboard",
    },
    Program {
        name: "tetra",
        default_size_factor: 6,
        // 1,048,576 triangles.
        max_size_factor: 10,
        summary: "Sierpinski tetrahedron of 4^n triangles",
    },
    Program {
        name: "tree",
        default_size_factor: 11,
        // 1,048,575 spheres + 1,048,575 cones.
        max_size_factor: 19,
        summary: "branching tree of cones and spheres over a field",
    },
];

/// A program's `generate(out, size_factor)`.
type Generator = fn(&mut Output, u32);

/// A program's `primitive_count(size_factor)`.
type CountFormula = fn(u32) -> u64;

/// A program's generator and primitive-count formula.
struct Entry {
    generate: Generator,
    count: CountFormula,
}

/// The port of `name` (every name of [`PROGRAMS`] has one).
fn entry(name: &str) -> Option<Entry> {
    let (generate, count): (Generator, CountFormula) = match name {
        "balls" => (balls::generate, balls::primitive_count),
        "gears" => (gears::generate, gears::primitive_count),
        "jacks" => (jacks::generate, jacks::primitive_count),
        "lattice" => (lattice::generate, lattice::primitive_count),
        "mount" => (mount::generate, mount::primitive_count),
        "rings" => (rings::generate, rings::primitive_count),
        "sample" => (sample::generate, sample::primitive_count),
        "shells" => (shells::generate, shells::primitive_count),
        "sombrero" => (sombrero::generate, sombrero::primitive_count),
        "teapot" => (teapot::generate, teapot::primitive_count),
        "tetra" => (tetra::generate, tetra::primitive_count),
        "tree" => (tree::generate, tree::primitive_count),
        _ => return None,
    };
    Some(Entry { generate, count })
}

/// The program, its port and the size factor to use, checked.
fn resolve(
    name: &str,
    size_factor: Option<u32>,
) -> Result<(&'static Program, Entry, u32), SpdError> {
    let unknown = || SpdError::UnknownProgram {
        name: name.to_string(),
    };
    let program = find(name).ok_or_else(unknown)?;
    let entry = entry(name).ok_or_else(unknown)?;
    let size_factor = size_factor.unwrap_or(program.default_size_factor);
    if !(1..=program.max_size_factor).contains(&size_factor) {
        return Err(SpdError::SizeFactor {
            name: program.name,
            size_factor,
            min: 1,
            max: program.max_size_factor,
        });
    }
    Ok((program, entry, size_factor))
}

/// The NFF text of `name` at `size_factor` (the SPD default when `None`). It starts
/// with a `#` comment naming the program, the size factor and the primitive counts.
pub fn generate(name: &str, size_factor: Option<u32>) -> Result<String, SpdError> {
    generate_with_surface_terms(name, size_factor).map(|(text, _)| text)
}

/// [`generate`]'s text and the SPD surface terms the NFF cannot hold of every material
/// the program wrote ([`SurfaceTerms`]: `ka` and `ks_spec` of its `lib_output_color`
/// calls), in the order of the text's `f` lines. [`add_surface_terms`] gives them to
/// the scene parsed from the text.
pub fn generate_with_surface_terms(
    name: &str,
    size_factor: Option<u32>,
) -> Result<(String, Vec<SurfaceTerms>), SpdError> {
    let (program, entry, size_factor) = resolve(name, size_factor)?;
    // About 40 bytes per primitive line (patches and big polygons take more).
    let estimate = (entry.count)(size_factor).saturating_mul(48).min(1 << 30) as usize;
    let mut out = Output::with_capacity(estimate);
    (entry.generate)(&mut out, size_factor);
    let (mut text, counts, terms) = out.finish_with_surface_terms();
    let header = format!(
        "# Generated by rtprof from SPD 3.14 {}.c, size factor {size_factor}: {} primitives ({})\n",
        program.name,
        counts.total(),
        counts.describe()
    );
    // In place (the counts are known only now): no second copy of a text that can be
    // 200 MB.
    text.insert_str(0, &header);
    Ok((text, terms))
}

/// Gives `scene`, parsed from the text of [`generate_with_surface_terms`], that call's
/// surface terms (`terms`), as [`Scene::surface_terms`]: the `k`-th `f` line's
/// material gets the `k`-th. The scene's materials are its `f` lines in order, after
/// the default material the parser puts first when a primitive comes before any `f`
/// line (which has none); a scene with fewer materials than `terms` is left as it is.
pub fn add_surface_terms(scene: &mut Scene, terms: &[SurfaceTerms]) {
    let Some(first) = scene.materials.len().checked_sub(terms.len()) else {
        return;
    };
    scene.surface_terms = std::iter::repeat_n(None, first)
        .chain(terms.iter().copied().map(Some))
        .collect();
}

/// The scene of `name` at `size_factor` (the SPD default when `None`) as `spd:NAME`
/// loads it: [`generate`]'s text parsed within `limits`, its materials with the SPD
/// surface terms ([`add_surface_terms`]).
pub fn generate_scene(
    name: &str,
    size_factor: Option<u32>,
    limits: &Limits,
) -> Result<Scene, SpdError> {
    let (text, terms) = generate_with_surface_terms(name, size_factor)?;
    let mut scene = tracer::nff::parse_nff_with_limits(&text, &format!("spd:{name}"), limits)
        .map_err(|e| SpdError::Parse {
            message: e.to_string(),
        })?;
    add_surface_terms(&mut scene, &terms);
    Ok(scene)
}

/// The number of primitives `generate(name, size_factor)` writes, from the formula in
/// the program's module documentation (no generation).
pub fn primitive_count(name: &str, size_factor: Option<u32>) -> Result<u64, SpdError> {
    let (_, entry, size_factor) = resolve(name, size_factor)?;
    Ok((entry.count)(size_factor))
}
