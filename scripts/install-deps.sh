#!/usr/bin/env bash
# Installs the Debian 12 packages rigid needs, and only those that are missing.
# Idempotent and quick when everything is present: one `dpkg -s` per package.
# Usage: scripts/install-deps.sh [build|bench|fuzz]   (default: build; fuzz: build's packages
# without the node check)
# build includes clang: the tests build the exported C++ with clang++ as well as g++; `make fuzz`
# uses its libFuzzer and sanitizer runtimes.
# build also needs Node 20 and npm (the report page is bundled from web/ at build time; the
# browser tests drive Debian's chromium with playwright-core): they are checked, not installed
# (Debian 12's nodejs is 18), and a missing or old node stops here with the remedy.
# python3-mypy: python/tests/test_stubs.py checks the type stubs with mypy.stubtest.
set -euo pipefail

check_node() {
  local remedy="install Node 20 or newer with npm (e.g. from nodejs.org or NodeSource), or configure with -DRIGID_REPORT=OFF to build without the report page"
  if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
    echo "rigid: error: node and npm are needed to bundle the report page (web/); $remedy" >&2
    exit 1
  fi
  local major
  major=$(node -p 'process.versions.node.split(".")[0]' 2>/dev/null || echo 0)
  if [[ "$major" -lt 20 ]]; then
    echo "rigid: error: node $(node --version 2>/dev/null) is too old for the report page (web/ needs Node 20); $remedy" >&2
    exit 1
  fi
}
if [[ "${1:-build}" == "build" ]]; then check_node; fi

build_packages=(
  g++ cmake ninja-build pkg-config make
  libeigen3-dev libboost-dev libboost-math-dev libginac-dev libcln-dev
  libfmt-dev libspdlog-dev libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  libtinyxml2-dev
  openmpi-bin libopenmpi-dev
  libcgal-demo assimp-testmodels
  libgtest-dev libgmock-dev libbenchmark-dev
  libmujoco-dev libmujoco-samples
  pybind11-dev python3-dev python3-numpy python3-pytest python3-scipy python3-sympy python3-meshio
  python3-mypy
  python3-pip python3-setuptools python3-wheel python3-venv
  chromium
  clang
)
bench_packages=(libbullet-dev libode-dev)

wanted=("${build_packages[@]}")
if [[ "${1:-build}" == "bench" ]]; then wanted+=("${bench_packages[@]}"); fi

missing=()
for p in "${wanted[@]}"; do
  if ! dpkg -s "$p" >/dev/null 2>&1 || ! dpkg -s "$p" 2>/dev/null | grep -q '^Status: install ok installed'; then
    missing+=("$p")
  fi
done
if [[ ${#missing[@]} -eq 0 ]]; then
  exit 0
fi

echo "rigid: installing missing Debian packages: ${missing[*]}"
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
    echo "rigid: error: missing packages (${missing[*]}) and not root; run as root or install sudo" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
