# Project-wide warning flags; applied per target with lrigid_warnings(target).
function(lrigid_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(LRIGID_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# Instrumented builds (docs/stability.md). Use a separate build directory for each.
#   LRIGID_SANITIZE  AddressSanitizer + UndefinedBehaviorSanitizer on everything (gcc or clang);
#                    any report aborts the program, so the test suite fails on it.
#   LRIGID_FUZZ      the libFuzzer targets in fuzz/ (clang only), with ASan + UBSan and
#                    coverage instrumentation of the whole tree; ctest -L fuzz runs them.
option(LRIGID_FUZZ "Build the libFuzzer targets in fuzz/ (needs clang)" OFF)

if(LRIGID_SANITIZE OR LRIGID_FUZZ)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
endif()

if(LRIGID_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "LRIGID_FUZZ=ON needs clang: -DCMAKE_CXX_COMPILER=clang++ "
                        "-DCMAKE_C_COMPILER=clang (compiler here: ${CMAKE_CXX_COMPILER_ID})")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
  enable_testing()
  # the runtime's targets are linked by name, so they may be defined after this point
  add_subdirectory(${CMAKE_SOURCE_DIR}/fuzz ${CMAKE_BINARY_DIR}/fuzz)
endif()
