# --start-from-modes (docs/estimation.md, "Start from the data's modes"): fit and diagnose also start where the
# model's modes match the data's own. Data from the independent truth generator (scripts/truthgen): a drawn
# five-storey tower; the example's model with every storey stiffness 10 times its truth's, from where the plain
# search stops far from the data (measured: nrmse 0.78, with parameters at bounds) and the start from the modes
# reaches the noise (nrmse 0.0091). A fit that ends with most parameters at a bound names the option (at_bound.cmake).
# ctest-timeout: 900
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
execute_process(COMMAND /usr/bin/python3 "${SOURCE}/scripts/truthgen/truthgen.py" --example tower5 --case nominal
                        --draw 2 --seed 102 -o "${WORK}/tower.csv"
                RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "truthgen failed: ${err}")
endif()
set(TOWER "${SOURCE}/examples/tower5/tower5.mdl")
set(STIFF --set k1=2e7 --set k2=2e7 --set k3=2e7 --set k4=2e7 --set k5=2e7)

# From the priors alone (the case this option is for): far from the data.
expect_run(STATUS 0 STDOUT "\nnrmse 0\\.[3-9]"
  ARGS fit ${TOWER} --data tower.csv ${STIFF})
expect_run(STATUS 0 STDERR "fit: start from the data's modes: 5 modes \\(0\\.649-3\\.952 Hz\\): 10 mass/stiffness and 5 damping parameters placed"
  STDOUT "\nnrmse 0\\.00[0-9]+ "
  ARGS fit ${TOWER} --data tower.csv ${STIFF} --start-from-modes --json fit.json)
file(READ "${WORK}/fit.json" json)
string(JSON summary GET "${json}" method_details start_from_modes summary)
string(JSON k1 GET "${json}" method_details start_from_modes values k1)
if(NOT summary MATCHES "^5 modes" OR k1 LESS 9.5e5 OR k1 GREATER 1.06e6)  # the truth's k1: 1.003e6
  message(SEND_ERROR "fit JSON: the start is not recorded as placed on 5 modes near the truth: ${summary}, k1 ${k1}")
endif()

# The diagnosis's nominal fit: with the start, the model explains the data and nothing is found.
expect_run(STATUS 0 STDOUT "verdict: no_extension_justified" STDERR "nominal model: nrmse 0\\.01[0-9]*," TIMEOUT 300
  ARGS diagnose ${TOWER} --data tower.csv ${STIFF} --start-from-modes)

# Methods with starts of their own refuse it, saying what to do.
expect_run(STATUS 1 STDERR "--start-from-modes starts the output-error search; --method modal has its own starts"
  ARGS fit ${TOWER} --data tower.csv --method modal --start-from-modes)
