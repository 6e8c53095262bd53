# Flags of the fuzz build (PKM_FUZZ, make fuzz): coverage for libFuzzer plus ASan + UBSan on every target of
# that build directory. Harness executables add the libFuzzer main themselves (fuzz/CMakeLists.txt).
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "PKM_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
endif()
# UB must stop the run (a report that recovers would not count as a crash for libFuzzer). In the sanitizer build
# (PKM_SANITIZE: make sanitize) the library keeps the sanitizers' flags only: coverage instrumentation doubles
# the run time of the test suite there, so only the harnesses themselves are instrumented (fuzz/CMakeLists.txt)
# and CI's short runs are a smoke test over the seeds and the reproducers; make fuzz is the coverage-guided
# fuzzing.
if(NOT PKM_SANITIZE)
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
# The library silences GCC-only warnings by name (#pragma GCC diagnostic); clang need not know them.
add_compile_options(-Wno-unknown-warning-option)
