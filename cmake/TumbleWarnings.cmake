# Warnings for tumble's own targets (dependencies are included as SYSTEM and stay quiet).
function(tumble_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                         -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference
                         -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough)
  if(TUMBLE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
