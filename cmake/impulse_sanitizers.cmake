# SPDX-License-Identifier: MIT
# IMPULSE_SANITIZE=address,undefined builds our targets with those sanitizers; any finding aborts.
function(impulse_apply_sanitizers target)
  if(IMPULSE_SANITIZE)
    target_compile_options(${target} PUBLIC -fsanitize=${IMPULSE_SANITIZE} -fno-sanitize-recover=all
                                            -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=${IMPULSE_SANITIZE})
  endif()
endfunction()
