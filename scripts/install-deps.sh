#!/usr/bin/env bash
# Installs mechgraph's dependencies from Debian 12 packages (only what is missing): everything, or
# with --study only what building the program and its plugins needs.
set -euo pipefail
# What building `mechgraph` and its plugins needs (scripts/run-study.sh installs only these) ...
packages=(cmake g++ ninja-build ccache pkg-config
          libboost-dev libboost-program-options-dev libboost-filesystem-dev
          libeigen3-dev libspdlog-dev libyaml-cpp-dev catch2 libsundials-dev libdxflib-dev)
# ... and what the reports, the Python module, the benchmarks and the whole test suite add.
if [ "${1:-}" != "--study" ]; then
  packages+=(python3-pint python3-tqdm)  # the Python module: units (pint), sweep progress bars (tqdm)
  packages+=(time)  # /usr/bin/time -f %M: the resident size of merge (tests/hostile/hostile_outputs_test.cpp)
  packages+=(git)   # python/tests/test_pip_install.py copies what git tracks
  packages+=(locales)  # the locales' sources: python/tests/test_locale.py makes a German locale (localedef)
  packages+=(libbenchmark-dev gnuplot-nox python3-ezdxf chromium python3-pil graphviz poppler-utils
             pybind11-dev python3-pybind11 python3-numpy python3-pandas python3-scipy python3-matplotlib
             python3-pytest python3-venv python3-pip python3-setuptools python3-wheel python3-distributed python3-nbclient python3-ipykernel python3-nbformat
             clang abigail-tools libc++-dev libc++abi-dev  # the SDK checks: C headers under clang, abidw/abidiff, a libc++ plugin
             libclang-rt-14-dev  # clang's sanitizer runtimes and libFuzzer (scripts/run-fuzzers.sh)
             python3-openturns)  # the uncertainty study checked against OpenTURNS (python/tests/test_study_openturns.py)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "installing: ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
fi
