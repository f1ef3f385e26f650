//! `rtprof scene`: the scenes rtprof knows by name. `list` names them with their
//! primitive counts; `gen` writes any of them as NFF (an SPD database at any size
//! factor, a generator, a built-in scene).

use anyhow::{Context, Result};
use runner::scene_input::SceneInput;
use std::path::PathBuf;
use tracer::image_io::write_atomically;

#[derive(clap::Args, Debug)]
pub struct SceneArgs {
    #[command(subcommand)]
    command: SceneCommand,
}

#[derive(clap::Subcommand, Debug)]
#[command(defer = true)]
enum SceneCommand {
    /// List the scenes usable by name wherever a scene is asked for.
    List,
    /// Write a named scene as NFF: `rtprof scene gen spd:balls --size-factor 5 -o balls.nff`.
    Gen(GenArgs),
}

#[derive(clap::Args, Debug)]
struct GenArgs {
    #[arg(value_name = "NAME", value_parser = SceneInput::parse_arg, help = SceneInput::HELP)]
    name: SceneInput,
    /// SPD size factor (the same as spd:NAME:N) [default: the SPD's own].
    #[arg(long, value_name = "N")]
    size_factor: Option<u32>,
    /// Output NFF file [default: standard output].
    #[arg(short, long, value_name = "FILE.nff")]
    output: Option<PathBuf>,
}

pub fn run(args: &SceneArgs) -> Result<()> {
    match &args.command {
        SceneCommand::List => {
            print!("{}", runner::scene_input::catalogue_text());
            Ok(())
        }
        SceneCommand::Gen(g) => generate(g),
    }
}

fn generate(args: &GenArgs) -> Result<()> {
    let input = args.name.to_generate(args.size_factor)?;
    let text = input.text(&tracer::Limits::default())?;
    match &args.output {
        Some(path) => {
            write_atomically(path, text.as_bytes())
                .with_context(|| format!("cannot write {}", path.display()))?;
            eprintln!("wrote {} ({input})", path.display());
        }
        None => print!("{text}"),
    }
    Ok(())
}
