# Two commands do all the set-up on a fresh Debian machine:
#   make run   installs what is missing, builds build/pkm and plans the shipped pocket program on the ch5 hexapod
#              (servo-rate actuator motion in build/run/: ticks.h5 with the actuators and path tables,
#              summary.json, and the HTML report build/run/report.html)
#   make test  installs what is missing, builds and runs the whole test suite
# Extra targets: make sanitize (tests under AddressSanitizer + UBSanitizer), make lint (clang-format check, cppcheck,
# no new function over 100 lines: scripts/function-sizes.py),
# make conformance (the G-code golden files against LinuxCNC's rs274), make browser-test (the HTML report in
# headless Chromium), make screenshots (the same, saving docs/images/report-*.png),
# make fuzz (the libFuzzer harnesses in fuzz/, built with clang + ASan/UBSan in build-fuzz/, FUZZ_SECONDS each),
# make nightly (the generated-program property suite at nightly size), make bench, make format, make tidy,
# make consumer (installs pkm::kinematics into build/install and builds and runs examples/consumer against it),
# make python (the Python module pkm in build/python, docs/python.md),
# make linuxcnc (the LinuxCNC kinematics module pkmkins, installed into LinuxCNC's modules: docs/linuxcnc.md).
JOBS ?= $(shell nproc)
BUILD ?= build
EXAMPLE ?= examples/machines/hexapod_ch5.yaml
PROGRAM ?= examples/programs/pocket.ngc
FUZZ_SECONDS ?= 60
# make sanitize also runs each libFuzzer harness for this long (0: not at all); its build has them.
SANITIZE_FUZZ_SECONDS ?= 6
# The Release build's flags when set (CI: "-O1 -DNDEBUG ...", the suite checks results, not speed;
# make bench measures speed in its own -O3 build). Empty: CMake's Release default (-O3 -DNDEBUG).
RELEASE_FLAGS ?=
# The whole-run tests that make sanitize leaves to make test (tests/sanitizer_skip.txt, one ctest name per line,
# without the " # GetParam() = ..." that ctest appends to parameterised ones); SANITIZE_SKIP= runs them too.
SANITIZE_SKIP ?= ^($(shell grep -v '^\#' tests/sanitizer_skip.txt | grep . | paste -sd'|'))( |$$)

.PHONY: deps configure build python linuxcnc run test sanitize lint conformance cl-real package package-test browser-test screenshots fuzz nightly bench format tidy consumer clean

# make test and make linuxcnc also install LinuxCNC (the module builds against it; the tests run it); make run
# does not need it.
deps:
	@bash scripts/install-deps.sh $(DEPS_FLAGS)
test linuxcnc: DEPS_FLAGS = --with-linuxcnc

# The library and the tests compile as unity builds (batches of 8 files): on CI's 2 cores that halves the build
# time. The benchmarks build in their own directory (make bench), so that make test does not wait for them.
configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPKM_WERROR=ON -DPKM_UNITY_LIB=ON -DPKM_UNITY_TESTS=ON -DPKM_BUILD_BENCH=OFF $(if $(RELEASE_FLAGS),-DCMAKE_CXX_FLAGS_RELEASE="$(RELEASE_FLAGS)") > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# The Python module alone (docs/python.md): build/python/pkm, used as PYTHONPATH=build/python /usr/bin/python3.
python: configure
	@cmake --build $(BUILD) -j $(JOBS) --target pkm_python

# The LinuxCNC modules (the kinematics pkmkins, the executor pkmexec): rtapi_app loads modules only from its own
# folder, so they are installed there (with sudo when not root). make test's LinuxCNC runs install them
# themselves when they run as root.
linuxcnc: configure
	@cmake --build $(BUILD) -j $(JOBS) --target pkmkins pkmexec
	@for m in pkmkins pkmexec; do \
		$$([ "$$(id -u)" -eq 0 ] || echo sudo) install -m 644 $(BUILD)/linuxcnc/$$m.so /usr/lib/linuxcnc/modules/$$m.so \
		&& echo "linuxcnc: installed /usr/lib/linuxcnc/modules/$$m.so"; done

# make run builds only what its job needs (the library and the CLI); make test builds the tests too.
# build/run is this target's own folder: --force lets it replace what an older pkm left there without a
# manifest (docs/reliability.md, output sets).
run: configure
	@cmake --build $(BUILD) -j $(JOBS) --target pkm
	$(BUILD)/pkm plan $(PROGRAM) --machine $(EXAMPLE) --out $(BUILD)/run --report $(BUILD)/run/report.html --force

# A fresh build directory starts from tests/test_costs.txt (the tests above 1 s, as ctest measured them in a
# clean-clone run), so that ctest starts the longest first (the LinuxCNC runs, which take turns on one lock)
# and the two cores end together; without it they started last and ran alone for over two minutes. ctest runs
# JOBS + 1 tests at a time, JOBS of them at most taking a core ("cpus" slots, Testing/cpus.json): the extra one is
# a LinuxCNC run, which mostly waits for real-time motion (before, it held one of the two cores for 160 s).
test: build
	@mkdir -p $(BUILD)/Testing/Temporary
	@[ -f $(BUILD)/Testing/Temporary/CTestCostData.txt ] || cp tests/test_costs.txt $(BUILD)/Testing/Temporary/CTestCostData.txt
	@printf '{"version": {"major": 1, "minor": 0}, "local": [{"cpus": [{"id": "0", "slots": %s}]}]}\n' $(JOBS) > $(BUILD)/Testing/cpus.json
	cd $(BUILD) && ctest --output-on-failure -j $$(($(JOBS) + 1)) --resource-spec-file Testing/cpus.json

# Under the sanitizers the generated-program suite runs 2 programs per machine (make test: 16; make nightly: 300).
# -g0: function names in the sanitizers' stack traces, no line tables (CI's compile time).
# Built as on a machine without Node.js (PKM_NODE not found): the library and tests must configure and build
# without the report page, and configuring must say so in one line (the Release build of make test has the page).
# The CLI's own tests (tests/cli/) are left to make test (CI's time on 2 cores); the CLI is built, other tests run it.
# The instrumentation covers the library, the CLI and the LinuxCNC bridge; the tests' own code links the runtime
# uninstrumented (CMakeLists.txt, pkm_sanitized), and UBSan's vptr check is off.
# Built with clang (installed with the fuzzing tools): it compiles the instrumented code about 1.5x faster than GCC.
# Unless SANITIZE_FUZZ_SECONDS is 0 (CI), the same build has the libFuzzer harnesses (PKM_FUZZ), run for that long
# each after the tests over their seeds and reproducers. Only the harnesses have coverage instrumentation there
# (on the whole library it doubles the suite's time); make fuzz is the coverage-guided run. A fresh build directory
# starts from tests/sanitizer_test_costs.txt (the tests above 1 s under the sanitizers, as ctest measured them),
# so that ctest starts the longest first and the two cores end together.
sanitize:
	@bash scripts/install-deps.sh --with-fuzz
	@mkdir -p build-asan
	@cmake -S . -B build-asan -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g0" -DPKM_SANITIZE=ON -DPKM_PYTHON=OFF -DPKM_FUZZ=$(if $(filter 0,$(SANITIZE_FUZZ_SECONDS)),OFF,ON) -DPKM_BUILD_BENCH=OFF -DPKM_WERROR=ON -DPKM_UNITY_LIB=ON -DPKM_UNITY_TESTS=ON -DPKM_NODE=/none/node -DPKM_NPM=/none/npm > build-asan/configure.log
	@grep "building without the HTML report page: Node.js or npm not found" build-asan/configure.log
	@cmake --build build-asan -j $(JOBS) --target pkm_tests pkm $(if $(filter 0,$(SANITIZE_FUZZ_SECONDS)),,pkm_fuzzers)
	@mkdir -p build-asan/Testing/Temporary
	@[ -f build-asan/Testing/Temporary/CTestCostData.txt ] || cp tests/sanitizer_test_costs.txt build-asan/Testing/Temporary/CTestCostData.txt
	cd build-asan && PKM_GENERATED_PROGRAMS=2 PKM_HONEST_PROGRAMS=4 PKM_RANDOM_GEOMETRIES=1 ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS) -E '$(SANITIZE_SKIP)'
	@if [ "$(SANITIZE_FUZZ_SECONDS)" != 0 ]; then bash fuzz/run.sh build-asan $(SANITIZE_FUZZ_SECONDS); fi

# Formatting must match .clang-format; cppcheck must find nothing.
lint: deps
	@find src apps tests bench fuzz python linuxcnc tools -name '*.hpp' -o -name '*.cpp' | xargs clang-format --dry-run --Werror
	@cppcheck -j $(JOBS) --quiet --enable=warning,performance,portability --std=c++20 --language=c++ -I src \
		--suppress=missingIncludeSystem --inline-suppr --error-exitcode=1 src apps linuxcnc/module_machine.cpp linuxcnc/pkmkins_bridge.cpp linuxcnc/pkmexec_bridge.cpp
	@/usr/bin/python3 scripts/function-sizes.py --baseline scripts/function-sizes-allowed.txt src apps python/src linuxcnc > /dev/null
	@/usr/bin/python3 scripts/include-order.py
	@echo "lint: clean"

# The G-code conformance golden files must be what LinuxCNC's rs274 answers today (installs linuxcnc-uspace);
# then every sample program LinuxCNC ships, run by rs274 and by pkm interpret, must agree move by move unless
# tests/program/conformance/known.txt says why not (scripts/conformance-samples.py).
conformance: build
	@bash scripts/install-deps.sh --with-linuxcnc
	@bash scripts/regen-rs274-golden.sh --check
	@bash scripts/regen-cycle-golden.sh --check
	@bash scripts/regen-comp-golden.sh --check
	@/usr/bin/python3 scripts/conformance-samples.py --pkm $(BUILD)/pkm --jobs $(JOBS)

# Real CAM systems' CL files (docs/cl-data.md): CL_REAL=folder where the files of tests/program/cl_real_sources.tsv
# were fetched (their licences keep them out of the repository).
cl-real: build
	@test -n "$(CL_REAL)" || { echo "make cl-real CL_REAL=FOLDER: the folder holding the files listed in tests/program/cl_real_sources.tsv"; exit 2; }
	@/usr/bin/python3 scripts/cl-real-smoke.py "$(CL_REAL)" --pkm $(BUILD)/pkm

# The HTML report in headless Chromium (installs Debian's chromium): tests/browser/report_browser_test.mjs.
browser-test: build
	@bash scripts/install-deps.sh --with-browser
	node tests/browser/report_browser_test.mjs --pkm $(BUILD)/pkm --out $(BUILD)/browser-test

# The same, keeping screenshots of the reports for docs/images.
screenshots: build
	@bash scripts/install-deps.sh --with-browser
	node tests/browser/report_browser_test.mjs --pkm $(BUILD)/pkm --out $(BUILD)/browser-test --screenshots docs/images

# Each harness of fuzz/ for FUZZ_SECONDS, FUZZ_JOBS (nproc) at a time, on its corpus in build-fuzz/corpus/ (fuzz/run.sh);
# fails and prints the reproducer on a crash, leak, UB or timeout. Only the harnesses and the library are built,
# at -O1 with assertions on, so that a broken contract stops the run too.
fuzz:
	@bash scripts/install-deps.sh --with-fuzz
	@cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g1" \
		-DPKM_FUZZ=ON -DPKM_PYTHON=OFF -DPKM_BUILD_BENCH=OFF -DPKM_WERROR=ON -DPKM_UNITY_LIB=ON > /dev/null
	@cmake --build build-fuzz -j $(JOBS) --target pkm_fuzzers
	@bash fuzz/run.sh build-fuzz $(FUZZ_SECONDS)

# The generated CAM-like programs (tests/planning/generated_programs_test.cpp) on every shipped machine,
# NIGHTLY_PROGRAMS per machine instead of make test's 24, the corner-blend properties, and 200 programs per
# machine inside and outside the workspace that must be refused at a line or hold (plan_honesty_test.cpp).
NIGHTLY_PROGRAMS ?= 300
nightly: build
	PKM_GENERATED_PROGRAMS=$(NIGHTLY_PROGRAMS) PKM_HONEST_PROGRAMS=200 $(BUILD)/pkm_tests --gtest_filter='*GeneratedPrograms*:CornerBlend*:*PlanHonesty*'

bench: deps
	@cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DPKM_UNITY_LIB=ON -DPKM_BUILD_BENCH=ON > /dev/null
	@cmake --build build-bench -j $(JOBS)
	@for b in build-bench/bench/*; do $$b --benchmark_min_time=0.2; done
	PYTHONPATH=build-bench/python PKM_BINARY=build-bench/pkm /usr/bin/python3 bench/python/bench_batch.py
	PYTHONPATH=build-bench/python /usr/bin/python3 bench/python/bench_sweep.py

# The installed libraries from outside (docs/libraries.md): cmake --install into $(BUILD)/install, then
# examples/consumer, a separate CMake project (find_package(pkm)), built in $(BUILD)/consumer and run (IK and FK
# round trip of a hexapod on pkm::kinematics; a machine file read and a program planned on pkm::motion).
consumer: build
	@cmake --install $(BUILD) --prefix $(BUILD)/install > /dev/null
	@cmake -S examples/consumer -B $(BUILD)/consumer -DCMAKE_PREFIX_PATH=$(abspath $(BUILD))/install > /dev/null
	@cmake --build $(BUILD)/consumer -j $(JOBS)
	$(BUILD)/consumer/pkm_consumer
	$(BUILD)/consumer/pkm_plan_consumer examples/machines/hexapod_ch5.yaml

# The Debian package (cmake/package.cmake) in build/, and that package used as a user would: unpacked into a root
# of its own (dpkg-deb -x), its pkm run on an example, its man page and completion present, its version the
# project's.
package: build
	@cd $(BUILD) && cpack -G DEB > /dev/null && ls pkm_*.deb

package-test: package
	@bash scripts/package-test.sh $(BUILD)

format:
	@find src apps tests bench fuzz python linuxcnc tools -name '*.hpp' -o -name '*.cpp' | xargs clang-format -i

tidy: build
	@find src apps -name '*.cpp' | xargs clang-tidy -p $(BUILD) --quiet

clean:
	rm -rf build build-asan build-bench build-fuzz
