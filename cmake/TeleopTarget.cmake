# Common settings of every teleop target: warnings on, public headers under include/.

# teleop_library(NAME <name> SOURCES ... DEPENDS ...) defines teleop_<name>_lib (alias teleop::<name>)
# with public headers in <dir>/include.
function(teleop_library)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPENDS;PRIVATE_DEPENDS" ${ARGN})
  set(target teleop_${ARG_NAME}_lib)
  add_library(${target} ${ARG_SOURCES})
  add_library(teleop::${ARG_NAME} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  target_link_libraries(${target} PUBLIC ${ARG_DEPENDS} PRIVATE ${ARG_PRIVATE_DEPENDS})
  teleop_warnings(${target})
endfunction()

# teleop_executable(NAME <name> SOURCES ... DEPENDS ...): a thin main.
function(teleop_executable)
  cmake_parse_arguments(ARG "" "NAME" "SOURCES;DEPENDS" ${ARGN})
  add_executable(${ARG_NAME} ${ARG_SOURCES})
  target_link_libraries(${ARG_NAME} PRIVATE ${ARG_DEPENDS})
  teleop_warnings(${ARG_NAME})
  teleop_tsan_shim(${ARG_NAME})
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
