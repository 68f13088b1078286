# SPDX-License-Identifier: MIT
# What the command-line test scripts share: their required -D variables, a fresh scratch folder,
# and checks that record failures and carry on, so that one broken check does not hide the others.
#
#   include(check_harness.cmake)
#   start_checks(<script name> <required variable>...)  # then check_passed / check_failed ...
#   run_impulse(<arguments>...)                         # then expect_success() or checks of run_*
#   finish_checks(<what was checked>)                   # FATAL_ERROR listing every failure
#   ${hex16}                                            # a regex for a 16-hex-digit state hash

set(hex16 "[0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f]")
set(hex16 "${hex16}${hex16}")

# Refuses to run without the script's -D variables, then empties WORK and the failure list.
macro(start_checks script)
    foreach(variable ${ARGN})
        if(NOT DEFINED ${variable} OR "${${variable}}" STREQUAL "")
            message(FATAL_ERROR "${script}: pass -D${variable}=... (see the header of this file)")
        endif()
    endforeach()
    if(DEFINED IMPULSE AND NOT EXISTS "${IMPULSE}")
        message(FATAL_ERROR "${script}: no executable at IMPULSE=${IMPULSE}")
    endif()
    file(REMOVE_RECURSE "${WORK}")
    file(MAKE_DIRECTORY "${WORK}")
    set(failures "")
endmacro()

# Records a failed check (in the caller's `failures`) and carries on.
function(check_failed what)
    message("FAIL: ${what}")
    string(REPLACE ";" "," what "${what}")
    list(APPEND failures "${what}")
    set(failures "${failures}" PARENT_SCOPE)
endfunction()

function(check_passed what)
    message(STATUS "ok: ${what}")
endfunction()

# Runs ${IMPULSE} with the given arguments in WORK, so that a file written to the current folder
# lands in the scratch folder; sets run_rc, run_out, run_err (stripped) and run_command. The timeout
# guards the "never hangs" promise: every run of the scripts simulates at most a second.
macro(run_impulse)
    execute_process(
        COMMAND "${IMPULSE}" ${ARGN}
        WORKING_DIRECTORY "${WORK}"
        RESULT_VARIABLE run_rc
        OUTPUT_VARIABLE run_out
        ERROR_VARIABLE run_err
        TIMEOUT 120)
    string(STRIP "${run_err}" run_err)
    string(JOIN " " run_command "impulse" ${ARGN})
endmacro()

# Checks that the last run_impulse exited with `code`.
macro(expect_exit code)
    if(run_rc STREQUAL "${code}")
        check_passed("${run_command} exits ${code}")
    else()
        check_failed("${run_command} exited with ${run_rc}, expected ${code}: ${run_err}")
    endif()
endmacro()

# Checks that the last run_impulse exited 0.
macro(expect_success)
    expect_exit(0)
endmacro()

# True (in `result`) when run_rc is an exit code other than 0, not a signal or a timeout, which
# execute_process reports as text ("Child aborted", "Segmentation fault", ...).
macro(exited_with_error result)
    if(run_rc MATCHES "^[0-9]+$" AND NOT run_rc EQUAL 0)
        set(${result} TRUE)
    else()
        set(${result} FALSE)
    endif()
endmacro()

# Ends the script: FATAL_ERROR listing every failed check, or one line saying all passed.
macro(finish_checks what)
    list(LENGTH failures failure_count)
    if(failure_count GREATER 0)
        list(JOIN failures "\n  " failure_text)
        message(FATAL_ERROR "${failure_count} ${what} check(s) failed:\n  ${failure_text}")
    endif()
    message(STATUS "all ${what} checks passed")
endmacro()
