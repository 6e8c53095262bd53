#!/usr/bin/env bash
# Installs pkm's build and test dependencies from Debian packages (idempotent).
# Runs apt-get only for packages that are missing; uses sudo when not root.
#   --with-linuxcnc  also LinuxCNC (linuxcnc-uspace and linuxcnc-uspace-dev): the kinematics module pkmkins builds
#                    against it and make test runs it headless (docs/linuxcnc.md); its rs274 interpreter is
#                    the peer of the conformance suite (scripts/regen-rs274-golden.sh)
#   --with-browser   also Debian's Chromium, for the report's browser test (tests/browser/)
#   --with-fuzz      also clang with libFuzzer's runtime and llvm-symbolizer, for make fuzz (fuzz/)
# Node.js and npm build the HTML report's page (web/); a machine that has them already (any source) keeps its own.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev libyaml-cpp-dev libcli11-dev libfmt-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev libnlopt-cxx-dev libboost-dev libtbb-dev libhdf5-dev libdeflate-dev zlib1g-dev
  clang-format cppcheck
  pybind11-dev python3-dev python3-numpy python3-pytest python3-distributed python3-matplotlib python3-h5py
  python3-pip python3-venv python3-setuptools python3-wheel
)
if [ "${1:-}" = "--with-linuxcnc" ]; then packages+=(linuxcnc-uspace linuxcnc-uspace-dev); fi
if [ "${1:-}" = "--with-browser" ]; then packages+=(chromium); fi
if [ "${1:-}" = "--with-fuzz" ]; then packages+=(clang libclang-rt-dev llvm); fi
if ! command -v node > /dev/null || ! command -v npm > /dev/null; then packages+=(nodejs npm); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ "${#missing[@]}" -eq 0 ]; then
  exit 0
fi
echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
