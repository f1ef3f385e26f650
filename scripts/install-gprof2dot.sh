#!/usr/bin/env bash
# Installs what the gprof tests need (tests/gprof2dot.rs, analysis/tests/gprof_import.rs,
# run with `-- --ignored`): gcc and binutils' gprof (Debian packages), to build a `-pg`
# program and print its profile, and gprof2dot (PyPI, pinned), the usual reader of
# gprof's text, which must read rtprof's call graph as it reads gprof's. The tests run
# it as `python3 -m gprof2dot`, the module pip installs (its `gprof2dot` script may not
# be on PATH). Does nothing when all are there. Needs root (or sudo) for apt-get.
set -euo pipefail
cd "$(dirname "$0")"

version=2025.4.14

bash ./install-packages.sh --no-recommends gcc binutils python3
installed=$(python3 -m pip show gprof2dot 2>/dev/null | sed -n 's/^Version: //p' || true)
if [ "$installed" != "$version" ]; then
    if ! python3 -m pip --version > /dev/null 2>&1; then
        bash ./install-packages.sh --no-recommends python3-pip
    fi
    echo "install-gprof2dot: installing gprof2dot $version"
    # Debian's own Python refuses pip outside a virtual environment (PEP 668); the
    # package is one pure-Python module, so installing it beside the system's is safe.
    python3 -m pip install --quiet --disable-pip-version-check "gprof2dot==$version" 2> /dev/null \
        || python3 -m pip install --quiet --disable-pip-version-check --break-system-packages "gprof2dot==$version"
fi
python3 -m gprof2dot --help > /dev/null
echo "install-gprof2dot: gprof2dot $version ($(python3 -m pip show gprof2dot | sed -n 's/^Location: //p')), $(gprof --version | head -1), $(gcc --version | head -1)"
