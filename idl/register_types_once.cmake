# Run on fastddsgen's -typeobject output (idl/CMakeLists.txt):
#   cmake -DGEN_DIR=<dir> -DNAMES="base;arm;..." -P register_types_once.cmake
# fastddsgen 2.3 registers a file's type objects from every default constructor of its types: a
# lookup and insertion per type into Fast DDS's type object factory, with std::string keys, each
# time (40 allocations for a JointState, measured). Samples are constructed on the control loop
# (a NodeStatus's links are emplaced each status), which must not allocate. Later fastddsgen
# versions guard the registration with std::call_once; this does the same to the generated files.
foreach(name IN LISTS NAMES)
  set(file ${GEN_DIR}/${name}TypeObject.cxx)
  file(READ ${file} text)
  set(head "void register${name}Types()\n{")
  string(FIND "${text}" "${head}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${file}: no register${name}Types() to guard (has fastddsgen's output changed?)")
  endif()
  string(REPLACE "${head}" "static void register${name}Types_unguarded()\n{" text "${text}")
  string(PREPEND text "#include <mutex>\n")
  string(APPEND text
    "\n// idl/register_types_once.cmake: the type objects are registered once per process\n"
    "void register${name}Types()\n{\n    static std::once_flag once;\n"
    "    std::call_once(once, register${name}Types_unguarded);\n}\n")
  file(WRITE ${file} "${text}")
endforeach()
