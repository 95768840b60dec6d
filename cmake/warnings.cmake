# Project-wide warning flags; applied per target with lrigid_warnings(target).
function(lrigid_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(LRIGID_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

if(LRIGID_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
endif()
