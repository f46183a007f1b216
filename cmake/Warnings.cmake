# bounce_warnings(target): the project's warning set; errors when BOUNCE_WERROR (CI).
function(bounce_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow=local -Wnon-virtual-dtor
                         -Wno-missing-field-initializers)
  if(BOUNCE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
