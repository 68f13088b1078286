# SPDX-License-Identifier: MIT
# Installs the build into a scratch prefix and uses it as a program outside the source tree would:
# examples/ built with find_package(impulse) and run, a program using impulse::core alone built
# while assimp, nlohmann_json and libpng are hidden from CMake, a missing component refused with
# its reason, pkg-config flags, the installed command line and the installed Python module.
#
#   cmake -DBUILD=<build dir> -DSOURCE=<source dir> -DWORK=<scratch dir> [-DPYTHON=<python3>]
#         -P install_test.cmake
cmake_minimum_required(VERSION 3.21)

include("${CMAKE_CURRENT_LIST_DIR}/../cli/check_harness.cmake")
start_checks(install_test.cmake BUILD SOURCE WORK)
set(prefix "${WORK}/prefix")

# Runs a command in WORK; sets run_rc, run_out, run_err and run_command like run_impulse.
macro(run)
    execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE run_rc OUTPUT_VARIABLE run_out
                    ERROR_VARIABLE run_err TIMEOUT 600)
    string(STRIP "${run_err}" run_err)
    string(JOIN " " run_command ${ARGN})
endmacro()

run("${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${prefix}")
expect_success()
foreach(file include/impulse/impulse.hpp include/impulse/world.hpp include/impulse/io/scene.hpp
             lib/libimpulse_core.a lib/libimpulse_io.a lib/cmake/impulse/impulseConfig.cmake
             lib/cmake/impulse/impulseConfigVersion.cmake lib/pkgconfig/impulse.pc bin/impulse)
    if(EXISTS "${prefix}/${file}")
        check_passed("installed ${file}")
    else()
        check_failed("${file} was not installed")
    endif()
endforeach()
file(GLOB_RECURSE internal RELATIVE "${prefix}" "${prefix}/include/*/rigid_body.hpp" "${prefix}/lib/libimpulse_viz.a")
if(internal)
    check_failed("internal files were installed: ${internal}")
endif()

# examples/ out of tree, found through CMAKE_PREFIX_PATH
set(generator)
if(CMAKE_GENERATOR)
    set(generator -G "${CMAKE_GENERATOR}")
endif()
run("${CMAKE_COMMAND}" -S "${SOURCE}/examples" -B "${WORK}/examples" -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release)
expect_success()
run("${CMAKE_COMMAND}" --build "${WORK}/examples")
expect_success()
run("${WORK}/examples/resting_box")
expect_success()
if(run_out MATCHES "as expected: at rest at z = 0.1 m")
    check_passed("the installed resting_box example ran to its expected end")
else()
    check_failed("resting_box printed: ${run_out}")
endif()

# impulse::core alone, with the libraries of io and viz hidden: it must need none of them
file(MAKE_DIRECTORY "${WORK}/core_only")
file(WRITE "${WORK}/core_only/CMakeLists.txt" "
cmake_minimum_required(VERSION 3.21)
project(core_only LANGUAGES CXX)
find_package(impulse REQUIRED COMPONENTS core)
if(TARGET impulse::io)
  message(FATAL_ERROR \"impulse::io was loaded although assimp is hidden\")
endif()
add_executable(resting_box \"${SOURCE}/examples/resting_box.cpp\")
target_link_libraries(resting_box PRIVATE impulse::core)
")
run("${CMAKE_COMMAND}" -S "${WORK}/core_only" -B "${WORK}/core_only/build" -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_DISABLE_FIND_PACKAGE_assimp=ON -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON
    -DCMAKE_DISABLE_FIND_PACKAGE_PNG=ON)
expect_success()
run("${CMAKE_COMMAND}" --build "${WORK}/core_only/build")
expect_success()
run("${WORK}/core_only/build/resting_box")
expect_success()
run(ldd "${WORK}/core_only/build/resting_box")
if(run_out MATCHES "assimp|png")
    check_failed("the core-only program links ${CMAKE_MATCH_0}: ${run_out}")
else()
    check_passed("the core-only program links neither assimp nor libpng")
endif()

# asking for impulse::io with assimp hidden is refused, saying why
file(MAKE_DIRECTORY "${WORK}/needs_io")
file(WRITE "${WORK}/needs_io/CMakeLists.txt" "
cmake_minimum_required(VERSION 3.21)
project(needs_io LANGUAGES CXX)
find_package(impulse REQUIRED COMPONENTS io)
")
run("${CMAKE_COMMAND}" -S "${WORK}/needs_io" -B "${WORK}/needs_io/build" -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_DISABLE_FIND_PACKAGE_assimp=ON)
if(NOT run_rc EQUAL 0 AND run_err MATCHES "impulse::io needs assimp")
    check_passed("find_package(impulse COMPONENTS io) without assimp says impulse::io needs assimp")
else()
    check_failed("find_package(impulse COMPONENTS io) without assimp: exit ${run_rc}: ${run_err}")
endif()

# pkg-config
find_program(PKG_CONFIG pkg-config)
if(PKG_CONFIG)
    set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
    run("${PKG_CONFIG}" --cflags --libs impulse)
    expect_success()
    string(STRIP "${run_out}" flags)
    separate_arguments(flags UNIX_COMMAND "${flags}")
    run(c++ -std=c++20 -O1 "${SOURCE}/examples/resting_box.cpp" -o "${WORK}/resting_box_pc" ${flags})
    expect_success()
    run("${WORK}/resting_box_pc")
    expect_success()
endif()

# the installed command line
run("${prefix}/bin/impulse" run "${SOURCE}/scenes/ball_drop_elastic.json" --duration 0.1 --out "${WORK}/drop.csv")
expect_success()

# the installed Python module, from the prefix's site packages
if(PYTHON)
    file(GLOB_RECURSE modules "${prefix}/lib/*/impulse*.so")
    if(NOT modules)
        check_failed("no Python module under ${prefix}/lib")
    else()
        list(GET modules 0 module)
        get_filename_component(site "${module}" DIRECTORY)
        set(ENV{PYTHONPATH} "${site}")
        run("${PYTHON}" -c "import impulse\nworld = impulse.World()\nprint(impulse.__file__)")
        expect_success()
        if(run_out MATCHES "^${prefix}")
            check_passed("python imports the installed module from ${site}")
        else()
            check_failed("python imported ${run_out}, not the installed module")
        endif()
    endif()
endif()

finish_checks("install")
