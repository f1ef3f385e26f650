//! Links the rtprof binary as a position-dependent executable on Linux.
//!
//! As a position-independent executable (the default), every start of rtprof had the
//! dynamic loader apply about 85,000 relative relocations, one per pointer in the
//! binary's static data (most of them typst's and its fonts' tables, which a render
//! never reads), copying some 360 pages on write: about 1 ms of each process, more
//! than the rest of the loader and `main` together for a small render. Linked at a
//! fixed address, those pointers are final in the file and nothing is relocated
//! (scripts/startup-cost.py measures it). The cost: the binary's own code and data are
//! not address-randomised (libraries, stack and heap still are), which matters little
//! for a local profiling tool. The code is unchanged (it is compiled
//! position-independent either way); only the link differs. Set
//! `RTPROF_PIE=1` at build time to keep the default.

fn main() {
    println!("cargo:rerun-if-env-changed=RTPROF_PIE");
    let linux = std::env::var("CARGO_CFG_TARGET_OS").is_ok_and(|os| os == "linux");
    let keep_pie = std::env::var_os("RTPROF_PIE").is_some_and(|v| v == "1");
    if linux && !keep_pie {
        println!("cargo:rustc-link-arg-bins=-no-pie");
    }
}
