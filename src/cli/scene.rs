//! `rtprof scene`: the project's scenes. `list` names the built-in ones; `gen` writes a
//! generated scene (sphereflake, lattice) as NFF.

use anyhow::{Context, Result};
use std::path::PathBuf;
use tracer::image_io::write_atomically;

#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    #[command(subcommand)]
    command: SceneCommand,
}

#[derive(clap::Subcommand, Debug)]
enum SceneCommand {
    /// List the built-in scenes (usable by name wherever a scene is asked for).
    List,
    /// Generate a scene as NFF.
    Gen(GenArgs),
}

#[derive(clap::Args, Debug)]
struct GenArgs {
    #[command(subcommand)]
    kind: GenKind,
    /// Output NFF file (default: standard output).
    #[arg(short, long, value_name = "FILE.nff", global = true)]
    output: Option<PathBuf>,
}

#[derive(clap::Subcommand, Debug)]
enum GenKind {
    /// Eric Haines's recursive sphereflake: 1 + 9 + 81 + … spheres (depth 4: 7381).
    Sphereflake {
        /// Recursion depth (0-6).
        #[arg(long, default_value_t = 3)]
        depth: u32,
    },
    /// An n×n×n lattice of spheres joined by cylinders (a heavy mixed scene).
    Lattice {
        /// Spheres per side (1-40).
        #[arg(long, default_value_t = 5)]
        side: u32,
    },
}

pub fn run(args: &SceneArgs) -> Result<()> {
    match &args.command {
        SceneCommand::List => {
            print!("{}", tracer::builtin_scenes::list_text());
            Ok(())
        }
        SceneCommand::Gen(g) => {
            let text = match g.kind {
                GenKind::Sphereflake { depth } => tracer::generators::sphereflake(depth)?,
                GenKind::Lattice { side } => tracer::generators::lattice(side)?,
            };
            match &g.output {
                Some(path) => {
                    write_atomically(path, text.as_bytes())
                        .with_context(|| format!("cannot write {}", path.display()))?;
                    eprintln!("wrote {}", path.display());
                }
                None => print!("{text}"),
            }
            Ok(())
        }
    }
}
