#!/usr/bin/env bash
# Runs every check on a fresh machine with a Rust toolchain: installs what the tests need
# (cargo-nextest; the LIGGGHTS tutorial cases from Debian's liggghts-doc package, which the
# tutorial tests run; OpenMPI and libclang, to build and run rdem's `mpi` feature under
# mpirun; GNU time, which measures a run's peak memory; VTK's Python reader, with which
# tests read our VTK files), then formatting, clippy with warnings as errors (with and
# without MPI), the doc tests and the whole test suite with the `mpi` feature
# (cargo-nextest, release), then the Python package: a virtual environment (target/pyenv)
# with maturin, numpy, pytest and meshio (for the .pvd example) from pip, the wheel built
# and installed in it, and the Python tests. `.ci/run` calls this script.
# Usage: bash scripts/test.sh
set -euo pipefail
cd "$(dirname "$0")/.."

if ! cargo nextest --version >/dev/null 2>&1; then
  echo "cargo-nextest not found: installing it" >&2
  cargo install cargo-nextest --locked
fi
for component in rustfmt clippy; do
  if command -v rustup >/dev/null 2>&1 && ! rustup component list --installed 2>/dev/null | grep -q "^$component"; then
    rustup component add "$component"
  fi
done
tutorials=/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public
packages=()
[ -d "$tutorials" ] || packages+=(liggghts-doc)
command -v mpirun >/dev/null 2>&1 || packages+=(openmpi-bin)
[ -e /usr/lib/x86_64-linux-gnu/openmpi/include/mpi.h ] || [ -e /usr/include/mpi.h ] \
  || dpkg -s libopenmpi-dev >/dev/null 2>&1 || packages+=(libopenmpi-dev)
dpkg -s libclang-dev >/dev/null 2>&1 || packages+=(libclang-dev)
[ -x /usr/bin/time ] || packages+=(time)
if [ ${#packages[@]} -gt 0 ]; then
  echo "installing Debian packages: ${packages[*]}" >&2
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -q --no-install-recommends "${packages[@]}" >/dev/null
fi

if ! python3 -c "import vtk" >/dev/null 2>&1; then
  echo "VTK's Python reader not found: installing it (pip install vtk)" >&2
  python3 -m pip install --quiet vtk
fi

# Each traced command shows the seconds since the start, so a slow step stands out.
export PS4='+ [${SECONDS}s] '
# No debug info in the release builds of this script (the workspace keeps it for
# profiling): the builds and links are the longest part of the run.
export CARGO_PROFILE_RELEASE_DEBUG=0
set -x
cargo fmt --all -- --check
cargo clippy --workspace --all-targets -- -D warnings
cargo clippy --workspace --all-targets --features rdem-cli/mpi -- -D warnings
# Doc tests first, so that the last summary printed is the test suite's; with the features
# of the suite, so that both use one release build of the libraries.
cargo test --workspace --doc --release --features rdem-cli/mpi
# The MPI tests start mpirun themselves (--oversubscribe, so they run on 2 cores too).
cargo nextest run --workspace --release --features rdem-cli/mpi --no-fail-fast

# The Python package: the wheel built by maturin, installed in a virtual environment.
python3 -m venv target/pyenv
target/pyenv/bin/python -m pip install --quiet --upgrade maturin numpy pytest meshio
rm -rf target/wheels-test
# With the suite's features, so that the wheel links the engine the suite has just built
# instead of building it a second time (crates/rdem-py/Cargo.toml says how the two builds
# are kept alike); `--compatibility linux`: this wheel links the machine's libmpi, and is
# for the tests here, not for PyPI.
target/pyenv/bin/maturin build --release --quiet --features rdem-cli/mpi --compatibility linux \
  --out target/wheels-test
target/pyenv/bin/python -m pip install --quiet --force-reinstall --no-deps target/wheels-test/rdem-*.whl
target/pyenv/bin/python -m pytest -q python/tests
