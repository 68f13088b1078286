# SPDX-License-Identifier: MIT
# IMPULSE_SANITIZE=address,undefined builds our targets with those sanitizers; any finding aborts.
# IMPULSE_FUZZ builds them with address and undefined always, plus libFuzzer's coverage feedback
# (fuzzer-no-link: the fuzz targets in tests/fuzz add libFuzzer's main when they link).
function(impulse_apply_sanitizers target)
  set(sanitizers "${IMPULSE_SANITIZE}")
  if(IMPULSE_FUZZ)
    set(sanitizers fuzzer-no-link,address,undefined)
  endif()
  if(sanitizers)
    target_compile_options(${target} PUBLIC -fsanitize=${sanitizers} -fno-sanitize-recover=all
                                            -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=${sanitizers})
  endif()
endfunction()
