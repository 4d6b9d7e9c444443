// The version mbgen reports: the project's one version string (CMake's project(VERSION)), which the emitter also
// writes into generated files.
#pragma once

#include <string>

#include "emit/cpp_emitter.hpp"

namespace mbgen::cli {
inline std::string version_text() { return std::string("mbgen ") + emit::mbgen_version(); }
}  // namespace mbgen::cli
