# SPDX-License-Identifier: MIT
# Warnings for legal input that gives a poor simulation (docs/warnings.md), as the command line
# gives them: each case of tests/data/warnings/ runs (exit 0) with its warning on standard error,
# `--dt` is taken into account, bench lists the warnings in its JSON and prints them on standard
# error, render prints them, reference scenes run without any, and a body the tolerances do not
# serve is refused with exit 2, by the loader or, after an option changes the tolerances, by the step.
#
#   cmake -DIMPULSE=<impulse executable> -DSCENES=<scenes dir> -DDATA=<tests/data dir>
#         -DWORK=<scratch dir> -P warnings_test.cmake
#
# Every check is run; each failure is printed as it happens and the script ends with FATAL_ERROR
# listing all of them, so one broken check does not hide the others.
cmake_minimum_required(VERSION 3.21)

include("${CMAKE_CURRENT_LIST_DIR}/check_harness.cmake")
start_checks(warnings_test.cmake IMPULSE SCENES DATA WORK)

# Per file of tests/data/warnings, a regular expression its warning must match after
# "impulse: warning: <file>: ".
set(expect_large_step "^dt = 1 s is too large for this scene: gravity moves a body from rest 9\\.81 m in one step .*\"ball\".*Use dt <= 0\\.0357 s")
set(expect_fast_body "^dt = 0\\.001 s is too large for the speed of \"bullet\": at 300 m/s .*\"plate\" \\(0\\.05 m")
set(expect_small_body "^\"marble\" is small for the step's length tolerances: push_out_allowance \\(0\\.0001 m\\) is 2 % .*at most 5e-05 m")
set(expect_overlap "^\"left\" and body 2 overlap by 0\\.02 m at the start, more than the contact thickness")
set(expect_mass_ratio "^\"anvil\" \\(1e\\+03 kg\\) is 1e\\+05 times as heavy as \"feather\" \\(0\\.01 kg\\)")
set(expect_far_from_origin "^\"far\" reaches 1e\\+08 m from the origin")

file(GLOB cases "${DATA}/warnings/*.json")
list(SORT cases)
list(LENGTH cases case_count)
if(case_count LESS 6)
    check_failed("only ${case_count} warning cases in ${DATA}/warnings")
endif()
foreach(case IN LISTS cases)
    get_filename_component(stem "${case}" NAME_WE)
    run_impulse(run "${case}" --no-progress)
    expect_success()
    if(NOT run_out MATCHES "state hash  ${hex16}")
        check_failed("${stem}.json: no summary on standard output:\n${run_out}")
    endif()
    set(prefix "impulse: warning: ${case}: ")
    string(FIND "${run_err}" "${prefix}" at)
    if(NOT at EQUAL 0)
        check_failed("${stem}.json: stderr does not start with \"${prefix}\": ${run_err}")
        continue()
    endif()
    string(REGEX MATCHALL "impulse: warning: " warning_lines "${run_err}")
    list(LENGTH warning_lines warning_count)
    string(LENGTH "${prefix}" prefix_length)
    string(SUBSTRING "${run_err}" ${prefix_length} -1 what)
    if(NOT DEFINED expect_${stem})
        check_failed("${stem}.json: warnings_test.cmake has no expected warning for it (set expect_${stem})")
    elseif(warning_count EQUAL 1 AND what MATCHES "${expect_${stem}}")
        check_passed("${stem}.json runs with the one warning: ${what}")
    else()
        check_failed("${stem}.json: ${warning_count} warnings, the first \"${what}\", expected one matching \"${expect_${stem}}\"")
    endif()
endforeach()

# ---- --dt counts: the reference ball drop warns at 1 s and is silent at its own 1 ms ------------
set(drop "${SCENES}/ball_drop_elastic.json")
run_impulse(run "${drop}" --dt 1 --duration 2)
expect_success()
if(run_err MATCHES "^impulse: warning: [^\n]*ball_drop_elastic\\.json: dt = 1 s is too large")
    check_passed("run --dt 1 on the elastic ball drop warns of the time step")
else()
    check_failed("run --dt 1 on the elastic ball drop: stderr \"${run_err}\"")
endif()
foreach(reference ball_drop_elastic box_stack_10 tori_stack)
    run_impulse(run "${SCENES}/${reference}.json" --duration 0.01)
    expect_success()
    if(run_err STREQUAL "")
        check_passed("${reference} runs without a warning")
    else()
        check_failed("${reference}: stderr \"${run_err}\"")
    endif()
endforeach()

# ---- bench: the warnings on stderr and in the JSON, an empty list for a scene without ----------
run_impulse(bench "${DATA}/warnings/large_step.json" "${SCENES}/box_stack_10.json" --steps 1 --warm-up 0 --json)
expect_success()
string(STRIP "${run_out}" json)
string(JSON first_type ERROR_VARIABLE json_error TYPE "${json}" scenes 0 warnings)
string(JSON first_count ERROR_VARIABLE json_error LENGTH "${json}" scenes 0 warnings)
string(JSON first_warning ERROR_VARIABLE json_error GET "${json}" scenes 0 warnings 0)
string(JSON second_count ERROR_VARIABLE second_error LENGTH "${json}" scenes 1 warnings)
if(first_type STREQUAL "ARRAY" AND first_count EQUAL 1 AND first_warning MATCHES "${expect_large_step}")
    check_passed("bench --json lists the warning of large_step: ${first_warning}")
else()
    check_failed("bench --json: scenes[0].warnings is ${first_type} of ${first_count}: \"${first_warning}\" ${json_error}\n${run_out}")
endif()
if(second_count EQUAL 0 AND NOT second_error)
    check_passed("bench --json gives box_stack_10 an empty warnings list")
else()
    check_failed("bench --json: scenes[1].warnings has ${second_count} entries ${second_error}")
endif()
if(run_err MATCHES "^impulse: warning: [^\n]*large_step\\.json: dt = 1 s is too large" AND NOT run_err MATCHES "box_stack_10")
    check_passed("bench prints the warning on stderr, and none for box_stack_10")
else()
    check_failed("bench: stderr \"${run_err}\"")
endif()

# ---- render prints them too ------------------------------------------------------------------
run_impulse(render "${DATA}/warnings/overlap.json" --out "${WORK}/overlap.png" --size 64x48 --no-progress)
expect_success()
if(run_err MATCHES "^impulse: warning: [^\n]*overlap\\.json: \"left\" and body 2 overlap by 0\\.02 m")
    check_passed("render prints the overlap warning")
else()
    check_failed("render: stderr \"${run_err}\"")
endif()

# ---- refusals: by the loader with the field, by the step after an option changed the tolerances --
run_impulse(run "${DATA}/bad/tiny_sphere.json")
if(run_rc STREQUAL "2" AND run_err MATCHES "^impulse: [^\n]*tiny_sphere\\.json: /bodies/1/shape/radius: its thinnest half extent, 1e-09 m, is below")
    check_passed("a sphere of 1e-9 m is refused with exit 2, naming the field and the size")
else()
    check_failed("tiny_sphere.json: exit ${run_rc}, stderr \"${run_err}\"")
endif()
# 0.5 mm loads with push-out off (the contact thickness of 1 um serves it); --push-out on brings in
# the allowance of 0.1 mm, which does not
file(READ "${DATA}/warnings/small_body.json" bead)
string(REPLACE "\"radius\": 0.005" "\"radius\": 0.0005" bead "${bead}")
string(REPLACE "\"position\": [0, 0, 0.005]" "\"position\": [0, 0, 0.0005]" bead "${bead}")
string(REPLACE "\"gravity\"" "\"solver\": {\"push_out\": false},\n  \"gravity\"" bead "${bead}")
file(WRITE "${WORK}/bead.json" "${bead}")
run_impulse(run "${WORK}/bead.json" --duration 0.01)
expect_success()
run_impulse(run "${WORK}/bead.json" --duration 0.01 --push-out on)
if(run_rc STREQUAL "2" AND run_err MATCHES "^impulse: [^\n]*bead\\.json: size: body 1: [^\n]*push_out_allowance \\(0\\.0001 m\\)")
    check_passed("--push-out on with a 0.5 mm bead is refused with exit 2, naming the allowance")
else()
    check_failed("bead.json --push-out on: exit ${run_rc}, stderr \"${run_err}\"")
endif()

finish_checks("warnings")
