#!/usr/bin/env bash
# Installs the named Debian packages that are not installed yet, with one `apt-get update`
# and one `apt-get install` (non-interactive); does nothing when all are there. Needs root
# (or sudo). The one place the project's scripts and CI install system packages.
#
#   scripts/install-packages.sh [--no-recommends] PACKAGE...
set -euo pipefail

recommends=()
if [ "${1:-}" = "--no-recommends" ]; then
    recommends=(--no-install-recommends)
    shift
fi
if [ "$#" -eq 0 ]; then
    echo "install-packages: name at least one Debian package" >&2
    exit 2
fi

missing=()
for package in "$@"; do
    # `dpkg -s` also lists removed packages whose configuration remains: ask for the state.
    state=$(dpkg-query -W -f='${db:Status-Status}' "$package" 2>/dev/null || true)
    [ "$state" = "installed" ] || missing+=("$package")
done
if [ "${#missing[@]}" -eq 0 ]; then
    echo "install-packages: $* already installed"
    exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
    sudo="sudo"
fi
echo "install-packages: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${recommends[@]}" "${missing[@]}" >/dev/null
echo "install-packages: installed ${missing[*]}"
