# User strings cannot inject code (docs/cli.md, "Generated C++ and reports take user text safely"): not into the
# generated C++ (banner comments, #include, string literals with trigraphs), the LaTeX or Markdown of `inspect`, nor
# through the report directory's name into a shell.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)

# A model file name with a newline and code: the banner comment keeps it on one line.
write_model(m "param u = 1 \"N??/m\\x|y~z^w\"")
set(evil "a\nstatic int x = puts(\"pwned\"), y")
file(COPY_FILE "${WORK}/m.mdl" "${WORK}/${evil}.mdl")
expect_run(STATUS 0 ARGS "${evil}.mdl" -o gen.cpp)
foreach(f gen.cpp gen.hpp)
  file(STRINGS "${WORK}/${f}" lines)
  foreach(line IN LISTS lines)
    if(line MATCHES "^static int x")
      message(SEND_ERROR "${f}: the model's file name injected a line of code: ${line}")
    endif()
  endforeach()
endforeach()
# The unit's `??/` (a backslash under -trigraphs) and `\` are escaped inside the string literal.
file(READ "${WORK}/gen.hpp" header)
string(FIND "${header}" "\"N\\?\\?/m\\\\x|y~z^w\"" unit_literal)
if(unit_literal EQUAL -1)
  message(SEND_ERROR "the unit is not written as an escaped string literal in gen.hpp")
endif()

# `-o` with a quote and a newline cannot be named in `#include "..."`: a usage error, nothing written.
tree_state(before "${WORK}")
expect_run(STATUS 2 STDERR "cannot be named in the source's #include line" ARGS m.mdl -o "q\"\n#error x.cpp")
expect_unchanged("${before}" "${WORK}" "-o with a quote")

# LaTeX and Markdown: the unit's backslash, ~, ^ and | are text, not markup.
expect_run(STATUS 0 STDOUT "textbackslash\\{\\}x\\|y\\\\textasciitilde\\{\\}z\\\\textasciicircum\\{\\}w"
  ARGS inspect m.mdl --format latex)
expect_run(STATUS 0 STDOUT "\\| N\\?\\?/m\\\\\\\\x\\\\\\|y\\\\~z\\^w \\|" ARGS inspect m.mdl --format markdown)

# A report directory named with quotes and a shell command: no shell runs it; the report and (where gnuplot is
# installed) its plots are written.
set(dir "a'; touch INJECTED; echo '")
expect_run(STATUS 0 ARGS ${FAST_FIT} --report "${dir}")
if(EXISTS "${WORK}/INJECTED")
  message(SEND_ERROR "the report directory's name ran a shell command")
endif()
if(NOT EXISTS "${WORK}/${dir}/report.md")
  message(SEND_ERROR "no report in `${dir}`")
endif()
find_program(GNUPLOT gnuplot)
if(GNUPLOT AND NOT EXISTS "${WORK}/${dir}/set1_y_F.svg")
  message(SEND_ERROR "gnuplot is installed but the plots of `${dir}` were not drawn")
endif()

# A channel name that is not UTF-8 (byte 0xFF): report.md and report.html declare UTF-8 and hold U+FFFD instead, and
# the plot titled with it stays well-formed SVG (raw, it broke the XML and the HTML's embedded image).
string(ASCII 255 ff)
file(STRINGS "${WORK}/one_frf.csv" frf_lines)
set(text "")
foreach(line IN LISTS frf_lines)
  if(line MATCHES "^f_hz")
    set(line "f_hz,y${ff}/F.re,y${ff}/F.im")
  endif()
  string(APPEND text "${line}\n")
endforeach()
file(WRITE "${WORK}/latin.csv" "${text}")
expect_run(STATUS 0 ARGS modal --data latin.csv --report latin)
file(READ "${WORK}/latin/report.md" md)
string(FIND "${md}" "y�/F" replaced)
if(replaced EQUAL -1)
  message(SEND_ERROR "report.md does not name the channel with U+FFFD")
endif()
set(checked report.md report.html)
if(GNUPLOT)
  list(APPEND checked frf_1.svg)
endif()
foreach(f IN LISTS checked)
  file(READ "${WORK}/latin/${f}" content)
  string(FIND "${content}" "${ff}" raw)
  if(NOT raw EQUAL -1)
    message(SEND_ERROR "latin/${f} holds the byte 0xFF: not UTF-8")
  endif()
endforeach()
