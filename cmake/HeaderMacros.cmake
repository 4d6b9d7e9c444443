# The macros that the headers generated code includes define (<cmath>, <limits>, Eigen, the runtime's headers), as
# the compiler building mbgen sees them: a model name or namespace equal to one (INFINITY, M_PI, EIGEN_PI, INT_MAX)
# would be replaced by the preprocessor and the emitted code would not compile (docs/cli.md). Written at configure
# time to OUT as C++ string literals, one per line, sorted, for compiler/ir/identifier.cpp.
function(mbgen_write_header_macros out)
  get_target_property(eigen_dirs Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
  set(flags -std=c++17 -dM -E -x c++ -I${PROJECT_SOURCE_DIR}/runtime/include)
  foreach(d IN LISTS eigen_dirs)
    list(APPEND flags -I${d})
  endforeach()
  set(probe "${CMAKE_CURRENT_BINARY_DIR}/header_macros_probe.cpp")
  file(WRITE "${probe}" "#include <array>\n#include <cmath>\n#include <limits>\n#include <memory>\n#include <stdexcept>\n"
                        "#include <string>\n#include <vector>\n#include <Eigen/Core>\n#include \"mbgen/model.hpp\"\n"
                        "#include \"mbgen/state_space_form.hpp\"\n#include \"mbgen/transfer_function.hpp\"\n")
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} ${flags} "${probe}" RESULT_VARIABLE status OUTPUT_VARIABLE defines
                  ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "listing the macros of the generated code's headers failed:\n${err}")
  endif()
  string(REGEX MATCHALL "#define [A-Za-z][A-Za-z0-9_]*" found "${defines}")
  set(names "")
  foreach(d IN LISTS found)
    string(SUBSTRING "${d}" 8 -1 name)
    list(APPEND names "${name}")
  endforeach()
  list(REMOVE_DUPLICATES names)
  list(SORT names)
  set(text "// Written by cmake/HeaderMacros.cmake: macros of the headers generated code includes, sorted.\n")
  foreach(name IN LISTS names)
    string(APPEND text "\"${name}\",\n")
  endforeach()
  file(WRITE "${out}.new" "${text}")
  file(COPY_FILE "${out}.new" "${out}" ONLY_IF_DIFFERENT)
  # The same headers preprocessed, for list_global_names (the names they declare at global scope).
  list(REMOVE_ITEM flags -dM)
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} ${flags} -P "${probe}" -o "${CMAKE_CURRENT_BINARY_DIR}/header_probe.ii"
                  RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "preprocessing the generated code's headers failed:\n${err}")
  endif()
endfunction()
