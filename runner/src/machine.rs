//! What a run was made on and with: the machine (CPU, cores, OS, host), the build
//! (rtprof version, rustc, git commit, profile; recorded by `build.rs`), the command
//! line that reproduces it and when it started.

use results::{Build, Machine, rfc3339_utc};

fn first_line(path: &str, prefix: &str) -> Option<String> {
    std::fs::read_to_string(path).ok()?.lines().find_map(|l| {
        l.strip_prefix(prefix)
            .map(|rest| rest.trim_start_matches([' ', '\t', ':']).trim().to_string())
    })
}

/// This machine, read from /proc where it exists.
pub fn machine() -> Machine {
    let read = |p: &str| {
        std::fs::read_to_string(p)
            .ok()
            .map(|s| s.trim().to_string())
    };
    Machine {
        cpu_model: first_line("/proc/cpuinfo", "model name").unwrap_or_else(|| "unknown".into()),
        cores: std::thread::available_parallelism().map_or(1, |n| n.get() as u32),
        os: match (
            read("/proc/sys/kernel/ostype"),
            read("/proc/sys/kernel/osrelease"),
        ) {
            (Some(a), Some(b)) => format!("{a} {b}"),
            _ => std::env::consts::OS.to_string(),
        },
        hostname: read("/proc/sys/kernel/hostname").unwrap_or_else(|| "unknown".into()),
    }
}

/// This build.
pub fn build_info() -> Build {
    Build {
        rtprof_version: env!("CARGO_PKG_VERSION").to_string(),
        rustc: env!("RTPROF_RUSTC").to_string(),
        git_commit: env!("RTPROF_GIT_COMMIT").to_string(),
        profile: if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        }
        .to_string(),
    }
}

/// The command line of this process as a shell would accept it, named `rtprof`.
pub fn command_line() -> String {
    let args: Vec<String> = std::env::args()
        .skip(1)
        .map(|a| {
            if a.chars()
                .all(|c| c.is_ascii_alphanumeric() || "-_./=:,+".contains(c))
            {
                a
            } else {
                format!("'{}'", a.replace('\'', r"'\''"))
            }
        })
        .collect();
    format!("rtprof {}", args.join(" "))
}

/// Now, RFC 3339 UTC.
pub fn now_rfc3339() -> String {
    rfc3339_utc(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_secs()),
    )
}
