# The syntax docs/language.md documents is accepted: `pi`, functions of numbers and products with pi in parameter
# values (they failed with "gcd: arguments must be polynomials over the rationals" and no location), the issue's
# `rho*pi*r^2*0.5` with rho and r parameters too.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
foreach(value "pi" "sin(0.5)" "7800*pi*0.1^2*0.5" "rho*pi*r^2*0.5")
  string(MAKE_C_IDENTIFIER "${value}" name)
  file(WRITE "${WORK}/${name}.mdl" "model m\nparam rho = 7800; param r = 0.1\nparam m1 = ${value}\nparam k = 1000\n"
             "ground g\nbody b { mass m1; dof x }\nspring s { from g; to b; along x; stiffness k }\ninput F force on b along x\n"
             "output y displacement of b along x\n")
  expect_run(STATUS 0 STDOUT "Transfer functions" ARGS inspect ${name}.mdl)
  expect_run(STATUS 0 ARGS ${name}.mdl -o ${name}.cpp)
endforeach()
