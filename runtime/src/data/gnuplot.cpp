#include "mbgen/gnuplot.hpp"

#include <cstdlib>

namespace mbgen {

bool gnuplot_available() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

std::string render_gnuplot(const std::string& dir, const std::vector<std::string>& stems) {
  const bool available = gnuplot_available();
  bool rendered = available;
  for (std::size_t i = 0; available && i < stems.size(); ++i) {
    const std::string cmd = "cd '" + dir + "' && gnuplot '" + stems[i] + ".gp' > /dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0) rendered = false;
  }
  if (rendered) return "";
  return std::string("**The plots were not rendered** (") + (available ? "gnuplot failed" : "gnuplot is not installed") +
         "): run `gnuplot NAME.gp` in this directory to draw them from the .dat files.\n";
}

}  // namespace mbgen
