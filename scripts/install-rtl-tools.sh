#!/usr/bin/env bash
# Installs the tools the RTL tests need (crate `rtl`, `cargo test -p rtl -- --ignored`):
# Verilator, which compiles the operators' Verilog into C++, and g++, which builds that
# model with its testbench. Debian packages, non-interactive; does nothing when both
# are already there. Needs root (or sudo) for apt-get.
set -euo pipefail

missing=()
command -v verilator >/dev/null 2>&1 || missing+=(verilator)
command -v g++ >/dev/null 2>&1 || missing+=(g++)
# Verilator's generated makefiles call make.
command -v make >/dev/null 2>&1 || missing+=(make)

if [ "${#missing[@]}" -eq 0 ]; then
    echo "install-rtl-tools: verilator, g++ and make are installed"
    verilator --version
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
