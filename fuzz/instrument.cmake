# Included by the top-level CMakeLists.txt when RTSIM_FUZZ is ON, before any library is defined:
# every library is compiled with libFuzzer's coverage instrumentation and AddressSanitizer and
# UndefinedBehaviorSanitizer, so the fuzz targets in fuzz/ (linked with -fsanitize=fuzzer) get
# coverage from the parsers and every memory or UB error aborts. docs/fuzzing.md.

if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR
    "RTSIM_FUZZ=ON needs clang (libFuzzer is part of clang), but the C++ compiler is "
    "${CMAKE_CXX_COMPILER_ID} (${CMAKE_CXX_COMPILER}). Configure a separate build folder with "
    "CXX=clang++ (Debian packages clang, llvm), or use scripts/fuzz.sh.")
endif()

# -fno-sanitize-recover: an undefined-behaviour report aborts, so libFuzzer records it as a crash
# instead of printing it and going on. Frame pointers and -g: readable stacks in reports.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                    -fno-omit-frame-pointer -g)
add_link_options(-fsanitize=address,undefined)

# toml++ stays Debian's shared library, the one every rtsim build runs; it is not instrumented, so
# coverage starts where its parse result reaches rtsim. (Compiled from its headers with the
# sanitizers, toml++ 3.3.0 stops at once on two known defects of its own, reachable by input but
# harmless in the release library: fuzz/findings/tomlplusplus/README.md.)

# The edit distance behind "did you mean" (common/suggest.cpp) compares each byte of an unknown
# name with each byte of every known one. Traced comparisons there guide no mutation and cost the
# most: config_fuzz took 37 s on a 60 KB unknown key with them, 8 s without (a release build,
# under a second). Its coverage counters stay. (fuzz/findings/README.md)
set_source_files_properties(${CMAKE_SOURCE_DIR}/common/suggest.cpp PROPERTIES
                            COMPILE_OPTIONS -fno-sanitize-coverage=trace-cmp)
