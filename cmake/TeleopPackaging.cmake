# What an install of teleop holds beyond the targets themselves (cmake/TeleopTarget.cmake installs
# those), and the Debian package made from it. docs/install.md describes the result.
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
install(DIRECTORY ${PROJECT_SOURCE_DIR}/idl/ DESTINATION ${TELEOP_DATA_DIR}/idl FILES_MATCHING PATTERN "*.idl"
  PATTERN ros2 EXCLUDE)
# the ROS 2 message package of the same samples (transport.naming: ros2; docs/transport.md), to
# copy into a colcon workspace
install(DIRECTORY ${PROJECT_SOURCE_DIR}/idl/ros2/teleop_msgs DESTINATION ${TELEOP_DATA_DIR}/ros2)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)

# A lab machine's provisioning (provisioning/, docs/provisioning.md): the limits, the udev rules,
# the units and the CAN bring-up, at the paths the system reads them from. They form the component
# `system`, which the package installs (CPACK_INSTALL_CMAKE_PROJECTS below) and a plain
# `cmake --install` leaves alone: an install into a prefix never writes /etc. The same files go to
# share/teleop/provisioning for an install from source to copy by hand.
set(provisioning ${PROJECT_SOURCE_DIR}/provisioning)
install(FILES ${provisioning}/95-teleop.conf DESTINATION /etc/security/limits.d COMPONENT system EXCLUDE_FROM_ALL)
install(FILES ${provisioning}/can/can0.conf DESTINATION /etc/teleop/can COMPONENT system EXCLUDE_FROM_ALL)
install(FILES ${provisioning}/60-teleop.rules DESTINATION /usr/lib/udev/rules.d COMPONENT system EXCLUDE_FROM_ALL)
install(FILES ${provisioning}/teleop-node@.service ${provisioning}/teleop-can@.service ${provisioning}/teleop.slice
  DESTINATION /usr/lib/systemd/system COMPONENT system EXCLUDE_FROM_ALL)
install(DIRECTORY ${provisioning}/ DESTINATION ${TELEOP_DATA_DIR}/provisioning
  PATTERN postinst EXCLUDE PATTERN postrm EXCLUDE)
install(FILES ${PROJECT_SOURCE_DIR}/docs/provisioning.md DESTINATION ${CMAKE_INSTALL_DOCDIR})

# everything the install copies and nothing else (no tests, no benchmarks): what the package
# script builds, what the install test needs built
add_custom_target(teleop_installables)
get_property(installed_targets GLOBAL PROPERTY TELEOP_INSTALLED_TARGETS)
add_dependencies(teleop_installables ${installed_targets})
# run by the install before it copies anything (CMakeLists.txt): every installed target built?
set(installed_files "")
foreach(target ${installed_targets})
  string(APPEND installed_files "$<TARGET_FILE:${target}>\n")
endforeach()
file(GENERATE OUTPUT ${CMAKE_BINARY_DIR}/teleop_installed_files.txt CONTENT "${installed_files}")
file(WRITE ${CMAKE_BINARY_DIR}/teleop_check_installables.cmake [=[
file(STRINGS "${CMAKE_CURRENT_LIST_DIR}/teleop_installed_files.txt" files)
set(missing "")
foreach(f IN LISTS files)
  if(NOT EXISTS "${f}")
    get_filename_component(name "${f}" NAME)
    list(APPEND missing ${name})
  endif()
endforeach()
if(missing)
  list(JOIN missing ", " missing)
  message(FATAL_ERROR "teleop: this build tree lacks installed targets (${missing}); nothing was installed. "
    "Build them first: cmake --build ${CMAKE_CURRENT_LIST_DIR} --target teleop_installables")
endif()
]=])

# `cpack -G DEB` in the build directory (scripts/package.sh): teleop_<version>_amd64.deb, one
# package with the executables, the libraries, the headers, the CMake files, the data and the
# provisioning.
set(CPACK_PACKAGE_NAME teleop)
set(CPACK_PACKAGE_VENDOR "teleop")
set(CPACK_PACKAGE_CONTACT "teleop maintainers <teleop@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
# one string: two would join as a list, with a ';' in the package's description
set(CPACK_PACKAGE_DESCRIPTION "Leader, follower, digital twin and hand nodes over Fast DDS, with network \
impairment emulation, experiments and the bus tools; libraries and CMake files to build against it.")
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
# Debian's own prefix: /usr/bin, /usr/lib (on the loader's default path), /usr/share/teleop
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# the libraries' dependencies (libfastrtps, libmujoco, libyaml-cpp, ...) read from the binaries
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_GENERATE_SHLIBS ON)
# what dpkg-shlibdeps cannot see: `teleop plot` and the experiments' figures run python3 with
# matplotlib (scripts/teleop_plot); building against the installed CMake package needs the
# headers its public interface includes (and libqhull-dev, whose include folder Debian's mujoco
# config names without depending on it; libcli11-dev: teleop::runtime's public header includes CLI11); fastdds-tools has the discovery server, can-utils
# candump/cansend for the hand's bus
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3, python3-matplotlib")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
    "libfastrtps-dev, libfastcdr-dev, libyaml-cpp-dev, libeigen3-dev, libmujoco-dev, libqhull-dev, libcli11-dev, fastdds-tools, can-utils")
# everything a plain install copies, and the system component
set(CPACK_INSTALL_CMAKE_PROJECTS "${CMAKE_BINARY_DIR};teleop;ALL;/;${CMAKE_BINARY_DIR};teleop;system;/")
# what dpkg keeps a local edit of (/etc), and the user and group teleop made at installation
file(WRITE ${CMAKE_BINARY_DIR}/debian/conffiles "/etc/security/limits.d/95-teleop.conf\n/etc/teleop/can/can0.conf\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${CMAKE_BINARY_DIR}/debian/conffiles ${provisioning}/postinst ${provisioning}/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# adduser for the postinst's system user
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser")
include(CPack)
