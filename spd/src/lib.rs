//! `spd`: Eric Haines's Standard Procedural Databases (SPD 3.14), generated in Rust.
//!
//! The SPD is a set of small C programs, each making one scene from a size factor. This
//! crate ports them (from the public repository `erich666/StandardProceduralDatabases`)
//! and writes their NFF through [`tracer::nff_writer`], so that every command can use
//! `spd:NAME[:SIZE_FACTOR]` without the files. At the default size factors the output is
//! the scene of the SPD files (`-r 1 -c`: NFF, curved primitives kept).

/// One SPD program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Program {
    /// `balls`, `gears`, …
    pub name: &'static str,
    /// The SPD's default size factor.
    pub default_size_factor: u32,
    /// Largest size factor accepted (memory and time stay reasonable).
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

/// Every program (temporary catalogue: the port fills it).
pub const PROGRAMS: &[Program] = &[Program {
    name: "balls",
    default_size_factor: 4,
    max_size_factor: 6,
    summary: "sphereflake: 1 + 9 + 81 + ... spheres over a ground polygon",
}];

/// The NFF text of `name` at `size_factor` (the SPD default when `None`).
pub fn generate(name: &str, size_factor: Option<u32>) -> Result<String, SpdError> {
    let program = find(name).ok_or_else(|| SpdError::UnknownProgram {
        name: name.to_string(),
    })?;
    let size_factor = size_factor.unwrap_or(program.default_size_factor);
    if !(1..=program.max_size_factor).contains(&size_factor) {
        return Err(SpdError::SizeFactor {
            name: program.name,
            size_factor,
            min: 1,
            max: program.max_size_factor,
        });
    }
    let options = tracer::generators::SphereflakeOptions {
        depth: size_factor,
        lights: tracer::generators::LightSet::Three,
        ground: true,
    };
    Ok(tracer::generators::sphereflake_with(&options).unwrap_or_default())
}
