# The sanitizer and fuzz builds (docs/reliability.md "Sanitizers", "Fuzzing"), both through the
# `sanitize` preset of CMakePresets.json: clang 14, the whole tree with AddressSanitizer and
# UndefinedBehaviorSanitizer, and the libFuzzer targets of tests/fuzz. The ordinary build (gcc) uses
# neither.
option(BOUNCE_SANITIZE "Build every target with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(BOUNCE_FUZZ "Build the libFuzzer targets (tests/fuzz; clang only, implies coverage instrumentation)" OFF)

if(BOUNCE_SANITIZE)
  # -fno-sanitize-recover: undefined behaviour aborts the test that ran into it instead of printing a
  # line nobody reads. Frame pointers keep the reports' stacks whole at -O1.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()

if(BOUNCE_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "BOUNCE_FUZZ needs clang (libFuzzer): configure with the `sanitize` preset (cmake --preset sanitize)")
  endif()
  # Coverage for libFuzzer in every library the targets reach (the parsers, the scene validation, the
  # path tracer behind them); only the fuzz targets link libFuzzer itself (-fsanitize=fuzzer).
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# bounce_sanitizer_defaults(DIR...): gives every executable defined in DIR the sanitizers' default
# options (cmake/SanitizerDefaults.cpp). They are compiled into the binaries rather than set in the
# environment so that every way a binary runs gets them: ctest, the build's own gtest discovery (which
# runs the test binaries at build time), scripts that start `bounce`, and a developer's shell.
function(bounce_sanitizer_defaults)
  if(NOT BOUNCE_SANITIZE)
    return()
  endif()
  foreach(dir ${ARGN})
    get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target ${targets})
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "EXECUTABLE")
        target_sources(${target} PRIVATE ${PROJECT_SOURCE_DIR}/cmake/SanitizerDefaults.cpp)
      endif()
    endforeach()
  endforeach()
endfunction()
