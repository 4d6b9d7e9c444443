// A report directory's two renderings of one document: report.md and report.html, after the plots are drawn.
#include "mbgen/report/gnuplot.hpp"
#include "mbgen/report/report_document.hpp"
#include "mbgen/report/report_files.hpp"
#include "text/utf8.hpp"

#include <filesystem>

namespace mbgen::report {

void write_report(const std::string& dir, Document doc, const std::vector<std::string>& plot_stems) {
  const std::string note = render_gnuplot(dir, plot_stems);
  if (!note.empty()) doc.paragraph(note);
  const std::filesystem::path root(dir);
  // Both declare UTF-8; a user's string may not be (text/utf8.hpp).
  write_report_file((root / "report.md").string(), valid_utf8(to_markdown(doc)));
  // After the plots: the HTML embeds the files gnuplot wrote.
  write_report_file((root / "report.html").string(), valid_utf8(to_html(doc, dir)));
}

}  // namespace mbgen::report
