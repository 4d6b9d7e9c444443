# --report DIR never deletes what the user had (docs/cli.md, "Report directories"): it writes into a new directory,
# an empty one, or one mbgen wrote before (marker file); otherwise it exits 1 touching nothing.
include(${CMAKE_CURRENT_LIST_DIR}/cli_support.cmake)
set(fit ${FAST_FIT})

# A directory of the user's: refused, its file kept.
file(WRITE "${WORK}/mine/keep" "notes\n")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "mine: error: cannot write a report here: .*did not write" ARGS ${fit} --report mine)
expect_unchanged("${before}" "${WORK}" "--report into a user's directory")

# An existing file: refused, not turned into a directory.
file(WRITE "${WORK}/afile" "text\n")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "afile: error: .*not a directory" ARGS ${fit} --report afile)
expect_unchanged("${before}" "${WORK}" "--report naming a file")

# The directory that holds the data: refused (no marker), the data kept.
file(COPY "${WORK}/one_frf.csv" DESTINATION "${WORK}/datadir")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "datadir: error: cannot write a report here" ARGS
  fit one.mdl --data datadir/one_frf.csv --starts 1 --report datadir)
expect_unchanged("${before}" "${WORK}" "--report naming the data's directory")

# `.` and `old/` (the working directory, a trailing slash): refused, nothing deleted.
file(WRITE "${WORK}/old/inside" "x\n")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "working directory" ARGS ${fit} --report .)
expect_run(STATUS 1 STDERR "old: error: cannot write a report here" ARGS ${fit} --report old/)
expect_unchanged("${before}" "${WORK}" "--report . and old/")

# --json inside the report directory: a usage error, before any work.
tree_state(before "${WORK}")
expect_run(STATUS 2 STDERR "--json: .*inside the report directory" ARGS ${fit} --json out/f.json --report out)
expect_unchanged("${before}" "${WORK}" "--json inside --report")

# `-` (standard output elsewhere) cannot hold a directory: a usage error; it made a directory named `-`.
tree_state(before "${WORK}")
expect_run(STATUS 2 STDERR "^mbgen: --report: - \\(standard output\\) cannot hold a report directory"
  ARGS ${fit} --report -)
expect_unchanged("${before}" "${WORK}" "--report -")

# A new directory, then the same directory again (it carries the marker): replaced whole.
expect_run(STATUS 0 ARGS ${fit} --report new)
if(NOT EXISTS "${WORK}/new/report.md" OR NOT EXISTS "${WORK}/new/.mbgen-report")
  message(SEND_ERROR "the report or its marker is missing")
endif()
file(WRITE "${WORK}/new/set1_y_F.dat" "stale\n")  # an entry the marker lists: replaced
expect_run(STATUS 0 ARGS ${fit} --report new)
file(READ "${WORK}/new/set1_y_F.dat" dat LIMIT 10)
if(dat MATCHES "stale")
  message(SEND_ERROR "the report directory was not replaced")
endif()
expect_no_temporaries("${WORK}")

# An mbgen report directory to which the user added a file: refused, the file named and kept.
file(WRITE "${WORK}/new/my_notes.md" "mine\n")
tree_state(before "${WORK}")
expect_run(STATUS 1 STDERR "new: error: .*`my_notes.md` was not written by mbgen" ARGS ${fit} --report new)
expect_unchanged("${before}" "${WORK}" "--report into an mbgen directory with a user's file")

# An empty directory: written into.
file(MAKE_DIRECTORY "${WORK}/empty")
expect_run(STATUS 0 ARGS ${fit} --report empty)
if(NOT EXISTS "${WORK}/empty/report.md")
  message(SEND_ERROR "no report in the empty directory")
endif()
expect_no_temporaries("${WORK}")

# A report staged by a run killed with kill -9 (the hidden directory `.NAME.mbgen-tmp-HOST-PID`, its process gone)
# is removed by the next run that writes that report.
cmake_host_system_information(RESULT host QUERY HOSTNAME)
string(REGEX REPLACE "[^A-Za-z0-9-]" "_" host "${host}")
file(WRITE "${WORK}/.killed.mbgen-tmp-${host}-99999999/report.md" "half-written\n")
expect_run(STATUS 0 ARGS ${fit} --report killed)
if(EXISTS "${WORK}/.killed.mbgen-tmp-${host}-99999999" OR NOT EXISTS "${WORK}/killed/report.md")
  message(SEND_ERROR "the staged report of a killed run was not removed, or the new report is missing")
endif()
expect_no_temporaries("${WORK}")
