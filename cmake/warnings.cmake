# sffcal_set_warnings(<target>): the project's warning set, applied to its own targets only.
function(sffcal_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion -Wnon-virtual-dtor -Wold-style-cast -Wcast-align -Woverloaded-virtual)
  if(SFFCAL_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
