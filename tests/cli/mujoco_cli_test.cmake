# SPDX-License-Identifier: MIT
# The MuJoCo subcommands as a user runs them: export-mjcf writes a model that `impulse run` runs to
# the same trajectory as the scene, compare prints both engines side by side, and a model impulse
# cannot simulate is refused with exit code 2 and the documented message.
#
#   cmake -DIMPULSE=<impulse executable> -DSCENES=<scenes dir> -DDATA=<tests/data dir>
#         -DWORK=<scratch dir> -P mujoco_cli_test.cmake
cmake_minimum_required(VERSION 3.21)

foreach(variable IMPULSE SCENES DATA WORK)
    if(NOT DEFINED ${variable} OR "${${variable}}" STREQUAL "")
        message(FATAL_ERROR "mujoco_cli_test.cmake: pass -D${variable}=... (see the header of this file)")
    endif()
endforeach()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(failures "")

function(check what condition_text)
    if(${ARGN})
        message(STATUS "ok: ${what}")
    else()
        message("FAIL: ${what}: ${condition_text}")
        list(APPEND failures "${what}")
        set(failures "${failures}" PARENT_SCOPE)
    endif()
endfunction()

macro(run_impulse)
    execute_process(COMMAND "${IMPULSE}" ${ARGN} RESULT_VARIABLE run_rc OUTPUT_VARIABLE run_out
                    ERROR_VARIABLE run_err TIMEOUT 300)
    string(STRIP "${run_err}" run_err)
endmacro()

# export-mjcf, then run the model: the same trajectory file as the scene, byte for byte
set(scene "${SCENES}/ball_drop_damped.json")
run_impulse(export-mjcf "${scene}" --out "${WORK}/drop.xml")
check("export-mjcf exits 0" "exit ${run_rc}, stderr: ${run_err}" run_rc EQUAL 0)
run_impulse(run "${WORK}/drop.xml" --duration 1 --out "${WORK}/from_mjcf.csv")
check("impulse run MODEL.xml exits 0" "exit ${run_rc}, stderr: ${run_err}" run_rc EQUAL 0)
run_impulse(run "${scene}" --duration 1 --out "${WORK}/from_json.csv")
file(SHA256 "${WORK}/from_mjcf.csv" hash_mjcf)
file(SHA256 "${WORK}/from_json.csv" hash_json)
check("the exported model runs to the scene's trajectory, byte for byte" "${hash_mjcf} vs ${hash_json}"
      hash_mjcf STREQUAL hash_json)

# export-mjcf to standard output
run_impulse(export-mjcf "${scene}")
check("export-mjcf without --out prints the model" "exit ${run_rc}, output starts ${run_out}"
      run_rc EQUAL 0 AND run_out MATCHES "<mujoco model=\"ball_drop_damped\">")

# compare: exit 0, both columns, the figures of a head-on collision
run_impulse(compare "${SCENES}/ball_ball_headon.json")
check("compare exits 0" "exit ${run_rc}, stderr: ${run_err}" run_rc EQUAL 0)
check("compare prints an impulse and a MuJoCo column" "output: ${run_out}"
      run_out MATCHES "figure +impulse +MuJoCo")
check("compare prints the exit velocities, the penetration and ms per step" "output: ${run_out}"
      run_out MATCHES "velocity body 1" AND run_out MATCHES "deepest penetration" AND run_out MATCHES "ms per step")

# an MJCF model wherever a scene is accepted: plot, render and view with --scene MODEL.xml, render
# of the model itself, compare of the model
set(model "${WORK}/drop.xml")
run_impulse(plot "${WORK}/from_mjcf.csv" --scene "${model}" --out "${WORK}/model_plot.png" --size 320x240)
check("plot TRAJ --scene MODEL.xml exits 0 and writes the picture" "exit ${run_rc}, stderr: ${run_err}"
      run_rc EQUAL 0 AND EXISTS "${WORK}/model_plot.png")
run_impulse(view "${WORK}/from_mjcf.csv" --scene "${model}" --out "${WORK}/model_view.html")
check("view TRAJ --scene MODEL.xml exits 0 and writes the page" "exit ${run_rc}, stderr: ${run_err}"
      run_rc EQUAL 0 AND EXISTS "${WORK}/model_view.html")
run_impulse(render "${model}" --duration 0.3 --fps 10 --size 160x120 --no-video --out "${WORK}/model_frames")
file(GLOB model_frames "${WORK}/model_frames/*.png")
list(LENGTH model_frames model_frame_count)
check("render MODEL.xml simulates the model and writes its frames" "exit ${run_rc}, ${model_frame_count} frames, stderr: ${run_err}"
      run_rc EQUAL 0 AND model_frame_count EQUAL 4)
run_impulse(render "${WORK}/from_mjcf.csv" --scene "${model}" --size 160x120 --out "${WORK}/model_still.png")
check("render TRAJ --scene MODEL.xml exits 0" "exit ${run_rc}, stderr: ${run_err}" run_rc EQUAL 0)
run_impulse(compare "${model}")
check("compare MODEL.xml runs the model on both sides" "exit ${run_rc}, stderr: ${run_err}, output: ${run_out}"
      run_rc EQUAL 0 AND run_out MATCHES "runs the model with native mj_step" AND run_out MATCHES "apex")
file(READ "${model}" model_text)
string(REGEX REPLACE "[^\n]*impulse_duration[^\n]*\n" "" model_text "${model_text}")
file(WRITE "${WORK}/drop_untimed.xml" "${model_text}")
run_impulse(compare "${WORK}/drop_untimed.xml")
check("compare MODEL.xml without impulse_duration says what to add" "exit ${run_rc}, stderr: ${run_err}"
      NOT run_rc EQUAL 0 AND run_err MATCHES "no duration: add <numeric name=\"impulse_duration\"")
run_impulse(render "${WORK}/drop_untimed.xml" --size 160x120 --out "${WORK}/no_duration.png")
check("render MODEL.xml without a duration asks for --duration" "exit ${run_rc}, stderr: ${run_err}"
      run_rc EQUAL 2 AND run_err MATCHES "pass --duration")

# refusals: exit 2, the file named, the problem listed
run_impulse(run "${DATA}/mujoco/hinge.xml" --duration 0.1)
check("a hinge joint is refused with exit 2 and the documented message" "exit ${run_rc}, stderr: ${run_err}"
      run_rc EQUAL 2 AND run_err MATCHES "hinge.xml: the model uses what impulse does not simulate:"
      AND run_err MATCHES "hinge joint 'hinge' on body 'arm': impulse simulates free bodies only")
run_impulse(run "${WORK}/no_such_model.xml")
check("a missing model exits 2 naming the file" "exit ${run_rc}, stderr: ${run_err}"
      run_rc EQUAL 2 AND run_err MATCHES "no_such_model.xml: MuJoCo cannot load it")
file(WRITE "${WORK}/no_duration.xml"
     "<mujoco><worldbody><body pos=\"0 0 1\"><freejoint/><geom type=\"sphere\" size=\"0.1\"/></body></worldbody></mujoco>")
run_impulse(run "${WORK}/no_duration.xml")
check("a model without duration asks for one" "exit ${run_rc}, stderr: ${run_err}"
      run_rc EQUAL 2 AND run_err MATCHES "no duration")
run_impulse(run "${WORK}/no_duration.xml" --duration 0.1)
check("--duration supplies it" "exit ${run_rc}, stderr: ${run_err}" run_rc EQUAL 0)
run_impulse(export-mjcf "${WORK}/no_such_scene.json")
check("export-mjcf of a missing scene exits 2" "exit ${run_rc}, stderr: ${run_err}" run_rc EQUAL 2)

list(LENGTH failures failure_count)
if(failure_count GREATER 0)
    list(JOIN failures "\n  " failure_text)
    message(FATAL_ERROR "${failure_count} MuJoCo CLI check(s) failed:\n  ${failure_text}")
endif()
message(STATUS "all MuJoCo CLI checks passed")
