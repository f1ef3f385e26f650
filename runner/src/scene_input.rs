//! A scene as a user names it, on any command line or in a suite: an NFF file, one of
//! the project's built-in scenes (`balls3`), an SPD database generated at a size factor
//! (`spd:rings`, `spd:balls:2`) or one of the project's generators (`sphereflake:3`,
//! `lattice:4`). One parser for every command, so `scene list` is true everywhere.

use std::fmt;
use std::path::{Path, PathBuf};

use results::SceneFamily;
use tracer::builtin_scenes::BuiltinScene;
use tracer::nff::parse_nff_with_limits;
use tracer::{Limits, Scene, load_nff_with_limits};

use crate::error::RunError;

/// The prefix of the SPD databases' names.
pub const SPD_PREFIX: &str = "spd:";

/// The project's own generators (`KIND:N`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Generator {
    /// Haines's sphereflake without the ground polygon: `sphereflake:DEPTH`.
    Sphereflake,
    /// Spheres on a cubic lattice joined by cylinders: `lattice:SIDE`.
    Lattice,
}

impl Generator {
    const ALL: [Generator; 2] = [Generator::Sphereflake, Generator::Lattice];

    pub fn name(self) -> &'static str {
        match self {
            Generator::Sphereflake => "sphereflake",
            Generator::Lattice => "lattice",
        }
    }

    fn text(self, n: u32) -> Result<String, tracer::generators::GeneratorError> {
        match self {
            Generator::Sphereflake => tracer::generators::sphereflake(n),
            Generator::Lattice => tracer::generators::lattice(n),
        }
    }
}

/// What a scene argument names.
#[derive(Clone, Debug, PartialEq)]
pub enum SceneInput {
    /// An NFF file.
    File(PathBuf),
    /// A scene embedded in the binary (`tracer::builtin_scenes`).
    Builtin(&'static BuiltinScene),
    /// An SPD database at a size factor.
    Spd {
        program: &'static spd::Program,
        size_factor: u32,
    },
    /// One of the project's generators with its parameter.
    Generated {
        generator: Generator,
        parameter: u32,
    },
}

impl SceneInput {
    /// The help of every command's scene argument: one list of what a scene can be.
    pub const HELP: &str = "NFF file, built-in scene (balls3) or generated scene (spd:rings, \
                            spd:balls:2 = size factor 2, sphereflake:3); `rtprof scene list` \
                            names them all";

    /// The scene to write by name (`rtprof scene gen NAME --size-factor N`): an SPD
    /// database at `size_factor`, or any named scene as it is; a file is not a name.
    pub fn to_generate(&self, size_factor: Option<u32>) -> Result<SceneInput, RunError> {
        match (self, size_factor) {
            (SceneInput::Spd { program, .. }, Some(n)) => {
                SceneInput::spd(program, n).map_err(|e| RunError::Scene {
                    scene: format!("{SPD_PREFIX}{}:{n}", program.name),
                    message: e.to_string(),
                })
            }
            (SceneInput::File(path), _) => Err(RunError::Input(format!(
                "{} is not a scene name: `rtprof scene list` names the scenes rtprof can write",
                path.display()
            ))),
            (other, Some(_)) => Err(RunError::Input(format!(
                "--size-factor is for spd:NAME scenes, not {other}"
            ))),
            (other, None) => Ok(other.clone()),
        }
    }

    /// A scene as a command-line argument (relative paths from the current directory).
    pub fn parse_arg(text: &str) -> Result<Self, String> {
        Self::parse(text, Path::new("")).map_err(|e| e.to_string())
    }

    /// The default output name for a command on this scene: `<prefix><scene
    /// name><suffix>` in the current directory.
    pub fn named_after(&self, prefix: &str, suffix: &str) -> std::path::PathBuf {
        std::path::PathBuf::from(format!("{prefix}{}{suffix}", self.name()))
    }

    /// Reads a scene argument; relative paths start at `base`. A file that exists wins
    /// over a built-in name; `spd:` and `KIND:N` names are checked here (unknown names,
    /// size factors out of range), so a bad argument fails before any work.
    pub fn parse(text: &str, base: &Path) -> Result<Self, RunError> {
        let bad = |message: String| RunError::Scene {
            scene: text.to_string(),
            message,
        };
        if let Some(rest) = text.strip_prefix(SPD_PREFIX) {
            let (name, factor) = match rest.split_once(':') {
                Some((name, factor)) => (name, Some(factor)),
                None => (rest, None),
            };
            let program = spd::find(name).ok_or_else(|| {
                bad(spd::SpdError::UnknownProgram {
                    name: name.to_string(),
                }
                .to_string())
            })?;
            let size_factor = match factor {
                Some(f) => f.parse().map_err(|_| {
                    bad(format!(
                        "'{f}' is not a size factor: expected spd:{name}:N with N a whole number"
                    ))
                })?,
                None => program.default_size_factor,
            };
            return Self::spd(program, size_factor).map_err(|e| bad(e.to_string()));
        }
        let path = base.join(text);
        if path.exists() {
            return Ok(SceneInput::File(path));
        }
        if let Some(builtin) = tracer::builtin_scenes::find(text) {
            return Ok(SceneInput::Builtin(builtin));
        }
        if let Some((kind, param)) = text.split_once(':')
            && let Some(generator) = Generator::ALL.into_iter().find(|g| g.name() == kind)
        {
            let parameter: u32 = param
                .parse()
                .map_err(|_| bad(format!("'{param}' is not a number: expected {kind}:N")))?;
            check_generator(generator, parameter).map_err(bad)?;
            return Ok(SceneInput::Generated {
                generator,
                parameter,
            });
        }
        Ok(SceneInput::File(path))
    }

    /// An SPD database at `size_factor`, range-checked.
    pub fn spd(program: &'static spd::Program, size_factor: u32) -> Result<Self, spd::SpdError> {
        spd::primitive_count(program.name, Some(size_factor))?;
        Ok(SceneInput::Spd {
            program,
            size_factor,
        })
    }

    /// A short name for results, images and default output files: the file stem, the
    /// built-in name, `rings` for an SPD database at its default size factor and
    /// `balls-sf2` at another, `sphereflake3`.
    pub fn name(&self) -> String {
        match self {
            SceneInput::File(path) => path.file_stem().map_or_else(
                || path.display().to_string(),
                |s| s.to_string_lossy().into_owned(),
            ),
            SceneInput::Builtin(b) => b.name.to_string(),
            SceneInput::Spd {
                program,
                size_factor,
            } if *size_factor == program.default_size_factor => program.name.to_string(),
            SceneInput::Spd {
                program,
                size_factor,
            } => format!("{}-sf{size_factor}", program.name),
            SceneInput::Generated {
                generator,
                parameter,
            } => format!("{}{parameter}", generator.name()),
        }
    }

    /// Where the scene comes from, for results: the path, `builtin`, `spd:NAME:N` or
    /// `generated`.
    pub fn source(&self) -> String {
        match self {
            SceneInput::File(path) => path.display().to_string(),
            SceneInput::Builtin(_) => "builtin".into(),
            SceneInput::Spd { .. } => self.to_string(),
            SceneInput::Generated { .. } => "generated".into(),
        }
    }

    /// The scene's family in results.
    pub fn family(&self) -> SceneFamily {
        match self {
            SceneInput::File(_) => SceneFamily::Other,
            SceneInput::Builtin(b) => SceneFamily::of_builtin(b.name),
            SceneInput::Spd { .. } => SceneFamily::Spd,
            SceneInput::Generated { .. } => SceneFamily::Generated,
        }
    }

    /// The NFF text: read (within `limits.max_file_bytes`) or generated.
    pub fn text(&self, limits: &Limits) -> Result<String, RunError> {
        let text = match self {
            SceneInput::File(path) => {
                let length = std::fs::metadata(path)
                    .map_err(|e| RunError::io("read", path, &e))?
                    .len();
                limits
                    .check_file_size(length)
                    .map_err(|e| RunError::refused(path.display(), &e))?;
                std::fs::read_to_string(path).map_err(|e| RunError::io("read", path, &e))?
            }
            SceneInput::Builtin(b) => b.text.to_string(),
            SceneInput::Spd {
                program,
                size_factor,
            } => spd::generate(program.name, Some(*size_factor)).map_err(|e| RunError::Scene {
                scene: self.to_string(),
                message: e.to_string(),
            })?,
            SceneInput::Generated {
                generator,
                parameter,
            } => generator.text(*parameter).map_err(|e| RunError::Scene {
                scene: self.to_string(),
                message: e.to_string(),
            })?,
        };
        Ok(text)
    }

    /// The parsed scene, within `limits`; parse errors name the file (or the built-in
    /// name) and the line.
    pub fn load(&self, limits: &Limits) -> Result<Scene, RunError> {
        match self {
            SceneInput::File(path) => {
                load_nff_with_limits(path, limits).map_err(|e| RunError::load(&e))
            }
            SceneInput::Spd {
                program,
                size_factor,
            } => {
                // The NFF text, and the SPD surface terms it cannot hold (for the
                // POV-Ray writer: `tracer::Scene::surface_terms`).
                let (text, terms) =
                    spd::generate_with_surface_terms(program.name, Some(*size_factor)).map_err(
                        |e| RunError::Scene {
                            scene: self.to_string(),
                            message: e.to_string(),
                        },
                    )?;
                let mut scene = parse_nff_with_limits(&text, &self.to_string(), limits)
                    .map_err(|e| RunError::parse(&e))?;
                spd::add_surface_terms(&mut scene, &terms);
                Ok(scene)
            }
            _ => {
                let text = self.text(limits)?;
                parse_nff_with_limits(&text, &self.to_string(), limits)
                    .map_err(|e| RunError::parse(&e))
            }
        }
    }
}

/// Every name a scene argument accepts besides a file, with primitive counts
/// (`rtprof scene list`).
pub fn catalogue_text() -> String {
    use reports::format::kind_count;
    let mut text =
        String::from("Built-in scenes (the thesis's test bench and the project's own):\n");
    for b in tracer::builtin_scenes::all() {
        text += &format!(
            "  {:<22} {:<9} {}\n",
            b.name,
            b.family,
            kind_count(b.primitives as u64, "primitives")
        );
    }
    text += "\nSPD databases, generated (spd:NAME at the SPD's size factor, spd:NAME:N at N):\n";
    for p in spd::PROGRAMS {
        let count = spd::primitive_count(p.name, None).unwrap_or(0);
        let range = if p.max_size_factor == 1 {
            "size factor 1 only".to_string()
        } else {
            format!(
                "size factor {} (1-{})",
                p.default_size_factor, p.max_size_factor
            )
        };
        text += &format!(
            "  {:<22} {:<24} {:>18}  {}\n",
            format!("{SPD_PREFIX}{}", p.name),
            range,
            kind_count(count, "primitives"),
            p.summary
        );
    }
    text += "\nGenerators (KIND:N):\n";
    use tracer::generators::{MAX_LATTICE_SIDE, MAX_SPHEREFLAKE_DEPTH, sphereflake_sphere_count};
    text += &format!(
        "  {:<22} N = 0-{MAX_SPHEREFLAKE_DEPTH}: {} (N = 4); the SPD balls without its ground\n",
        "sphereflake:N",
        kind_count(sphereflake_sphere_count(4), "spheres")
    );
    text += &format!(
        "  {:<22} N = 1-{MAX_LATTICE_SIDE}: N^3 spheres and 3 N^2 (N-1) cylinders ({} for N = 5)\n",
        "lattice:N",
        kind_count(5 * 5 * 5 + 3 * 5 * 5 * 4, "primitives")
    );
    text
}

/// The generators' ranges, without generating.
fn check_generator(generator: Generator, parameter: u32) -> Result<(), String> {
    use tracer::generators::{GeneratorError, MAX_LATTICE_SIDE, MAX_SPHEREFLAKE_DEPTH};
    let error = match generator {
        Generator::Sphereflake if parameter > MAX_SPHEREFLAKE_DEPTH => {
            GeneratorError::SphereflakeTooDeep { depth: parameter }
        }
        Generator::Lattice if !(1..=MAX_LATTICE_SIDE).contains(&parameter) => {
            GeneratorError::LatticeSide { side: parameter }
        }
        _ => return Ok(()),
    };
    Err(error.to_string())
}

/// The spelling that names the scene again: the path, the built-in name,
/// `spd:NAME:N`, `KIND:N`.
impl fmt::Display for SceneInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SceneInput::File(path) => write!(f, "{}", path.display()),
            SceneInput::Builtin(b) => f.write_str(b.name),
            SceneInput::Spd {
                program,
                size_factor,
            } => write!(f, "{SPD_PREFIX}{}:{size_factor}", program.name),
            SceneInput::Generated {
                generator,
                parameter,
            } => write!(f, "{}:{parameter}", generator.name()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<SceneInput, RunError> {
        SceneInput::parse(text, Path::new("/nonexistent"))
    }

    #[test]
    fn names_resolve_to_spd_builtins_generators_and_files() {
        let rings = parse("spd:rings").unwrap();
        let program = spd::find("rings").unwrap();
        assert_eq!(
            rings,
            SceneInput::Spd {
                program,
                size_factor: program.default_size_factor
            }
        );
        assert_eq!(rings.name(), "rings");
        assert_eq!(rings.family(), SceneFamily::Spd);
        let balls2 = parse("spd:balls:2").unwrap();
        assert_eq!(balls2.name(), "balls-sf2");
        assert_eq!(balls2.to_string(), "spd:balls:2");
        // Round trip: the display names the same scene.
        assert_eq!(parse(&balls2.to_string()).unwrap(), balls2);
        assert_eq!(parse("both3").unwrap().family(), SceneFamily::Both);
        assert_eq!(parse("sphereflake:1").unwrap().name(), "sphereflake1");
        assert_eq!(
            parse("scene.nff").unwrap(),
            SceneInput::File(PathBuf::from("/nonexistent/scene.nff"))
        );
    }

    #[test]
    fn bad_names_say_what_is_wrong() {
        let message = |text: &str| parse(text).unwrap_err().to_string();
        assert!(message("spd:cube").contains("unknown SPD scene 'cube'"));
        assert!(message("spd:balls:x").contains("'x' is not a size factor"));
        assert!(message("spd:balls:99").contains("size factor 99 is out of range"));
        assert!(message("sphereflake:9").contains("too large"));
        assert!(message("lattice:0").contains("out of range"));
        let missing = parse("no-such.nff")
            .unwrap()
            .load(&Limits::default())
            .unwrap_err();
        assert!(
            missing.to_string().contains("/nonexistent/no-such.nff"),
            "{missing}"
        );
    }

    #[test]
    fn generated_scenes_load_with_the_counts_their_names_promise() {
        let limits = Limits::default();
        let flake = parse("sphereflake:1").unwrap().load(&limits).unwrap();
        assert_eq!(flake.spheres.len(), 1 + 9);
        let balls = parse("spd:balls:1").unwrap().load(&limits).unwrap();
        // The generator's ambient term of the floor, which the NFF text cannot hold.
        assert_eq!(balls.surface_terms(0).map(|t| t.ambient), Some(0.2));
        // SPD balls: the sphereflake and its ground polygon.
        assert_eq!((balls.spheres.len(), balls.polygons.len()), (10, 1));
    }
}
