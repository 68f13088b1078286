# SPDX-License-Identifier: MIT
# The impulse command line as a user runs it: exit codes, the trajectory CSV and its determinism,
# the help text, and the refusal of unusable scene files and options.
#
#   cmake -DIMPULSE=<impulse executable> -DSCENES=<scenes dir> -DDATA=<tests/data dir>
#         -DWORK=<scratch dir> -P cli_test.cmake
#
# Every check is run; each failure is printed as it happens and the script ends with FATAL_ERROR
# listing all of them, so one broken check does not hide the others.
cmake_minimum_required(VERSION 3.21)

include("${CMAKE_CURRENT_LIST_DIR}/check_harness.cmake")
start_checks(cli_test.cmake IMPULSE SCENES DATA WORK)

# Runs impulse with the given arguments; sets run_rc, run_out and run_err. A timeout guards the
# "never hangs" promise: every run below simulates at most half a second.
macro(run_impulse)
    execute_process(
        COMMAND "${IMPULSE}" ${ARGN}
        RESULT_VARIABLE run_rc
        OUTPUT_VARIABLE run_out
        ERROR_VARIABLE run_err
        TIMEOUT 120)
    string(STRIP "${run_err}" run_err)
    string(JOIN " " run_command "impulse" ${ARGN})
endmacro()

# Counts the data rows of a trajectory CSV into `rows` after checking its header and that every
# row is 15 finite numbers (body index 0: the reference scenes below have one dynamic body).
function(check_trajectory csv expected_rows)
    if(NOT EXISTS "${csv}")
        check_failed("${csv} was not written")
        set(failures "${failures}" PARENT_SCOPE)
        return()
    endif()
    file(READ "${csv}" content)
    string(FIND "${content}" "\n" end_of_header)
    if(end_of_header EQUAL -1)
        check_failed("${csv} has no complete line")
        set(failures "${failures}" PARENT_SCOPE)
        return()
    endif()
    string(SUBSTRING "${content}" 0 ${end_of_header} header)
    if(header STREQUAL "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz")
        check_passed("${csv} header is t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz")
    else()
        check_failed("${csv} header is \"${header}\"")
    endif()
    string(REGEX MATCHALL "\n" newlines "${content}")
    list(LENGTH newlines line_count)
    math(EXPR rows "${line_count} - 1")
    if(rows EQUAL expected_rows)
        check_passed("${csv} has ${expected_rows} data rows")
    else()
        check_failed("${csv} has ${rows} data rows, expected ${expected_rows}")
    endif()
    if(NOT content MATCHES "\n$")
        check_failed("${csv} does not end with a newline")
    endif()
    # a finite number as printf %.17g writes it (digits, sign, point, exponent): not nan or inf.
    # CMake regular expressions allow few groups, so the row pattern is spelt out without any.
    set(number "-?[0-9][-+.0-9e]*")
    set(row "^${number},0")
    foreach(column RANGE 1 13)
        string(APPEND row ",${number}")
    endforeach()
    file(STRINGS "${csv}" good_rows REGEX "${row}$")
    list(LENGTH good_rows good_count)
    if(good_count EQUAL rows)
        check_passed("${csv} rows are 15 finite numbers each")
    else()
        check_failed("${csv}: only ${good_count} of ${rows} rows are 15 finite numbers (NaN, inf or a malformed row)")
    endif()
    set(failures "${failures}" PARENT_SCOPE)
endfunction()

set(scene "${SCENES}/ball_drop_elastic.json")

# ---- a trajectory: 0.5 s at dt 1 ms is 500 steps plus the initial state -------------------------
run_impulse(run "${scene}" --duration 0.5 --out "${WORK}/a.csv")
if(run_rc STREQUAL "0")
    check_passed("${run_command} exits 0")
else()
    check_failed("${run_command} exited with ${run_rc}: ${run_err}")
endif()
check_trajectory("${WORK}/a.csv" 501)
if(EXISTS "${WORK}/a.csv")
    file(STRINGS "${WORK}/a.csv" lines)
    list(GET lines 1 first_row)
    list(GET lines -1 last_row)
    if(first_row MATCHES "^0,0," AND last_row MATCHES "^0\\.5,0,")
        check_passed("a.csv runs from t = 0 to t = 0.5")
    else()
        check_failed("a.csv runs from \"${first_row}\" to \"${last_row}\", expected t = 0 to 0.5")
    endif()
endif()

# ---- the same run twice writes the same bytes ------------------------------------------------
run_impulse(run "${scene}" --duration 0.5 --out "${WORK}/b.csv")
if(NOT run_rc STREQUAL "0")
    check_failed("${run_command} exited with ${run_rc}: ${run_err}")
elseif(EXISTS "${WORK}/a.csv" AND EXISTS "${WORK}/b.csv")
    file(SHA256 "${WORK}/a.csv" hash_a)
    file(SHA256 "${WORK}/b.csv" hash_b)
    if(hash_a STREQUAL hash_b)
        check_passed("two runs write byte-identical trajectories (sha256 ${hash_a})")
    else()
        check_failed("two runs of the same scene wrote different trajectories: ${hash_a} and ${hash_b}")
    endif()
else()
    check_failed("a.csv or b.csv missing, cannot compare the two runs")
endif()

# ---- --every 100: steps 0, 100, ..., 500 -----------------------------------------------------
run_impulse(run "${scene}" --duration 0.5 --every 100 --out "${WORK}/every.csv")
if(run_rc STREQUAL "0")
    check_passed("${run_command} exits 0")
else()
    check_failed("${run_command} exited with ${run_rc}: ${run_err}")
endif()
check_trajectory("${WORK}/every.csv" 6)

# ---- help ------------------------------------------------------------------------------------
run_impulse(run --help)
if(run_rc STREQUAL "0")
    check_passed("${run_command} exits 0")
else()
    check_failed("${run_command} exited with ${run_rc}: ${run_err}")
endif()
foreach(option --dt --duration --out --every)
    if(run_out MATCHES "${option}")
        check_passed("impulse run --help mentions ${option}")
    else()
        check_failed("impulse run --help does not mention ${option}:\n${run_out}")
    endif()
endforeach()

# ---- unusable scene files: exit 2, "impulse: <file>: <pointer>: <what>" on stderr --------------
# Per file, a regular expression that its message must match after "impulse: <file>: ".
set(expect_bad_json "^not valid JSON: .*line 6")
set(expect_nan_literal "^not valid JSON: ")
set(expect_negative_radius "^/bodies/1/shape/radius: .*positive")
set(expect_missing_dt "^/dt: missing")
set(expect_unknown_shape "^/bodies/1/shape/type: unknown shape \"cylinder\"")
# 1e999 is JSON syntax but no double: the field pointer and "finite", or at least the token
set(expect_mesh_not_closed "^/bodies/1/shape/file: .*open_box.obj: not closed: the edge from")
set(expect_mesh_missing_file "^/bodies/1/shape/file: .*no_such_mesh.obj: no such file")
set(expect_number_overflow "^(/bodies/1/shape/radius: .*finite|.*1e999)")

file(GLOB bad_scenes "${DATA}/bad/*.json")
list(SORT bad_scenes)
if(NOT bad_scenes)
    check_failed("no bad scene files in ${DATA}/bad")
endif()
foreach(bad IN LISTS bad_scenes)
    get_filename_component(stem "${bad}" NAME_WE)
    run_impulse(run "${bad}" --out "${WORK}/${stem}.csv")
    if(run_rc STREQUAL "2")
        check_passed("${stem}.json exits 2")
    else()
        check_failed("${stem}.json: expected exit code 2, got ${run_rc}; stderr: ${run_err}")
    endif()
    set(prefix "impulse: ${bad}: ")
    string(FIND "${run_err}" "${prefix}" at)
    if(NOT at EQUAL 0)
        check_failed("${stem}.json: stderr does not start with \"${prefix}\": ${run_err}")
        continue()
    endif()
    string(LENGTH "${prefix}" prefix_length)
    string(SUBSTRING "${run_err}" ${prefix_length} -1 what)
    string(STRIP "${what}" what)
    if(NOT DEFINED expect_${stem})
        check_failed("${stem}.json: cli_test.cmake has no expected message for it (set expect_${stem})")
    elseif(what MATCHES "${expect_${stem}}")
        check_passed("${stem}.json is refused with: ${what}")
    else()
        check_failed("${stem}.json: message \"${what}\" does not match \"${expect_${stem}}\"")
    endif()
endforeach()

# ---- unusable command lines: a non-zero exit code, never a crash ------------------------------
run_impulse(run "${WORK}/no_such_scene.json")
exited_with_error(refused)
if(refused AND run_err MATCHES "no_such_scene\\.json")
    check_passed("a missing scene file exits ${run_rc} and names the file")
else()
    check_failed("a missing scene file: exit ${run_rc}, stderr: ${run_err}")
endif()

foreach(bad_option "--dt;-1" "--dt;0" "--dt;nan" "--duration;-1" "--duration;nan" "--every;0" "--threads;-1"
                   "--threads;two")
    run_impulse(run "${scene}" ${bad_option} --out "${WORK}/option.csv")
    exited_with_error(refused)
    list(GET bad_option 0 option_name)
    if(refused AND run_err MATCHES "${option_name}")
        check_passed("${run_command} exits ${run_rc} and names ${option_name}")
    else()
        check_failed("${run_command}: exit ${run_rc}, stderr: ${run_err}")
    endif()
endforeach()

run_impulse(run "${scene}" --duration 0.01 --out "${WORK}/no_such_dir/out.csv")
exited_with_error(refused)
if(refused AND run_err MATCHES "no_such_dir/out\\.csv")
    check_passed("an output file that cannot be written exits ${run_rc} and names it")
else()
    check_failed("an output file that cannot be written: exit ${run_rc}, stderr: ${run_err}")
endif()

# ---- solver switches: the default is the Guendelman order with shock propagation ---------------
set(stack "${SCENES}/box_stack_10.json")
function(final_hash out_var)
    run_impulse(run "${stack}" --duration 0.2 ${ARGN})
    string(REGEX MATCH "state hash  ([0-9a-f]+)" hash_line "${run_out}")
    set(${out_var} "${CMAKE_MATCH_1}" PARENT_SCOPE)
endfunction()
final_hash(hash_default)
final_hash(hash_shock_on --shock-propagation on)
final_hash(hash_shock_off --shock-propagation off)
final_hash(hash_guendelman --scheme guendelman)
final_hash(hash_traditional --scheme traditional)
if(NOT hash_default STREQUAL "" AND hash_default STREQUAL hash_shock_on AND hash_default STREQUAL hash_guendelman
   AND NOT hash_default STREQUAL hash_shock_off AND NOT hash_default STREQUAL hash_traditional)
    check_passed("the default run equals --shock-propagation on and --scheme guendelman, and differs from off and traditional")
else()
    check_failed("solver switches: default ${hash_default}, shock on ${hash_shock_on}, off ${hash_shock_off}, "
                 "guendelman ${hash_guendelman}, traditional ${hash_traditional}")
endif()
run_impulse(run "${stack}" --duration 0.01 --shock-propagation maybe)
exited_with_error(refused)
if(refused AND run_err MATCHES "shock-propagation")
    check_passed("--shock-propagation maybe exits ${run_rc}")
else()
    check_failed("--shock-propagation maybe: exit ${run_rc}, stderr: ${run_err}")
endif()

finish_checks("CLI")
