# Flags of the fuzz build (PKM_FUZZ, make fuzz): coverage for libFuzzer plus ASan + UBSan on every target of
# that build directory. Harness executables add the libFuzzer main themselves (fuzz/CMakeLists.txt).
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR "PKM_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
endif()
# UB must stop the run (a report that recovers would not count as a crash for libFuzzer).
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined
                    -fno-omit-frame-pointer)
add_link_options(-fsanitize=address,undefined)
# The library silences GCC-only warnings by name (#pragma GCC diagnostic); clang need not know them.
add_compile_options(-Wno-unknown-warning-option)
