// write_chain_model N FILE: the chain of N six-coordinate bodies of compiler/symbolic/test_chain_model.hpp, as a
// model file for the build (tests/generated_code/CMakeLists.txt).
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "symbolic/test_chain_model.hpp"

int main(int argc, char** argv) {
  const int n = argc == 3 ? std::atoi(argv[1]) : 0;
  if (n < 1) {
    std::cerr << "usage: write_chain_model N FILE\n";
    return 2;
  }
  std::ofstream out(argv[2]);
  out << mbgen::symbolic::test::chain_model_text(n);
  if (!out) {
    std::cerr << "write_chain_model: cannot write " << argv[2] << "\n";
    return 1;
  }
  return 0;
}
