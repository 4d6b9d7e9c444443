# mbgen_generate(TARGET <target> MODELS <a.mdl> [<b.mdl> ...] [NAMESPACE <ns>] [OUTPUT_DIR <dir>] [PARTS <n>]
#                [OPTIONS <mbgen option> ...])
#
# Generates C++ for each model at build time with `mbgen MODEL.mdl -o NAME_model.cpp --header NAME_model.hpp`
# and compiles it into <target>, with OUTPUT_DIR on its include path and the mbgen runtime linked (both PUBLIC).
# Regenerates when a model (or mbgen itself) changes. NAME is the model file's stem. Like
# flatbuffers_generate_headers().
# - <target> need not exist: mbgen_generate then makes it, a static library of the generated code that other
#   targets link (`target_link_libraries(app PRIVATE <target>)`), or depend on when they #include the generated
#   sources themselves (`add_dependencies`). An existing target (an executable, say) gets the sources added.
#   Calling it again with the same <target> adds more models (e.g. each in a NAMESPACE of its own).
# - PARTS n > 1 (a model of hundreds of coordinates) splits each model's code into n translation units that the
#   build compiles in parallel: `--parts n`, i.e. NAME_model.cpp and NAME_model_part1.cpp .. _part<n-1>.cpp.
# - OPTIONS: further arguments of the `mbgen` compile command (e.g. `--function-ops 500`).
#
# Works in the mbgen source tree (target `mbgen`) and after find_package(mbgen) (imported `mbgen::mbgen`).
function(mbgen_generate)
  cmake_parse_arguments(ARG "" "TARGET;NAMESPACE;OUTPUT_DIR;PARTS" "MODELS;OPTIONS" ${ARGN})
  if(NOT ARG_TARGET OR NOT ARG_MODELS)
    message(FATAL_ERROR "mbgen_generate: TARGET and MODELS are required")
  endif()
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR "${CMAKE_CURRENT_BINARY_DIR}/mbgen_generated")
  endif()
  if(TARGET mbgen::mbgen)
    set(mbgen_exe mbgen::mbgen)
  else()
    message(FATAL_ERROR "mbgen_generate: no mbgen executable (call find_package(mbgen) first)")
  endif()
  if(NOT ARG_PARTS)
    set(ARG_PARTS 1)
  endif()
  if(NOT ARG_PARTS MATCHES "^[1-9][0-9]*$")
    message(FATAL_ERROR "mbgen_generate: PARTS must be a positive integer, not `${ARG_PARTS}`")
  endif()
  if(NOT TARGET ${ARG_TARGET})
    add_library(${ARG_TARGET} STATIC)
  endif()
  file(MAKE_DIRECTORY "${ARG_OUTPUT_DIR}")
  foreach(model IN LISTS ARG_MODELS)
    get_filename_component(model_abs "${model}" ABSOLUTE)
    get_filename_component(stem "${model}" NAME_WE)
    set(cpp "${ARG_OUTPUT_DIR}/${stem}_model.cpp")
    set(hpp "${ARG_OUTPUT_DIR}/${stem}_model.hpp")
    set(ns_args "")
    if(ARG_NAMESPACE)
      set(ns_args --namespace "${ARG_NAMESPACE}")
    endif()
    set(parts "")
    if(ARG_PARTS GREATER 1)
      math(EXPR last "${ARG_PARTS} - 1")
      foreach(k RANGE 1 ${last})
        list(APPEND parts "${ARG_OUTPUT_DIR}/${stem}_model_part${k}.cpp")
      endforeach()
    endif()
    add_custom_command(
      OUTPUT "${cpp}" "${hpp}" ${parts}
      COMMAND ${mbgen_exe} "${model_abs}" -o "${cpp}" --header "${hpp}" ${ns_args} --parts ${ARG_PARTS} ${ARG_OPTIONS}
      DEPENDS "${model_abs}" ${mbgen_exe}
      COMMENT "mbgen: generating C++ for ${model}"
      VERBATIM)
    target_sources(${ARG_TARGET} PRIVATE "${cpp}" "${hpp}" ${parts})
  endforeach()
  target_include_directories(${ARG_TARGET} PUBLIC "${ARG_OUTPUT_DIR}")
  target_link_libraries(${ARG_TARGET} PUBLIC mbgen::runtime)
endfunction()
