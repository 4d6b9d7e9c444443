# Inputs that gave wrong results with exit status 0 are refused with status 1 (or 2 for a malformed option):
# negative mass, --set or `# set` values outside the bounds or with a singular mass matrix, data that is zero or too
# large to square, a name declared twice across kinds, and model names or namespaces that are not valid C++.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

file(WRITE "${WORK}/neg.mdl" "model neg\nparam m1 = -2\nground g\nbody b { mass m1; dof x }\n"
           "spring s { from g; to b; along x; stiffness 1000 }\n")
expect_run(STATUS 1 STDERR "^neg.mdl:4:6: error: coordinate b.x has a negative mass" ARGS inspect neg.mdl)

write_model(m)
expect_run(STATUS 1 STDERR "^m.mdl:2:7: error: --set m1=20: outside the bounds \\[0.5, 10\\]" ARGS inspect m.mdl --set m1=20)
write_model(outside "param v = 3 in [0, 1]")
expect_run(STATUS 1 STDERR "^outside.mdl:9:11: error: the value of parameter `v` lies outside its bounds" ARGS inspect outside.mdl)

# `sensitivity --sweep` is held to what --set is: within the declared bounds, and a positive definite mass matrix at
# every point. Sweeps beyond the bounds and through negative masses were computed with status 0.
expect_run(STATUS 1 STDERR "^m.mdl:2:7: error: --sweep m1=5:20:3: outside the bounds \\[0.5, 10\\] declared for `m1`"
  ARGS sensitivity m.mdl --sweep m1=5:20:3)
expect_run(STATUS 0 STDOUT "feature map: m1 from 0.5 to 10, 3 points" ARGS sensitivity m.mdl --sweep m1=0.5:10:3)
file(WRITE "${WORK}/free.mdl" "model free\nparam m1 = 2\nground g\nbody b { mass m1; dof x }\n"
           "spring s { from g; to b; along x; stiffness 1000 }\n")
expect_run(STATUS 1 STDERR "^free.mdl:2:7: error: --sweep m1=-2:1:4: at m1 = -2 the mass matrix is not positive"
  ARGS sensitivity free.mdl --sweep m1=-2:1:4)
expect_run(STATUS 1 STDERR "^free.mdl:2:7: error: --sweep m1=0:1:3: at m1 = 0 the mass matrix"
  ARGS sensitivity free.mdl --sweep m1=0:1:3)

# Data: `# set m1=0.000` (the mass matrix singular, as --set m1=0 is refused), all-zero and 1e300 values.
file(STRINGS "${MDOF2_FRF}" lines)
list(GET lines 1 header)
list(SUBLIST lines 2 -1 rows)
set(zero "${header}\n")
set(huge "${header}\n")
set(set0 "# set m1=0.000\n${header}\n")
foreach(row IN LISTS rows)
  string(REGEX MATCH "^[^,]+" f "${row}")
  string(APPEND zero "${f},0,0,0.9,0,0,0.9\n")
  string(APPEND huge "${f},1e300,-1e300,0.9,1e300,1e300,0.9\n")
  string(APPEND set0 "${row}\n")
endforeach()
file(WRITE "${WORK}/zero.csv" "${zero}")
file(WRITE "${WORK}/huge.csv" "${huge}")
file(WRITE "${WORK}/set0.csv" "${set0}")
expect_run(STATUS 1 STDERR "^set0.csv:1: error: the values of its `# set` lines are not admissible: the mass matrix"
  ARGS fit ${MDOF2} --data set0.csv --starts 1)
# Every `# set` value is checked by the code that checks --set's (symbolic::ParameterTable), at its line: exactly
# against the declared bounds (a double just below 1/3 passed the bounds compared as doubles), within the range of a
# double (1e-310 passed), and a derived parameter is named as such (it was "no free parameter").
write_model(setm "param third = 0.5 in [1/3, 1]" "param tiny = 1" "param k2 = 10 in [1, 1e9]" "param twice = 2*c")
foreach(case "third=0.3333333333333333|outside the bounds \\[1/3, 1\\] declared for `third` \\(setm.mdl:9:7\\)"
             "tiny=1e-310|the value of `tiny` is beyond the range of a double"
             "k2=0|outside the bounds \\[1, 1e9\\] declared for `k2`"
             "twice=3|`twice` is derived \\(= 2\\*c\\) and cannot be set"
             "nothing=1|the model has no parameter named `nothing`")
  string(REPLACE "|" ";" case "${case}")
  list(GET case 0 assignment)
  list(GET case 1 why)
  string(REGEX REPLACE "[=.*+-]" "_" stem "${assignment}")
  file(READ "${WORK}/one_frf.csv" one_frf)
  file(WRITE "${WORK}/set_${stem}.csv" "# set m1=2\n# set ${assignment}\n${one_frf}")
  string(REPLACE "." "\\." shown "${assignment}")
  expect_run(STATUS 1 STDERR "^set_${stem}.csv:2: error: # set ${shown}: ${why}"
    ARGS fit setm.mdl --data set_${stem}.csv --starts 1)
endforeach()
# The same values by --set, for comparison: the same checks.
expect_run(STATUS 1 STDERR "--set third=0.3333333333333333: outside the bounds \\[1/3, 1\\]"
  ARGS fit setm.mdl --data one_frf.csv --starts 1 --set third=0.3333333333333333)
expect_run(STATUS 1 STDERR "^zero.csv: error: FRF d1/F1 is zero at every frequency" ARGS fit ${MDOF2} --data zero.csv --starts 1)
# The modal analysis too: it reported no modes and a channel error of 0 (a perfect fit) with status 0.
expect_run(STATUS 1 STDERR "^zero.csv: error: channel d1/F1 is zero at every line in the band"
  ARGS modal --data zero.csv)
expect_run(STATUS 1 STDERR "^huge.csv:2:2: error: '1e300' is too large" ARGS fit ${MDOF2} --data huge.csv --starts 1)

# Signals too small to square: every value's square below the smallest normal double. The FRF and the record's
# output gave nrmse NaN with status 0 (and an estimate with a std); an input that small gave nrmse 1 with status 0.
file(STRINGS "${WORK}/one_frf.csv" one_lines)
set(tiny_frf "")
foreach(line IN LISTS one_lines)
  if(line MATCHES "^[0-9]")
    string(REGEX MATCH "^[^,]+" f "${line}")
    string(APPEND tiny_frf "${f},1e-200,-3e-201\n")
  elseif(NOT line MATCHES "^#")
    string(APPEND tiny_frf "${line}\n")
  endif()
endforeach()
file(WRITE "${WORK}/tiny_frf.csv" "${tiny_frf}")
expect_run(STATUS 1
  STDERR "^tiny_frf.csv: error: FRF y/F is too small to fit: its largest magnitude, 1.04403e-200, is below 1e-150"
  ARGS fit one.mdl --data tiny_frf.csv --starts 1)
expect_run(STATUS 1 STDERR "^tiny_frf.csv: error: channel y/F is too small to analyse" ARGS modal --data tiny_frf.csv)
set(tiny_out "t,F,y\n")
set(tiny_in "t,F,y\n")
foreach(i RANGE 0 199)
  math(EXPR sign "1 - 2 * (${i} % 2)")
  string(APPEND tiny_out "${i}e-3,${sign},${sign}e-200\n")
  string(APPEND tiny_in "${i}e-3,${sign}e-200,${sign}e-3\n")
endforeach()
# A record without a column for the model's input: said to be "every input is zero throughout the record".
file(WRITE "${WORK}/no_input.csv" "t,y\n0,0\n1e-3,1e-4\n2e-3,2e-4\n3e-3,1e-4\n")
expect_run(STATUS 1 STDERR "^no_input.csv: error: the record has no column of the model's inputs \\(F\\)"
  ARGS fit one.mdl --data no_input.csv --starts 1)
file(WRITE "${WORK}/tiny_out.csv" "${tiny_out}")
file(WRITE "${WORK}/tiny_in.csv" "${tiny_in}")
expect_run(STATUS 1 STDERR "^tiny_out.csv: error: output y is too small to fit: its largest magnitude, 1e-200, is below"
  ARGS fit one.mdl --data tiny_out.csv --starts 1)
expect_run(STATUS 1 STDERR "^tiny_in.csv: error: every input is too small: its largest magnitude, 1e-200, is below"
  ARGS fit one.mdl --data tiny_in.csv --starts 1)

# A model with nothing to estimate: the fit compares it with the data, and says so (it printed an empty table).
file(READ "${WORK}/one.mdl" one_text)
string(REPLACE " estimate in [0.5, 10]" "" fixed_text "${one_text}")
file(WRITE "${WORK}/fixed.mdl" "${fixed_text}")
expect_run(STATUS 0 STDOUT "no parameter is declared `estimate`: the model is compared with the data at its values"
  ARGS fit fixed.mdl --data one_frf.csv --starts 1)

# One name for a parameter, a spring and an input.
file(WRITE "${WORK}/twice.mdl" "model twice\nparam F = 1000\nground g\nbody b { mass 1; dof x }\n"
           "spring F { from g; to b; along x; stiffness F }\ninput F force on b along x\n")
expect_run(STATUS 1 STDERR "^twice.mdl:5:8: error: `F` is already declared at line 2, column 7 \\(as a parameter\\)"
  ARGS inspect twice.mdl)

# Model names that cannot name a C++ namespace, and such --namespace values.
foreach(name namespace int std mbgen Eigen)
  file(WRITE "${WORK}/${name}.mdl" "model ${name}\nground g\nbody b { mass 1; dof x }\n"
             "spring s { from g; to b; along x; stiffness 1 }\n")
  expect_run(STATUS 1 STDERR "^${name}.mdl:1:7: error: the model's name `${name}` cannot name its C\\+\\+ namespace"
    ARGS ${name}.mdl -o ${name}.cpp)
endforeach()
expect_run(STATUS 2 STDERR "--namespace: `class::new` cannot name the generated namespace: `class` is a C\\+\\+ keyword"
  ARGS m.mdl -o m.cpp --namespace class::new)
expect_run(STATUS 2 STDERR "--namespace: `a b` cannot name" ARGS m.mdl -o m.cpp --namespace "a b")
file(GLOB written "${WORK}/*.cpp" "${WORK}/*.hpp")
if(written)
  message(SEND_ERROR "C++ written for a refused model or namespace: ${written}")
endif()

# Masses and stiffnesses 1e600 apart: no double holds M^-1 K. `inspect` said "the eigenvalue iteration did not
# converge" without naming the model, `sensitivity` called it an internal error (status 3), and the fit's singular
# dynamic stiffness named no file either.
file(WRITE "${WORK}/apart.mdl" "model apart\nparam k = 1e300 estimate\nparam m1 = 1e-300\nground g\n"
           "body b { mass m1; dof x }\nspring s { from g; to b; along x; stiffness k }\ninput F force on b along x\n"
           "output y displacement of b along x\n")
expect_run(STATUS 1 STDERR "^apart.mdl: error: cannot compute the modes at the current parameter values: .*overflows a double"
  ARGS inspect apart.mdl)
expect_run(STATUS 1 STDERR "^apart.mdl: error: .*overflows a double" ARGS sensitivity apart.mdl)
expect_run(STATUS 1 STDERR "^apart.mdl: error: " ARGS fit apart.mdl --data one_frf.csv --starts 1)
