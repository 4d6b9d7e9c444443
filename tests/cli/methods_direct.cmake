# `fit --method direct` and `--method hybrid` (docs/methods.md): data that cannot give every coordinate's motion is
# bad input (status 1) naming what is missing, and nothing is written; data that can (mdof2 measures both masses)
# gives a result of method "direct" / "hybrid" with the method's details.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
set(SPINDLE "${SOURCE}/examples/spindle/spindle.mdl")
set(SPINDLE_FRF "${SOURCE}/examples/spindle/data/frf_Fx.csv")

# The spindle's three x sensors against the five coordinates its x force moves.
foreach(method direct hybrid)
  expect_run(STATUS 1
    STDERR "frf_Fx.csv: error: --method direct needs the motion of every coordinate the input Fx moves \\(5: spindle.x, spindle.ry, housing.x, housing.ry, housing.rz\\), but the outputs measured \\(3: xs_front, xs_rear, xh_front\\) cannot give housing.x, housing.ry, housing.rz"
    ARGS fit ${SPINDLE} --data ${SPINDLE_FRF} --method ${method} --json out_${method}.json)
  if(EXISTS "${WORK}/out_${method}.json")
    message(SEND_ERROR "--method ${method} on the spindle wrote its JSON although it failed")
  endif()
endforeach()

# mdof2 with one of its two sensors: mass2.x is missing.
write_mdof2_d1_only(d1_only.csv)
expect_run(STATUS 1 STDERR "d1_only.csv: error: --method direct needs .* cannot give mass2.x"
  ARGS fit ${MDOF2} --data d1_only.csv --method direct)

# Unknown method names stay usage errors.
expect_run(STATUS 2 STDERR "--method" ARGS fit ${MDOF2} --data ${MDOF2_FRF} --method directt)

# Both masses measured: it runs, and says what it did.
expect_run(STATUS 0 STDOUT "direct\\)" ARGS fit ${MDOF2} --data ${MDOF2_FRF} --method direct --json d.json)
file(READ "${WORK}/d.json" json)
string(JSON method GET "${json}" method)
string(JSON solver GET "${json}" method_details direct solver)
string(JSON coordinates GET "${json}" method_details direct coordinates)
if(NOT method STREQUAL "direct" OR NOT solver STREQUAL "instrumental variables" OR NOT coordinates MATCHES "mass1.x.*mass2.x")
  message(SEND_ERROR "direct: method ${method}, solver ${solver}, coordinates ${coordinates}")
endif()
expect_run(STATUS 0 STDOUT "hybrid\\)" ARGS fit ${MDOF2} --data ${MDOF2_FRF} --method hybrid --starts 2 --json h.json)
file(READ "${WORK}/h.json" json)
string(JSON combines GET "${json}" method_details hybrid combines)
if(NOT combines MATCHES "^direct .* then frf-output-error")
  message(SEND_ERROR "hybrid: combines `${combines}`")
endif()
