// mbgen: the command line. Placeholder entry point until the pipeline stages land (see compiler/cli/).
#include <iostream>
int main() { std::cerr << "mbgen: not built yet\n"; return 2; }
