// Plots in reports: each plot is a gnuplot script STEM.gp beside its data STEM.dat, rendered to STEM.svg. The
// scripts stay in the report, so a plot can be redrawn (or restyled) where gnuplot was missing.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mbgen {

// Runs `gnuplot STEM.gp` in `dir` for each stem (directly, not through a shell). Returns an empty string when
// every plot was drawn, else a Markdown paragraph (no final newline) saying why not (gnuplot missing or failing) and how to draw them.
std::string render_gnuplot(const std::string& dir, const std::vector<std::string>& stems);

// `s` as a single-quoted gnuplot string (for titles): quotes doubled, control characters as blanks. Use it with
// `noenhanced`, so that `_` and `^` in names are not read as sub- and superscripts.
std::string gnuplot_string(std::string_view s);

}  // namespace mbgen
