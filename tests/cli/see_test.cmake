# SPDX-License-Identifier: MIT
# impulse plot, render and view as a user runs them: each writes a decodable, non-blank picture
# (or a page) of the size asked for, from a small trajectory and from a scene; unusable input is
# refused with exit code 2 and one line naming the file and the problem.
#
#   cmake -DIMPULSE=<impulse> -DPROBE=<impulse_png_probe> -DSCENES=<scenes dir> -DWORK=<scratch dir>
#         -P see_test.cmake
#
# Every check runs; the script ends with FATAL_ERROR listing the failures.
cmake_minimum_required(VERSION 3.21)

include("${CMAKE_CURRENT_LIST_DIR}/check_harness.cmake")
start_checks(see_test.cmake IMPULSE PROBE SCENES WORK)

# Decodes the PNG and checks its size and that it is not one flat colour.
function(check_png png width height)
    execute_process(COMMAND "${PROBE}" "${png}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    string(STRIP "${out}" out)
    if(NOT rc STREQUAL "0")
        check_failed("${png} does not decode: ${err}")
    elseif(NOT out MATCHES "^([0-9]+) ([0-9]+) ([0-9.]+)$")
        check_failed("${png}: probe printed \"${out}\"")
    elseif(NOT CMAKE_MATCH_1 EQUAL width OR NOT CMAKE_MATCH_2 EQUAL height)
        check_failed("${png} is ${CMAKE_MATCH_1}x${CMAKE_MATCH_2}, expected ${width}x${height}")
    elseif(CMAKE_MATCH_3 LESS 8)
        check_failed("${png} is nearly blank (pixel standard deviation ${CMAKE_MATCH_3})")
    else()
        check_passed("${png}: ${width}x${height}, pixel standard deviation ${CMAKE_MATCH_3}")
    endif()
    set(failures "${failures}" PARENT_SCOPE)
endfunction()

# Runs impulse, expects exit code 2 and a message matching `pattern`.
macro(expect_refusal pattern)
    run_impulse(${ARGN})
    if(run_rc STREQUAL "2" AND run_err MATCHES "${pattern}")
        check_passed("${run_command} is refused: ${run_err}")
    else()
        check_failed("${run_command}: expected exit 2 and a message matching \"${pattern}\"; "
                     "got exit ${run_rc}, stderr: ${run_err}")
    endif()
endmacro()

# ---- a small trajectory: the elastic drop, 1 s every 10 ms, and the two-ball collision ----
set(drop_scene "${SCENES}/ball_drop_elastic.json")
set(drop "${WORK}/drop.csv")
run_impulse(run "${drop_scene}" --duration 1 --every 10 --out "${drop}")
expect_success()
set(pair_scene "${SCENES}/ball_ball_oblique.json")
set(pair "${WORK}/pair.csv")
run_impulse(run "${pair_scene}" --duration 1 --every 10 --out "${pair}")
expect_success()

# ---- plot ----
run_impulse(plot "${drop}" --scene "${drop_scene}" --out "${WORK}/drop_plot.png" --size 800x600)
expect_success()
check_png("${WORK}/drop_plot.png" 800 600)
run_impulse(plot "${pair}" --size 640x480)
expect_success()
check_png("${WORK}/pair.png" 640 480)

# many bodies: up to 12 named in a key, up to 200 one curve each, above that a summary; every
# case says what it drew, and ten thousand bodies take seconds, not minutes
run_impulse(run "${SCENES}/box_stack_50.json" --duration 0.2 --every 10 --out "${WORK}/stack.csv")
expect_success()
run_impulse(plot "${WORK}/stack.csv" --scene "${SCENES}/box_stack_50.json" --out "${WORK}/stack.png" --size 640x480)
expect_success()
check_png("${WORK}/stack.png" 640 480)
if(run_out MATCHES "50 bodies, 21 samples; one curve per body, too many to name")
    check_passed("plot of 50 bodies says it draws one curve each, unnamed")
else()
    check_failed("plot of 50 bodies printed: ${run_out}")
endif()
set(pile_scene "${SCENES}/sphere_pile_10000.json")
run_impulse(run "${pile_scene}" --duration 0.003 --out "${WORK}/pile.csv")
expect_success()
string(TIMESTAMP before "%s")
run_impulse(plot "${WORK}/pile.csv" --scene "${pile_scene}" --out "${WORK}/pile.png" --size 640x480)
string(TIMESTAMP after "%s")
math(EXPR seconds "${after} - ${before}")
expect_success()
check_png("${WORK}/pile.png" 640 480)
if(run_out MATCHES "10000 bodies, 4 samples; summarised: lowest, median and highest height and speed, the paths of 50 bodies \\(every 200th\\) and of their mean")
    check_passed("plot of 10000 bodies summarises and says how")
else()
    check_failed("plot of 10000 bodies printed: ${run_out}")
endif()
if(seconds LESS 30)
    check_passed("plot of 10000 bodies took ${seconds} s")
else()
    check_failed("plot of 10000 bodies took ${seconds} s")
endif()

# ---- render's camera: from a direction, from a position with a zoom; bad vectors refused ----
set(stack_scene "${SCENES}/box_stack_10.json")
run_impulse(render "${stack_scene}" --duration 0.05 --size 160x120 --out "${WORK}/cam_default.png")
expect_success()
run_impulse(render "${stack_scene}" --duration 0.05 --size 160x120 --out "${WORK}/cam_above.png" --view-direction 0,0,1)
expect_success()
check_png("${WORK}/cam_above.png" 160 120)
run_impulse(render "${stack_scene}" --duration 0.05 --size 160x120 --out "${WORK}/cam_placed.png"
            --camera-position 4,0,1 --look-at 0,0,1 --zoom 2)
expect_success()
check_png("${WORK}/cam_placed.png" 160 120)
file(SHA256 "${WORK}/cam_default.png" cam_default)
file(SHA256 "${WORK}/cam_above.png" cam_above)
file(SHA256 "${WORK}/cam_placed.png" cam_placed)
if(NOT cam_default STREQUAL cam_above AND NOT cam_default STREQUAL cam_placed AND NOT cam_above STREQUAL cam_placed)
    check_passed("the camera options change the picture")
else()
    check_failed("the camera options left the picture as it was")
endif()
expect_refusal("--view-direction: expected X,Y,Z .three numbers., got .1,2." render "${stack_scene}"
               --out "${WORK}/bad.png" --view-direction 1,2)
expect_refusal("--view-direction: must not be zero" render "${stack_scene}" --out "${WORK}/bad.png"
               --view-direction 0,0,0)
expect_refusal("give one or the other" render "${stack_scene}" --out "${WORK}/bad.png" --view-direction 0,0,1
               --camera-position 1,1,1)
expect_refusal("--zoom: must be a number above 0" render "${stack_scene}" --out "${WORK}/bad.png" --zoom 0)
expect_refusal("--look-at goes with --camera-position" render "${stack_scene}" --out "${WORK}/bad.png" --look-at 0,0,0)

# ---- render: a scene to frames and a video, a trajectory to one picture ----
# a frame left by an earlier, longer render must not join this one (nor its video)
file(WRITE "${WORK}/frames/frame_00099.png" "stale")
file(WRITE "${WORK}/frames/notes.txt" "kept")
run_impulse(render "${drop_scene}" --duration 0.5 --fps 10 --size 160x120 --out "${WORK}/frames")
expect_success()
if(NOT EXISTS "${WORK}/frames/notes.txt")
    check_failed("render removed a file that is not one of its frames")
endif()
file(GLOB frames "${WORK}/frames/frame_*.png")
list(LENGTH frames frame_count)
if(frame_count EQUAL 6)
    check_passed("6 frames for 0.5 s at 10 fps")
else()
    check_failed("${frame_count} frames for 0.5 s at 10 fps, expected 6")
endif()
foreach(frame IN LISTS frames)
    check_png("${frame}" 160 120)
endforeach()
find_program(ffmpeg ffmpeg)
if(ffmpeg)
    set(video "${WORK}/frames/ball_drop_elastic.mp4")
    execute_process(COMMAND ffprobe -v error -count_frames -select_streams v:0 -show_entries
                            stream=width,height,nb_read_frames -of csv=p=0 "${video}"
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    string(STRIP "${out}" out)
    if(rc STREQUAL "0" AND out STREQUAL "160,120,6")
        check_passed("the MP4 decodes: 160x120, 6 frames")
    else()
        check_failed("the MP4 ${video}: ffprobe says \"${out}\" ${err}, expected 160,120,6")
    endif()
else()
    check_failed("ffmpeg is not installed (scripts/install-deps.sh installs it)")
endif()
run_impulse(render "${pair}" --scene "${pair_scene}" --out "${WORK}/pair_still.png" --at 0.5 --trail
           --size 200x150)
expect_success()
check_png("${WORK}/pair_still.png" 200 150)
run_impulse(render "${drop}" --out "${WORK}/markers.png" --size 120x90)
expect_success()
check_png("${WORK}/markers.png" 120 90)

# ---- view ----
run_impulse(view "${drop}" --scene "${drop_scene}" --out "${WORK}/drop.html")
expect_success()
if(EXISTS "${WORK}/drop.html")
    file(READ "${WORK}/drop.html" page)
    string(LENGTH "${page}" page_size)
    string(FIND "${page}" "OrbitControls" has_orbit)
    string(FIND "${page}" "\"times\":[0," has_times)
    string(FIND "${page}" "window.impulseViewer" has_viewer)
    if(page_size GREATER 100000 AND has_orbit GREATER -1 AND has_times GREATER -1 AND has_viewer GREATER -1)
        check_passed("drop.html (${page_size} bytes) inlines three.js, the orbit camera, the viewer and the data")
    else()
        check_failed("drop.html (${page_size} bytes) lacks three.js, OrbitControls, the viewer or the data")
    endif()
else()
    check_failed("drop.html was not written")
endif()
run_impulse(view "${pair}")
expect_success()
if(NOT EXISTS "${WORK}/pair.html")
    check_failed("view without --out writes pair.html beside the trajectory")
endif()

# ---- unusable input ----
file(WRITE "${WORK}/wrong_header.csv" "t,x,y,z\n0,0,0,1\n")
file(WRITE "${WORK}/short_row.csv" "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n0,0,0,0,1,1,0,0,0,0,0,0,0,0\n")
file(WRITE "${WORK}/not_a_number.csv" "t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n0,0,0,0,abc,1,0,0,0,0,0,0,0,0,0\n")
file(WRITE "${WORK}/empty.csv" "")
foreach(command plot render view)
    set(out_args "")
    if(command STREQUAL "render")
        set(out_args --out "${WORK}/refused.png")
    endif()
    expect_refusal("missing.csv: cannot open" ${command} "${WORK}/missing.csv" ${out_args})
    expect_refusal("wrong_header.csv: line 1: header must be t,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz; got t,x,y,z"
                   ${command} "${WORK}/wrong_header.csv" ${out_args})
    expect_refusal("short_row.csv: line 2: expected 15 comma-separated numbers, got 14" ${command}
                   "${WORK}/short_row.csv" ${out_args})
    expect_refusal("not_a_number.csv: line 2: column z: not a finite number" ${command}
                   "${WORK}/not_a_number.csv" ${out_args})
    expect_refusal("empty.csv: line 1: empty file" ${command} "${WORK}/empty.csv" ${out_args})
    # a scene with two dynamic bodies does not fit a trajectory of one
    expect_refusal("drop.csv: 1 bodies? per sample, but the scene .*ball_ball_oblique.json has 2" ${command} "${drop}"
                   --scene "${pair_scene}" ${out_args})
endforeach()
expect_refusal("missing.json: cannot open" render "${WORK}/missing.json" --out "${WORK}/frames")
expect_refusal("--size: expected WIDTHxHEIGHT" plot "${drop}" --size 10x)
expect_refusal("--at picks the time of one picture" render "${drop}" --at 0.5 --out "${WORK}/frames")
expect_refusal("--at 5 is outside the run, 0 to 1 s" render "${drop}" --at 5 --out "${WORK}/late.png")
if(EXISTS "${WORK}/late.png" OR EXISTS "${WORK}/refused.png")
    check_failed("a refused render left a picture behind")
endif()

finish_checks("plot, render and view")
