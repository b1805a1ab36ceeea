# What an install of teleop holds beyond the targets themselves (cmake/TeleopTarget.cmake installs
# those). docs/install.md describes the result.
include(CMakePackageConfigHelpers)

set(TELEOP_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/teleop)
set(TELEOP_DATA_DIR ${CMAKE_INSTALL_DATADIR}/teleop)

# find_package(teleop 0.1) -> teleop::transport, teleop::control, ...
install(EXPORT teleopTargets NAMESPACE teleop:: DESTINATION ${TELEOP_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/teleopConfig.cmake.in
  ${CMAKE_BINARY_DIR}/teleopConfig.cmake INSTALL_DESTINATION ${TELEOP_CMAKE_DIR})
# Before 1.0 a minor release may change the API (semantic versioning's 0.y rule), so a consumer
# asking for 0.1 gets any 0.1.z and nothing else; from 1.0 on this becomes SameMajorVersion.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/teleopConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/teleopConfig.cmake ${CMAKE_BINARY_DIR}/teleopConfigVersion.cmake
  DESTINATION ${TELEOP_CMAKE_DIR})

# The data the executables look up by name (common/data_paths.h): scenarios, nodes, network
# profiles, experiments, sweeps, tasks, trajectories and the MuJoCo models, the generated arms
# included (config/models/generated/ is rendered into the source tree at configure time). The
# templates and their generator only matter to a source tree.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${TELEOP_DATA_DIR}/config
  PATTERN templates EXCLUDE
  PATTERN generate_arms.cmake EXCLUDE)
# the data model, for peers written against the IDL rather than against teleop::msg
install(DIRECTORY ${PROJECT_SOURCE_DIR}/idl/ DESTINATION ${TELEOP_DATA_DIR}/idl FILES_MATCHING PATTERN "*.idl")
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)

# everything the install copies and nothing else (no tests, no benchmarks): what the package
# script builds, what the install test needs built
add_custom_target(teleop_installables)
get_property(installed_targets GLOBAL PROPERTY TELEOP_INSTALLED_TARGETS)
add_dependencies(teleop_installables ${installed_targets})
