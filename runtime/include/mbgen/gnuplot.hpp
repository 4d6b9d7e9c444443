// Plots in reports: each plot is a gnuplot script STEM.gp beside its data STEM.dat, rendered to STEM.svg. The
// scripts stay in the report, so a plot can be redrawn (or restyled) where gnuplot was missing.
#pragma once

#include <string>
#include <vector>

namespace mbgen {

bool gnuplot_available();

// Runs `gnuplot STEM.gp` in `dir` for each stem. Returns an empty string when every plot was drawn, else a
// Markdown note saying why not and how to draw them.
std::string render_gnuplot(const std::string& dir, const std::vector<std::string>& stems);

}  // namespace mbgen
