# bounce_warnings(target): the project's warning set; errors when BOUNCE_WERROR (CI).
function(bounce_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local -Wnon-virtual-dtor
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
