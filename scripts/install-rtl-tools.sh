#!/usr/bin/env bash
# Installs the tools the RTL tests and `rtprof hw sim` / `hw synth` need (crate `rtl`,
# `cargo test -p rtl -- --ignored`): Verilator, which compiles the generated Verilog into
# C++; g++ and make, which build that model with its testbench; Yosys, which synthesizes
# it for Cyclone IV E. Debian packages, non-interactive; does nothing when all are
# already there. Needs root (or sudo) for apt-get.
set -euo pipefail

missing=()
command -v verilator >/dev/null 2>&1 || missing+=(verilator)
command -v g++ >/dev/null 2>&1 || missing+=(g++)
# Verilator's generated makefiles call make.
command -v make >/dev/null 2>&1 || missing+=(make)
command -v yosys >/dev/null 2>&1 || missing+=(yosys)

if [ "${#missing[@]}" -eq 0 ]; then
    echo "install-rtl-tools: verilator, g++, make and yosys are installed"
    verilator --version
    yosys -V
    exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
    sudo="sudo"
fi

echo "install-rtl-tools: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
verilator --version
yosys -V
