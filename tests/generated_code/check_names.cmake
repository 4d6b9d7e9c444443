# Model names and namespaces in the emitted C++ (issue 36, docs/cli.md): the macros and C library types of the
# headers the generated code includes are refused (status 1 for a model's name, 2 for --namespace), and so is a
# top-level namespace of a name they declare at global scope; every name that is accepted gives code that compiles
# (-fsyntax-only with the compiler that built mbgen), under mbgen_models:: and as a top-level namespace.
#   -DMBGEN=... -DCXX=... -DINCLUDES="-I...|-I..." -DWORK=... -DSOURCE=...
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
string(REPLACE "|" ";" includes "${INCLUDES}")

function(model_named name)
  file(WRITE "${WORK}/${name}.mdl"
       "model ${name}\nparam m = 2 \"kg\" estimate in [0.5, 10]\nparam k = 1000\nground g\nbody b { mass m; dof x }\n"
       "spring s { from g; to b; along x; stiffness k; damping 1 }\ninput F force on b along x\n"
       "output y displacement of b along x\n")
endfunction()

# Refused, with the reason.
foreach(name INFINITY NAN M_PI HUGE_VAL INT_MAX EXIT_FAILURE EIGEN_PI EIGEN_DEFAULT_DENSE_INDEX_TYPE size_t int8_t
             uint64_t MBGEN_GENERATED_TEMPLATES_ONLY)
  model_named(${name})
  execute_process(COMMAND "${MBGEN}" ${name}.mdl -o ${name}.cpp WORKING_DIRECTORY "${WORK}"
                  RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT status EQUAL 1 OR NOT err MATCHES "${name}.mdl:1:7: error: .*`${name}`")
    message(SEND_ERROR "model ${name}: expected status 1 naming it at the model statement, got ${status}: ${err}")
  endif()
  execute_process(COMMAND "${MBGEN}" ${SOURCE}/examples/mdof2/mdof2.mdl -o ns_${name}.cpp --namespace ${name}
                  WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT status EQUAL 2 OR NOT err MATCHES "`${name}`")
    message(SEND_ERROR "--namespace ${name}: expected status 2, got ${status}: ${err}")
  endif()
endforeach()

# A top-level namespace may not take a name the headers declare at global scope (inside mbgen_models:: it may).
foreach(name sin y0 FILE div)
  execute_process(COMMAND "${MBGEN}" ${SOURCE}/examples/mdof2/mdof2.mdl -o top.cpp --namespace ${name}
                  WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT status EQUAL 2 OR NOT err MATCHES "declared at global scope")
    message(SEND_ERROR "--namespace ${name}: expected status 2 (declared at global scope), got ${status}: ${err}")
  endif()
endforeach()

# Accepted names compile: names of the C library's functions and the code's own words, and random identifiers.
set(names sin y0 pow abs exp FILE div Matrix VectorXd Scalar Model model value values make_model p_m std_ eigen
          Infinity nan_ m_pi)
foreach(i RANGE 1 6)
  string(RANDOM LENGTH 6 ALPHABET "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_0123456789" RANDOM_SEED ${i}
         tail)
  string(RANDOM LENGTH 1 ALPHABET "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ" RANDOM_SEED ${i} head)
  list(APPEND names "${head}${tail}")
endforeach()
foreach(name IN LISTS names)
  model_named(${name})
  execute_process(COMMAND "${MBGEN}" ${name}.mdl -o ${name}_model.cpp WORKING_DIRECTORY "${WORK}"
                  RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
  if(NOT status EQUAL 0)
    if(err MATCHES "reserved|macro|keyword")  # a random name that happens to be reserved (`__`)
      continue()
    endif()
    message(SEND_ERROR "model ${name}: mbgen failed (${status}): ${err}")
    continue()
  endif()
  foreach(top "" "--namespace;${name}")
    if(top)
      execute_process(COMMAND "${MBGEN}" ${name}.mdl -o top_${name}_model.cpp ${top} WORKING_DIRECTORY "${WORK}"
                      RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_QUIET)
      if(status EQUAL 2 AND err MATCHES "cannot name the generated namespace: `${name}` is")
        continue()  # refused, with the reason: fine (sin, FILE: declared at global scope)
      elseif(NOT status EQUAL 0)
        message(SEND_ERROR "--namespace ${name}: mbgen failed (${status}): ${err}")
        continue()
      endif()
      set(source top_${name}_model.cpp)
    else()
      set(source ${name}_model.cpp)
    endif()
    execute_process(COMMAND "${CXX}" -std=c++17 -fsyntax-only -Wall -Wextra -Werror ${includes} ${source}
                    WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status ERROR_VARIABLE err)
    if(NOT status EQUAL 0)
      message(SEND_ERROR "the code emitted for ${name} (${source}) does not compile:\n${err}")
    endif()
  endforeach()
endforeach()
