#!/usr/bin/env bash
# Installs the tools the RTL tests and `rtprof hw sim` / `hw synth` need (crate `rtl`,
# `cargo test -p rtl -- --ignored`): Verilator, which compiles the generated Verilog into
# C++; g++ and make, which build that model with its testbench; Yosys, which synthesizes
# it for Cyclone IV E; nextpnr-ice40, which places and routes an operator for a measured
# Fmax (rtl/tests/timing.rs). Debian packages, non-interactive; does nothing when all
# are already there. Needs root (or sudo) for apt-get.
set -euo pipefail
cd "$(dirname "$0")"

bash ./install-packages.sh --no-recommends verilator g++ make yosys nextpnr-ice40
verilator --version
yosys -V
nextpnr-ice40 --version
