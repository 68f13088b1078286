# SPDX-License-Identifier: MIT
# `cmake --install build [--prefix DIR]`: the libraries with their headers, the command line, the
# Python module (python/CMakeLists.txt), and what find_package(impulse) and pkg-config read.
#
# Each library is its own export set, so that a program using impulse::core alone needs Eigen and
# nothing else: impulseConfig.cmake loads impulse::io (assimp) and impulse::mujoco (MuJoCo) only
# when asked for them as components or when their dependencies are found.
include(CMakePackageConfigHelpers)

set(IMPULSE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/impulse CACHE STRING
    "Where impulseConfig.cmake is installed, relative to the prefix")

install(TARGETS impulse_core EXPORT impulseCoreTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(DIRECTORY include/impulse DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT dev)
install(EXPORT impulseCoreTargets NAMESPACE impulse:: DESTINATION ${IMPULSE_INSTALL_CMAKEDIR} COMPONENT dev)

install(TARGETS impulse_io EXPORT impulseIoTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
install(DIRECTORY io/include/impulse/io DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/impulse COMPONENT dev)
install(EXPORT impulseIoTargets NAMESPACE impulse:: DESTINATION ${IMPULSE_INSTALL_CMAKEDIR} COMPONENT dev)

set(IMPULSE_INSTALLED_MUJOCO OFF)
if(TARGET impulse_mujoco)
  set(IMPULSE_INSTALLED_MUJOCO ON)
  install(TARGETS impulse_mujoco EXPORT impulseMujocoTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          COMPONENT dev)
  install(DIRECTORY mujoco/include/impulse/mujoco DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/impulse COMPONENT dev)
  install(EXPORT impulseMujocoTargets NAMESPACE impulse:: DESTINATION ${IMPULSE_INSTALL_CMAKEDIR} COMPONENT dev)
endif()

if(TARGET impulse_app)
  install(TARGETS impulse_app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT cli)
endif()

configure_package_config_file(cmake/package/impulseConfig.cmake.in
  ${PROJECT_BINARY_DIR}/package/impulseConfig.cmake
  INSTALL_DESTINATION ${IMPULSE_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API
write_basic_package_version_file(${PROJECT_BINARY_DIR}/package/impulseConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/package/impulseConfig.cmake ${PROJECT_BINARY_DIR}/package/impulseConfigVersion.cmake
        DESTINATION ${IMPULSE_INSTALL_CMAKEDIR} COMPONENT dev)

# pkg-config: impulse (the core) and impulse-io; the static libraries need their dependencies' flags
set(IMPULSE_PC_OPENMP "")
if(IMPULSE_HAVE_OPENMP)
  set(IMPULSE_PC_OPENMP " -fopenmp")
endif()
# relocatable: the prefix is found from where the .pc file is, wherever --prefix put it
file(RELATIVE_PATH IMPULSE_PC_UP /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
configure_file(cmake/package/impulse.pc.in ${PROJECT_BINARY_DIR}/package/impulse.pc @ONLY)
configure_file(cmake/package/impulse-io.pc.in ${PROJECT_BINARY_DIR}/package/impulse-io.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/package/impulse.pc ${PROJECT_BINARY_DIR}/package/impulse-io.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT dev)
