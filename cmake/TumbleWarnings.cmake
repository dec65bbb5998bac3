# Warnings for tumble's own targets (dependencies are included as SYSTEM and stay quiet).
function(tumble_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                         -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference
                         -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough)
  # GCC 12 reports its own AVX-512 intrinsics (_mm512_undefined_pd inside xsimd's sqrt) as "(maybe)
  # uninitialized" at the caller: GCC bug 105593 in the compiler's headers, fixed in GCC 13. Clang (the
  # sanitizer build) keeps both warnings on tumble's code.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
    target_compile_options(${target} PRIVATE -Wno-maybe-uninitialized -Wno-uninitialized)
  endif()
  if(TUMBLE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
