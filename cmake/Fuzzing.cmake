# Coverage instrumentation for the fuzz build (issue 38, part 0).
#
# libFuzzer and AFL++ steer their mutations by the edges an input reaches, and only code compiled
# with coverage instrumentation reports edges. Compiling the harness alone with -fsanitize=fuzzer
# left the libraries it calls (predicates, io, engine, generators) dark: the fuzzer saw the
# harness file and the headers inlined into it, not the code under test. So every dtlab library
# a harness links is compiled with -fsanitize=fuzzer-no-link (instrumented, no fuzzer main), and
# the harness itself with -fsanitize=fuzzer. The CGAL oracle (dtlab_cgal_reference) stays dark on
# purpose: it is the reference, not the code under test, and its edges would only make the
# fuzzer explore CGAL.
#
# DTLAB_FUZZ_ENGINE picks who reads the edges:
#   libfuzzer  clang++ (the `fuzz` preset); counters as inline 8-bit counters;
#   afl        afl-clang-fast++ as the compiler (the `afl` preset). afl-cc instruments every
#              translation unit it compiles; the allowlist fuzz/afl_allowlist.txt limits that to
#              dtlab's own sources (the same set as for libFuzzer), and -fsanitize=fuzzer at link
#              time becomes AFL++'s libAFLDriver.
set(DTLAB_FUZZ_ENGINE "libfuzzer" CACHE STRING "Fuzzing engine of the harnesses: libfuzzer or afl")
set_property(CACHE DTLAB_FUZZ_ENGINE PROPERTY STRINGS libfuzzer afl)
if(NOT DTLAB_FUZZ_ENGINE MATCHES "^(libfuzzer|afl)$")
  message(FATAL_ERROR "DTLAB_FUZZ_ENGINE must be libfuzzer or afl, not '${DTLAB_FUZZ_ENGINE}'")
endif()

# The libraries under test, compiled with coverage instrumentation in a fuzz build.
set(DTLAB_FUZZ_INSTRUMENTED_LIBRARIES dtlab_predicates dtlab_io dtlab_generators dtlab_engine)

# afl: afl-cc reads the allowlist from the environment of each compile; the launcher must be set
# before the targets are made, so this file is included before the libraries' folders.
if(DTLAB_BUILD_FUZZERS AND DTLAB_FUZZ_ENGINE STREQUAL "afl")
  set(CMAKE_CXX_COMPILER_LAUNCHER
    "${CMAKE_COMMAND};-E;env;AFL_LLVM_ALLOWLIST=${PROJECT_SOURCE_DIR}/fuzz/afl_allowlist.txt")
endif()

# libfuzzer: called once the libraries exist (fuzz/CMakeLists.txt).
function(dtlab_instrument_for_libfuzzer)
  foreach(library IN LISTS DTLAB_FUZZ_INSTRUMENTED_LIBRARIES)
    target_compile_options(${library} PRIVATE -fsanitize=fuzzer-no-link)
  endforeach()
endfunction()
