# SPDX-License-Identifier: MIT
# One place for the warning set of our own targets (third-party code is left alone).
function(impulse_apply_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
    # bit-identical trajectories: no fused multiply-add contraction chosen by the optimiser
    target_compile_options(${target} PRIVATE -ffp-contract=off)
  endif()
endfunction()
