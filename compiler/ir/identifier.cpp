#include "ir/identifier.hpp"

#include <algorithm>
#include <iterator>

namespace mbgen::ir {

namespace {

bool letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool digit(char c) { return c >= '0' && c <= '9'; }

constexpr std::string_view kReservedNames[] = {"pi", "inf"};
constexpr std::string_view kLanguageWords[] = {"sqrt", "sin", "cos",   "x",        "y",     "z", "rx",
                                               "ry",   "rz",  "known", "estimate", "fixed", "in"};

// Keywords and alternative tokens of C++20, and names with a special meaning before the compiler sees them.
constexpr std::string_view kKeywords[] = {
    "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch", "char",
    "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr", "constinit",
    "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete", "do", "double",
    "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for", "friend", "goto", "if",
    "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq", "nullptr", "operator", "or",
    "or_eq", "private", "protected", "public", "register", "reinterpret_cast", "requires", "return", "short",
    "signed", "sizeof", "static", "static_assert", "static_cast", "struct", "switch", "template", "this",
    "thread_local", "throw", "true", "try", "typedef", "typeid", "typename", "union", "unsigned", "using", "virtual",
    "void", "volatile", "wchar_t", "while", "xor", "xor_eq",
    // Macros: predefined in GNU mode (the default of CMake and GCC), or from headers the generated code includes.
    "linux", "unix", "NULL", "EOF", "errno", "assert"};

// Macros of the headers the generated code includes (<cmath>, <limits>, Eigen, the runtime's), listed when mbgen was
// configured (cmake/HeaderMacros.cmake), sorted: a namespace of such a name is replaced by the preprocessor.
constexpr std::string_view kHeaderMacros[] = {
#include "header_macros.inc"
};

// Names the same headers declare at global scope (the C library's sin, y0, FILE, size_t), listed during the build
// (compiler/tools/list_global_names.cpp), sorted: a top-level namespace of such a name clashes with the declaration.
constexpr std::string_view kGlobalNames[] = {
#include "global_names.inc"
};

// Namespaces the generated code names without a leading `::`: a namespace of the same name inside the model's
// would hide them.
constexpr std::string_view kUsedNamespaces[] = {"std", "Eigen", "mbgen", "mpfr"};

template <std::size_t N>
bool among(std::string_view s, const std::string_view (&list)[N]) {
  for (std::string_view w : list)
    if (s == w) return true;
  return false;
}

}  // namespace

bool is_identifier(std::string_view s) {
  if (s.empty() || !letter(s.front())) return false;
  for (char c : s)
    if (!letter(c) && !digit(c)) return false;
  return true;
}

std::string to_identifier(std::string_view s) {
  std::string out;
  for (char c : s) out += letter(c) || digit(c) ? c : '_';
  if (out.empty() || digit(out.front())) out = "m_" + out;
  return out;
}

bool is_reserved_name(std::string_view s) { return among(s, kReservedNames); }

bool is_language_word(std::string_view s) { return among(s, kLanguageWords); }

std::string cxx_identifier_problem(std::string_view s) {
  const std::string quoted = "`" + std::string(s) + "`";
  if (!is_identifier(s))
    return s.empty() ? "a part of it is empty" : quoted + " is not an identifier (letters, digits and _)";
  if (among(s, kKeywords)) return quoted + " is a C++ keyword or a predefined macro";
  if (std::binary_search(std::begin(kHeaderMacros), std::end(kHeaderMacros), s))
    return quoted + " is a macro of the headers the generated code includes (<cmath>, <limits>, Eigen)";
  if (s.rfind("MBGEN_", 0) == 0 || s.rfind("EIGEN_", 0) == 0)
    return quoted + " could be a macro: names starting with MBGEN_ or EIGEN_ are reserved for mbgen's and Eigen's";
  if (s.size() > 2 && s.substr(s.size() - 2) == "_t")
    return quoted + " could be a type of the C library: names ending in _t are reserved for types (POSIX; size_t)";
  if (among(s, kUsedNamespaces))
    return quoted + " would hide the namespace " + quoted + " that the generated code uses";
  const bool underscore_capital = s.size() > 1 && s[0] == '_' && s[1] >= 'A' && s[1] <= 'Z';
  if (s.find("__") != std::string_view::npos || underscore_capital)
    return quoted + " is reserved for the C++ implementation (`__`, or `_` and a capital letter)";
  return "";
}

std::string cxx_top_namespace_problem(std::string_view s) {
  if (std::string problem = cxx_identifier_problem(s); !problem.empty()) return problem;
  if (std::binary_search(std::begin(kGlobalNames), std::end(kGlobalNames), s))
    return "`" + std::string(s) + "` is declared at global scope by the headers the generated code includes (a C "
           "library function or type): a top-level namespace of that name clashes with it";
  return "";
}

std::string cxx_parameter_variable(std::string_view name) { return "p_" + to_identifier(name); }

}  // namespace mbgen::ir
