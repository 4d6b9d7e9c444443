// Where the tests find the repository and their scratch space: the source and build trees this build was configured
// with (test_paths.cpp, written by CMake from tests/support/test_paths.cpp.in). Functions of the support library
// rather than macros on every test's command line, so that a test's object file does not depend on where the tree
// lies and a compiler cache shares it between clones (scripts/build). Outside any namespace: the tests open several.
#pragma once

const char* mbgen_source_dir();     // the repository's root
const char* mbgen_binary_dir();     // the build tree's root
const char* mbgen_test_data_dir();  // tests/data
