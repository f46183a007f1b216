# bounce_warnings(target): the project's warning set; errors when BOUNCE_WERROR (CI).
function(bounce_warnings target)
  # GCC's -Wshadow=local; clang (the fuzz build, cmake/Fuzz.cmake) spells the nearest one differently.
  set(shadow -Wshadow=local)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    set(shadow -Wshadow-uncaptured-local)
  endif()
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic ${shadow} -Wnon-virtual-dtor
                         -Wno-missing-field-initializers)
  if(BOUNCE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# bounce_layer(target sources...): a layer library. Until a layer has sources it is an INTERFACE
# library, so a partial checkout still configures.
macro(bounce_layer target)
  if("${ARGN}" STREQUAL "")
    add_library(${target} INTERFACE)
    set(${target}_SCOPE INTERFACE)
  else()
    add_library(${target} STATIC ${ARGN})
    bounce_warnings(${target})
    set(${target}_SCOPE PUBLIC)
  endif()
endmacro()
