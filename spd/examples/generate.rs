//! Writes one SPD scene as NFF and reports the time taken:
//! `cargo run --release -p spd --example generate -- NAME [SIZE_FACTOR] [> out.nff]`.
//! Without a redirect, only the timing line is printed (on stderr) and the text is
//! dropped; `--stdout` writes it.

use std::io::Write as _;
use std::time::Instant;

fn main() -> std::process::ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let to_stdout = args.iter().any(|a| a == "--stdout");
    let positional: Vec<&String> = args.iter().filter(|a| !a.starts_with("--")).collect();
    let Some(name) = positional.first() else {
        eprintln!(
            "usage: generate NAME [SIZE_FACTOR] [--stdout]   (names: {})",
            spd::names().join(", ")
        );
        return std::process::ExitCode::FAILURE;
    };
    let size_factor = match positional.get(1).map(|s| s.parse::<u32>()) {
        None => None,
        Some(Ok(n)) => Some(n),
        Some(Err(e)) => {
            eprintln!("bad size factor: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    let start = Instant::now();
    let text = match spd::generate(name, size_factor) {
        Ok(text) => text,
        Err(e) => {
            eprintln!("{e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    let elapsed = start.elapsed();
    let header = text.lines().next().unwrap_or("");
    eprintln!(
        "{header}\n{} bytes in {:.3} s",
        text.len(),
        elapsed.as_secs_f64()
    );
    if to_stdout && std::io::stdout().lock().write_all(text.as_bytes()).is_err() {
        return std::process::ExitCode::FAILURE;
    }
    std::process::ExitCode::SUCCESS
}
