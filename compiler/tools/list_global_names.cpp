// list_global_names PREPROCESSED.ii: the names a preprocessed C++ translation unit declares at global scope (the C
// library's functions and types: sin, y0, FILE, size_t), as C++ string literals, one per line, sorted. A top-level
// namespace of such a name does not compile ("redeclared as different kind of entity"), so the names the generated
// code's headers declare there are refused for --namespace's first part (compiler/ir/identifier.cpp). Built and run
// during the build (compiler/CMakeLists.txt) on what the compiler building mbgen makes of those headers.
//
// Every identifier outside any braces counts, except names the implementation reserves (a leading `_`): return and
// parameter types, keywords and attribute words come along, which over-refuses only names no one would choose.
// The braces of `extern "C" {` and `extern "C++" {` do not count: declarations inside them are global.
#include <cctype>
#include <fstream>
#include <iostream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: list_global_names PREPROCESSED.ii\n";
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  if (!in) {
    std::cerr << "list_global_names: cannot read " << argv[1] << "\n";
    return 1;
  }
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::set<std::string> names;
  std::vector<bool> opaque;  // per open brace: whether it opens a scope (false: extern "C" {)
  int opaque_depth = 0;
  std::string last_word, last_string;  // the tokens before a `{`: `extern` then a string literal
  bool after_extern_string = false;
  bool line_start = true;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (line_start && c == '#') {  // #pragma lines that -P keeps
      while (i < text.size() && text[i] != '\n') ++i;
      continue;
    }
    line_start = c == '\n';
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t j = i;
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_')) ++j;
      const std::string word = text.substr(i, j - i);
      if (opaque_depth == 0 && word[0] != '_') names.insert(word);
      after_extern_string = false;
      last_word = word;
      i = j;
    } else if (c == '"' || c == '\'') {
      std::size_t j = i + 1;
      while (j < text.size() && text[j] != c) j += text[j] == '\\' ? 2 : 1;
      after_extern_string = c == '"' && last_word == "extern";
      last_word.clear();
      i = j + 1;
    } else if (c == '{') {
      opaque.push_back(!after_extern_string);
      if (opaque.back()) ++opaque_depth;
      after_extern_string = false;
      last_word.clear();
      ++i;
    } else if (c == '}') {
      if (!opaque.empty()) {
        if (opaque.back()) --opaque_depth;
        opaque.pop_back();
      }
      ++i;
    } else {
      if (!std::isspace(static_cast<unsigned char>(c))) after_extern_string = false, last_word.clear();
      ++i;
    }
  }
  std::cout << "// Written by list_global_names: names the generated code's headers declare at global scope.\n";
  for (const std::string& name : names) std::cout << "\"" << name << "\",\n";
  return 0;
}
