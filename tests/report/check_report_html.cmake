# report.html in a real browser (issue 17): a fit and a diagnosis of examples/mdof2, under a model and a data file
# whose names carry `<script>`, `&` and quotes and a unit that closes the table and opens a script, each opened by
# headless Chromium. Checked: the HTML names nothing outside itself; it has the Markdown's headings, tables and
# figures; in the browser's DOM the tables are there, every plot decodes to an image of non-zero size, nothing was
# requested, and the hostile strings are text, not elements; the same input gives the same bytes.
#   cmake -DMBGEN=... -DSOURCE=<source tree> -DWORK=<scratch directory> -P check_report_html.cmake
# A screenshot of each report is left in WORK (fit.png, diag.png) for a human look.
if(NOT MBGEN OR NOT SOURCE OR NOT WORK)
  message(FATAL_ERROR "usage: cmake -DMBGEN=... -DSOURCE=... -DWORK=... -P check_report_html.cmake")
endif()
find_program(CHROMIUM NAMES chromium chromium-browser google-chrome-stable google-chrome)
if(NOT CHROMIUM)
  message("SKIPPED: Chromium is not installed, so report.html was not opened in a browser (scripts/setup installs "
          "Debian's chromium)")
  return()
endif()
find_program(GNUPLOT gnuplot)
if(NOT GNUPLOT)
  message("SKIPPED: gnuplot is not installed, so the reports have no plots to check (scripts/setup installs it)")
  return()
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# The hostile names: a model file and a data file named with a script tag, an entity and both quotes, and the
# masses' unit ending the table cell, the row and the table before a script.
# (`&copy` is read as an entity even without its `;`, which CMake would take for a list separator.)
set(evil "evil <script>alert(\"a&copy\")'")
set(evil_html "evil &lt;script&gt;alert(&quot;a&amp;copy&quot;)&#39;")  # as report.html must write it
set(unit "kg</td></tr></table><script>alert(2)</script>")
set(unit_html "kg&lt;/td&gt;&lt;/tr&gt;&lt;/table&gt;&lt;script&gt;alert(2)&lt;/script&gt;")
file(READ "${SOURCE}/examples/mdof2/mdof2.mdl" model)
string(REPLACE "\"kg\"" "\"${unit}\"" model "${model}")
file(WRITE "${WORK}/${evil}.mdl" "${model}")
file(COPY_FILE "${SOURCE}/examples/mdof2/data/frf_F1.csv" "${WORK}/${evil}.csv")

function(run_mbgen)
  execute_process(COMMAND "${MBGEN}" ${ARGN} WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE status
                  OUTPUT_QUIET ERROR_VARIABLE err TIMEOUT 120)
  if(NOT status EQUAL 0)
    string(REPLACE ";" " " shown "${ARGN}")
    message(FATAL_ERROR "`mbgen ${shown}` failed (${status}):\n${err}")
  endif()
endfunction()
run_mbgen(fit "${evil}.mdl" --data "${evil}.csv" --starts 2 --report fit)
run_mbgen(fit "${evil}.mdl" --data "${evil}.csv" --starts 2 --report fit_again)
run_mbgen(diagnose "${evil}.mdl" --data "${evil}.csv" --report diag)

file(SHA256 "${WORK}/fit/report.html" first)
file(SHA256 "${WORK}/fit_again/report.html" second)
if(NOT first STREQUAL second)
  message(SEND_ERROR "report.html differs between two runs of the same fit")
endif()

# The number of matches of `regex` in `text`: replacing each by one character and by two, the lengths differ by it
# (a list of the matches would be miscounted: they may hold `;` or `[`).
function(count_matches var regex text)
  string(REGEX REPLACE "${regex}" "x" one "${text}")
  string(REGEX REPLACE "${regex}" "xx" two "${text}")
  string(LENGTH "${one}" n1)
  string(LENGTH "${two}" n2)
  math(EXPR n "${n2} - ${n1}")
  set(${var} ${n} PARENT_SCOPE)
endfunction()

# chromium(out_var url args...): headless Chromium's standard output for URL; its profile kept inside WORK.
function(chromium var url)
  execute_process(COMMAND "${CHROMIUM}" --headless --no-sandbox --disable-gpu --disable-dev-shm-usage
                          --no-first-run --user-data-dir=${WORK}/profile ${ARGN} "${url}"
                  RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "chromium ${ARGN} ${url} failed (${status}):\n${err}")
  endif()
  set(${var} "${out}" PARENT_SCOPE)
endfunction()

foreach(report fit diag)
  set(dir "${WORK}/${report}")
  file(READ "${dir}/report.html" html)
  file(READ "${dir}/report.md" md)

  # Self-contained: no address, no external style or frame, every image source a data: URI.
  foreach(pattern "http:" "https:" "file://" "src=\"file" "<link" "<iframe" "<object" "<embed" "<base" "url("
                  "@import" "<script")
    string(FIND "${html}" "${pattern}" at)
    if(NOT at EQUAL -1)
      message(SEND_ERROR "${report}/report.html has `${pattern}`")
    endif()
  endforeach()
  count_matches(sources "src=\"" "${html}")
  count_matches(data_sources "src=\"data:image/[a-z+]+.base64," "${html}")
  if(NOT sources EQUAL data_sources)
    message(SEND_ERROR "${report}/report.html: ${sources} sources, only ${data_sources} of them data: URIs")
  endif()

  # The Markdown's content, block for block: headings, tables, figures.
  count_matches(md_headings "\n#+ " "\n${md}")
  count_matches(md_tables "\n\\|---" "${md}")
  count_matches(md_figures "\n!\\[" "\n${md}")
  count_matches(headings "<h[1-4]>" "${html}")
  count_matches(tables "<table>" "${html}")
  count_matches(figures "<figure><img " "${html}")
  if(NOT headings EQUAL md_headings OR NOT tables EQUAL md_tables OR NOT figures EQUAL md_figures)
    message(SEND_ERROR "${report}: report.md has ${md_headings} headings, ${md_tables} tables, ${md_figures} figures; "
                       "report.html ${headings}, ${tables}, ${figures} drawn")
  endif()
  if(md_figures LESS 4 OR md_tables LESS 2)
    message(SEND_ERROR "${report}: expected at least 4 figures and 2 tables, got ${md_figures} and ${md_tables}")
  endif()

  # Every user string escaped: the names (and in the fit, the unit) appear as text.
  string(FIND "${html}" "${evil_html}" at)
  if(at EQUAL -1)
    message(SEND_ERROR "${report}/report.html does not show the file names escaped as `${evil_html}`")
  endif()
  if(report STREQUAL "fit")
    string(FIND "${html}" "<td>${unit_html}</td>" at)
    if(at EQUAL -1)
      message(SEND_ERROR "fit/report.html does not show the unit escaped in its cell")
    endif()
  endif()

  # The browser's DOM of the report as written (its Content-Security-Policy in force): the tables are tables, and
  # no hostile string became an element (the DOM serializer writes text's `<` as `&lt;`).
  string(REPLACE " " "%20" url "file://${dir}/report.html")
  chromium(dom "${url}" --dump-dom)
  count_matches(dom_tables "<table>" "${dom}")
  count_matches(dom_images "<img " "${dom}")
  count_matches(dom_scripts "<script" "${dom}")
  if(NOT dom_tables EQUAL tables OR NOT dom_images EQUAL figures OR NOT dom_scripts EQUAL 0)
    message(SEND_ERROR "${report}: the browser's DOM has ${dom_tables} tables (of ${tables}), ${dom_images} images "
                       "(of ${figures}), ${dom_scripts} script elements (expected none)")
  endif()
  string(FIND "${dom}" "evil &lt;script&gt;alert(" at)
  if(at EQUAL -1)
    message(SEND_ERROR "${report}: the hostile file name is not text in the browser's DOM")
  endif()

  # Rendering: a copy with a probe appended (and the policy, which would block the probe, removed) counts on load
  # the images that decoded to a non-zero size and the resources the page requested.
  string(REGEX REPLACE "<meta http-equiv=\"Content-Security-Policy\"[^>]*>\n" "" probe "${html}")
  string(REPLACE "</body>" "<script>
window.addEventListener('load', function () {
  var images = document.images, drawn = 0;
  for (var i = 0; i < images.length; ++i)
    if (images[i].complete && images[i].naturalWidth > 0 && images[i].naturalHeight > 0) ++drawn;
  var out = document.createElement('pre');
  out.id = 'mbgen-probe';
  out.textContent = 'images ' + images.length + ' drawn ' + drawn + ' requests ' +
    performance.getEntriesByType('resource').length + ' tables ' + document.getElementsByTagName('table').length;
  document.body.appendChild(out);
});
</script>
</body>" probe "${probe}")
  file(WRITE "${WORK}/${report}_probe.html" "${probe}")  # beside the report, which stays as mbgen wrote it
  string(REPLACE " " "%20" url "file://${WORK}/${report}_probe.html")
  chromium(dom "${url}" --virtual-time-budget=10000 --dump-dom)
  if(NOT dom MATCHES "<pre id=\"mbgen-probe\">images ([0-9]+) drawn ([0-9]+) requests ([0-9]+) tables ([0-9]+)</pre>")
    message(SEND_ERROR "${report}: the probe did not report (the page did not finish loading?)")
  elseif(NOT CMAKE_MATCH_1 EQUAL figures OR NOT CMAKE_MATCH_2 EQUAL figures OR NOT CMAKE_MATCH_3 EQUAL 0
         OR NOT CMAKE_MATCH_4 EQUAL tables)
    message(SEND_ERROR "${report}: in the browser ${CMAKE_MATCH_2} of ${CMAKE_MATCH_1} images drawn (expected "
                       "${figures}), ${CMAKE_MATCH_3} requests (expected 0), ${CMAKE_MATCH_4} tables "
                       "(expected ${tables})")
  endif()

  # A screenshot for a human look (the test asserts only that the page rendered to a picture).
  string(REPLACE " " "%20" url "file://${dir}/report.html")
  chromium(ignored "${url}" --hide-scrollbars --window-size=1100,2400 --screenshot=${WORK}/${report}.png)
  file(SIZE "${WORK}/${report}.png" png_size)
  if(png_size LESS 20000)
    message(SEND_ERROR "${report}: the screenshot is ${png_size} bytes: nothing rendered?")
  endif()
  message(STATUS "${report}: ${headings} headings, ${tables} tables, ${figures} plots drawn; "
                 "screenshot ${WORK}/${report}.png")
endforeach()
