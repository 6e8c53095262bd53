#!/usr/bin/env bash
# Uses the Debian package make package built (BUILD/pkm_*.deb) as a user would, from a root of its own: the
# installed pkm answers its version (the project's), plans a shipped example, reads a CL program; the man page,
# the bash completion and the documentation are where Debian puts them; the Python module imports; an outside
# project builds against the installed libraries with find_package(pkm).
set -euo pipefail
build=${1:?usage: scripts/package-test.sh BUILD}
cd "$(dirname "$0")/.."
deb=$(ls "$build"/pkm_*.deb)
root=$(mktemp -d)
trap 'rm -rf "$root"' EXIT
dpkg-deb -x "$deb" "$root"
pkm="$root/usr/bin/pkm"
version=$(sed -n 's/^project(pkm VERSION \([0-9.]*\).*/\1/p' CMakeLists.txt)
[ "$("$pkm" --version)" = "pkm $version" ] || { echo "package-test: pkm --version says '$("$pkm" --version)', not pkm $version"; exit 1; }
[ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || { echo "package-test: the package's version is not $version"; exit 1; }
"$pkm" plan examples/programs/ch5_line.ngc --machine examples/machines/hexapod_ch5.yaml --out "$root/run" > /dev/null
[ -s "$root/run/summary.json" ] || { echo "package-test: the installed pkm wrote no summary"; exit 1; }
"$pkm" interpret examples/programs/ball_end_5axis.cl --count | grep -q "(NX CLSF)"
for f in usr/share/man/man1/pkm.1 usr/share/bash-completion/completions/pkm usr/share/doc/pkm/LICENSE \
         usr/share/doc/pkm/CHANGELOG.md; do
  [ -s "$root/$f" ] || { echo "package-test: $f is missing"; exit 1; }
done
config=$(find "$root/usr/lib" -path '*/cmake/pkm/pkmConfig.cmake' | head -n 1)
[ -n "$config" ] || { echo "package-test: no cmake/pkm/pkmConfig.cmake under /usr/lib"; exit 1; }
site="$root/usr/lib/python3/dist-packages"
[ "$(PYTHONPATH="$site" /usr/bin/python3 -c 'import pkm; print(pkm.__version__)')" = "$version" ] \
  || { echo "package-test: the installed Python module does not import, or is not version $version"; exit 1; }
# An outside project finds the installed libraries with find_package(pkm) (examples/consumer).
cmake -S examples/consumer -B "$root/consumer" -DCMAKE_PREFIX_PATH="$root/usr" > /dev/null
cmake --build "$root/consumer" -j "$(nproc)" > /dev/null
"$root/consumer/pkm_plan_consumer" examples/machines/hexapod_ch5.yaml > /dev/null
# Every command of the documentation, as written, with the installed pkm and Python module.
/usr/bin/python3 scripts/doc-commands.py --bin "$root/usr/bin" --python-site "$site"
# pip install . as docs/python.md says, into a virtual environment that sees Debian's numpy, built in the
# configured build folder (a fresh one would build the library again: the same CMake build, minutes on CI).
venv="$root/venv"
/usr/bin/python3 -m venv --system-site-packages "$venv"
PKM_CMAKE_BUILD_DIR="$build" "$venv/bin/pip" install --quiet --no-build-isolation --no-deps --no-index . \
  || { echo "package-test: pip install . failed"; exit 1; }
[ "$(cd "$root" && "$venv/bin/python" -c 'import pkm; print(pkm.__version__, pkm.__file__.startswith("'"$venv"'"))')" = "$version True" ] \
  || { echo "package-test: the module pip installed does not import from the environment, or is not version $version"; exit 1; }
bash -c "source '$root/usr/share/bash-completion/completions/pkm'; COMP_WORDS=(pkm interpret --fo); COMP_CWORD=2; _pkm; [ \"\${COMPREPLY[*]}\" = --format ]" \
  || { echo "package-test: the bash completion does not complete 'pkm interpret --fo'"; exit 1; }
echo "package-test: $(basename "$deb") installs pkm $version (plans, reads CL data, man page, completion, find_package(pkm), Python module, the documentation's commands, pip install .)"
