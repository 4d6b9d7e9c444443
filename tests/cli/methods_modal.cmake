# `fit --method modal` (docs/methods.md#modal): time records and data with too few modes for the parameters are bad
# input (status 1, saying why, nothing written); mdof2's FRFs give a result of method "modal" with its details.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
set(MDOF2_TIME "${SOURCE}/examples/mdof2/data/time_F1.csv")

expect_run(STATUS 1 STDERR "time_F1.csv: error: --method modal needs FRFs"
  ARGS fit ${MDOF2} --data ${MDOF2_TIME} --method modal --json t.json)
if(EXISTS "${WORK}/t.json")
  message(SEND_ERROR "--method modal on a time record wrote its JSON although it failed")
endif()

# The driving point alone: two modes, but per mode only frequency and scale: 4 numbers for 5 mass/stiffness parameters.
write_mdof2_d1_only(d1_only.csv)
expect_run(STATUS 1 STDERR "--method modal: the FRFs show 2 mode\\(s\\) .* which give 4 numbers .* fewer than the 5 mass/stiffness parameters.*\nnote: --method auto does without enough identified modes for the parameters to estimate\n"
  ARGS fit ${MDOF2} --data d1_only.csv --method modal)

expect_run(STATUS 0 STDOUT "modal\\)" ARGS fit ${MDOF2} --data ${MDOF2_FRF} --method modal --starts 4 --json m.json)
file(READ "${WORK}/m.json" json)
string(JSON method GET "${json}" method)
string(JSON subproblems LENGTH "${json}" method_details modal partition subproblems)
string(JSON modes LENGTH "${json}" method_details modal reference_modes)
if(NOT method STREQUAL "modal" OR NOT subproblems EQUAL 2 OR NOT modes EQUAL 2)
  message(SEND_ERROR "modal: method ${method}, ${subproblems} subproblems, ${modes} reference modes")
endif()
# The method gives no standard deviations: they are null in the JSON (once written as 0, a false certainty).
string(JSON k11_std TYPE "${json}" parameters k11 std)
if(NOT k11_std STREQUAL "NULL")
  message(SEND_ERROR "modal: parameters.k11.std is ${k11_std}, expected null (the method gives no std)")
endif()
