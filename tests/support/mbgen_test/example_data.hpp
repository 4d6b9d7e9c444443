// The examples' measured data sets, read as `mbgen fit --data` reads them. Header-only; *_test.cpp files only.
#pragma once

#include "mbgen_test/files.hpp"

#include "mbgen/data/data_set.hpp"

#include <string>

namespace mbgen::test {

// A data file of the source tree by its relative path, e.g. "examples/mdof2/data/frf_F1.csv".
inline DataSet example_data(const std::string& relative) { return read_data_file(source_path(relative)); }

}  // namespace mbgen::test
