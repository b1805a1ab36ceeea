# Common settings of every teleop target: warnings on, public headers under include/, installed
# (docs/install.md): libraries and headers into the export set teleopTargets, executables into bin.
include(GNUInstallDirs)

# teleop_library(NAME <name> SOURCES ... DEPENDS ...) defines teleop_<name>_lib (alias teleop::<name>)
# with public headers in <dir>/include.
function(teleop_library)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  set(target teleop_${ARG_NAME}_lib)
  add_library(${target} ${ARG_SOURCES})
  add_library(teleop::${ARG_NAME} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} PUBLIC ${ARG_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
  teleop_warnings(${target})
  # calls inside one of our shared libraries may be inlined as in a static build: nothing
  # interposes teleop's own symbols (only operator new, in the allocation tests, which is not ours)
  target_compile_options(${target} PRIVATE -fno-semantic-interposition)
  teleop_install_library(${target} ${ARG_NAME})
  # a library may have no public headers (its executable alone uses it)
  if(IS_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
endfunction()

# teleop_install_library(<target> <name>): libteleop_<name>.so.<version>, imported by consumers as
# teleop::<name> (find_package(teleop)). The soname carries major.minor: before 1.0 a minor release
# may break the ABI (the same rule as the package version file, cmake/TeleopPackaging.cmake).
function(teleop_install_library target name)
  set_target_properties(${target} PROPERTIES
    OUTPUT_NAME teleop_${name}
    EXPORT_NAME ${name}
    VERSION ${PROJECT_VERSION}
    SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
  # what `teleop_installables` builds (cmake/TeleopPackaging.cmake)
  set_property(GLOBAL APPEND PROPERTY TELEOP_INSTALLED_TARGETS ${target})
  install(TARGETS ${target} EXPORT teleopTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endfunction()

# teleop_executable(NAME <name> SOURCES ... DEPENDS ...): a thin main, installed into bin unless
# its directory sets TELEOP_INSTALL_EXECUTABLES to OFF (test/ and bench/: test aids, benchmarks).
function(teleop_executable)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPENDS})
  teleop_warnings(${ARG_NAME})
  teleop_tsan_shim(${ARG_NAME})
  if(NOT DEFINED TELEOP_INSTALL_EXECUTABLES OR TELEOP_INSTALL_EXECUTABLES)
    install(TARGETS ${ARG_NAME} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
    set_property(GLOBAL APPEND PROPERTY TELEOP_INSTALLED_TARGETS ${ARG_NAME})
  endif()
endfunction()

# teleop_link_registering(<target> <library target>): links a teleop library whose objects register
# themselves (robot::linked_probes()) though nothing calls into them: a static library whole, a
# shared one kept in although the linker's --as-needed (this toolchain's default) would drop it.
set(CMAKE_LINK_LIBRARY_USING_NO_AS_NEEDED "LINKER:--push-state,--no-as-needed" "<LINK_ITEM>" "LINKER:--pop-state")
set(CMAKE_LINK_LIBRARY_USING_NO_AS_NEEDED_SUPPORTED TRUE)
function(teleop_link_registering target library)
  if(BUILD_SHARED_LIBS)
    target_link_libraries(${target} PRIVATE "$<LINK_LIBRARY:NO_AS_NEEDED,${library}>")
  else()
    target_link_libraries(${target} PRIVATE "$<LINK_LIBRARY:WHOLE_ARCHIVE,${library}>")
  endif()
endfunction()

# the ThreadSanitizer build's missing interceptor (test/support/tsan_clocklock_shim.cpp)
function(teleop_tsan_shim target)
  if(TELEOP_TSAN)
    target_link_libraries(${target} PRIVATE teleop_tsan_shim)
  endif()
endfunction()

function(teleop_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor)
endfunction()
