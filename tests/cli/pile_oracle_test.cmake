# SPDX-License-Identifier: MIT
# impulse_pile_oracle as a user runs it: checkpoints where --every puts them, --until stopping with
# exit code 3, a resumed run reaching the state hash of the run that was not stopped (at 1 and 2
# threads), the verdict's exit codes 0 and 1 on checkpoints made to end the run, and bad input
# refused with exit code 2 and a message naming what was wrong. Every run is a few dozen steps.
#
#   cmake -DIMPULSE=<impulse_pile_oracle executable> -DWORK=<scratch dir> -P pile_oracle_test.cmake
cmake_minimum_required(VERSION 3.21)

include("${CMAKE_CURRENT_LIST_DIR}/check_harness.cmake")
start_checks(pile_oracle_test.cmake IMPULSE WORK)

# The state hash printed at step `step` in run_out, into `out_var` ("" when there is none).
function(hash_at step out_var)
    if(run_out MATCHES "step ${step} state hash (${hex16}), checkpoint")
        set(${out_var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
    else()
        set(${out_var} "" PARENT_SCOPE)
    endif()
endfunction()

# Checks the last run's exit code, and that its output `stream` (run_out or run_err) matches `pattern`.
function(expect_run code stream pattern what)
    expect_exit(${code})
    if(${stream} MATCHES "${pattern}")
        check_passed("${what}")
    else()
        check_failed("${what}: no match for '${pattern}' in:\n${${stream}}")
    endif()
    set(failures "${failures}" PARENT_SCOPE)
endfunction()

# Writes ${WORK}/<target>: the checkpoint ${WORK}/<source> with every line matching `regex` replaced
# by `replacement`, and without the lines matching the optional fifth argument.
function(edited_checkpoint source target regex replacement)
    file(STRINGS "${WORK}/${source}" lines)
    list(TRANSFORM lines REPLACE "${regex}" "${replacement}")
    if(ARGC GREATER 4)
        list(FILTER lines EXCLUDE REGEX "${ARGV4}")
    endif()
    list(JOIN lines "\n" text)
    file(WRITE "${WORK}/${target}" "${text}\n")
endfunction()

# ---- a run stopped by --until, with a checkpoint every 20 steps --------------------------------
run_impulse(box_pile_1000 --until 60 --every 20 --threads 1 --checkpoints straight)
expect_exit(3)
foreach(step 20 40 60)
    if(EXISTS "${WORK}/straight/box_pile_1000_step_${step}.txt")
        check_passed("a checkpoint at step ${step}")
    else()
        check_failed("no checkpoint at step ${step} in ${WORK}/straight")
    endif()
endforeach()
hash_at(60 straight_hash)
if(straight_hash MATCHES "^${hex16}$" AND run_out MATCHES "stopped at step 60 of 5000")
    check_passed("stopped at step 60 with state hash ${straight_hash}")
else()
    check_failed("no state hash at step 60 or no stop line in:\n${run_out}")
endif()

# ---- resumed from step 20, at one and at two threads: the same state at step 60 ----------------
foreach(threads 1 2)
    run_impulse(box_pile_1000 --resume straight/box_pile_1000_step_20.txt --until 60 --every 0
                --threads ${threads} --checkpoints resumed_${threads})
    expect_exit(3)
    hash_at(60 resumed_hash)
    if(run_out MATCHES "resumed from [^\n]* at step 20" AND resumed_hash STREQUAL straight_hash
       AND NOT straight_hash STREQUAL "")
        check_passed("resumed at step 20 on ${threads} thread(s), the state hash at step 60 is the straight run's")
    else()
        check_failed("resumed on ${threads} thread(s): hash '${resumed_hash}' against '${straight_hash}':\n${run_out}")
    endif()
endforeach()

# ---- the verdict: checkpoints edited to be at the scene's last step ----------------------------
edited_checkpoint(straight/box_pile_1000_step_60.txt at_the_end.txt "^step 60$" "step 5000")
file(STRINGS "${WORK}/at_the_end.txt" lines)
run_impulse(box_pile_1000 --resume at_the_end.txt)
expect_run(0 run_out "PASS: deepest penetration at the end"
           "a pile with no overlap at its last step passes")
# the second dynamic cube put where the first is (line 10 is the ground, 11-14 the walls, 15 on the
# cubes), so that the two are wholly inside each other
list(GET lines 14 first_cube)
list(REMOVE_AT lines 15)
list(INSERT lines 15 "${first_cube}")
list(JOIN lines "\n" text)
file(WRITE "${WORK}/overlapping.txt" "${text}\n")
run_impulse(box_pile_1000 --resume overlapping.txt)
expect_run(1 run_out "FAIL: deepest penetration at the end"
           "two cubes inside each other at the last step fail the oracle")

# ---- checkpoints of the earlier formats still continue the run -----------------------------------
# The second format has no contact layer (the run continues from no loads, so not bit for bit as the
# straight run); the first has no deepest_sample line either.
edited_checkpoint(straight/box_pile_1000_step_20.txt version_2.txt "^impulse pile checkpoint 3$"
                  "impulse pile checkpoint 2")
file(READ "${WORK}/version_2.txt" version_2_text)
string(REGEX REPLACE "\ncontacts [0-9]+\n.*$" "\n" version_2_text "${version_2_text}")
file(WRITE "${WORK}/version_2.txt" "${version_2_text}")
edited_checkpoint(version_2.txt version_1.txt "^impulse pile checkpoint 2$" "impulse pile checkpoint 1"
                  "^deepest_sample ")
foreach(version 2 1)
    run_impulse(box_pile_1000 --resume version_${version}.txt --until 60 --every 0 --threads 1
                --checkpoints version_${version})
    expect_exit(3)
    hash_at(60 version_hash)
    if(NOT version_hash STREQUAL "")
        check_passed("a format-${version} checkpoint of step 20 continues to step 60")
    else()
        check_failed("format-${version} checkpoint:\n${run_out}\n${run_err}")
    endif()
endforeach()

# ---- bad input: exit code 2 and what was wrong --------------------------------------------------
edited_checkpoint(straight/box_pile_1000_step_20.txt no_such_body.txt "^deepest_sample .*$"
                  "deepest_sample 20 0 999999")
run_impulse(box_pile_1000 --resume no_such_body.txt)
expect_run(2 run_err "no_such_body.txt: line 7: expected the field \"deepest_sample\""
           "a deepest pair that names no body of the scene is refused by line and field")
run_impulse(no_such_pile)
expect_run(2 run_err "scene: \"no_such_pile\" is not a reference pile \\(box_pile_1000"
           "an unknown scene is refused, with the piles it could be")
file(WRITE "${WORK}/garbage.txt" "not a checkpoint\n")
run_impulse(box_pile_1000 --resume garbage.txt)
expect_run(2 run_err "garbage.txt: line 1: not a pile checkpoint"
           "a file that is no checkpoint is refused by name and line")
run_impulse(sphere_pile_1000 --resume straight/box_pile_1000_step_20.txt)
expect_run(2 run_err "scene: the checkpoint is of \"box_pile_1000\", not of \"sphere_pile_1000\""
           "another scene's checkpoint is refused")
run_impulse(box_pile_1000 --resume straight/box_pile_1000_step_60.txt --until 40)
expect_run(2 run_err "--until: step 40 is not after the checkpoint's step 60"
           "--until before the checkpoint is refused")
run_impulse(box_pile_1000 --every -5)
expect_exit(2)

finish_checks("impulse_pile_oracle")
