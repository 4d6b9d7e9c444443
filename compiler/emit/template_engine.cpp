#include "emit/template_engine.hpp"

namespace mbgen::emit {
namespace {

struct Renderer {
  const std::string& text;
  const std::string& name;
  std::vector<const TemplateDict*> scopes;  // innermost last

  [[noreturn]] void fail(std::size_t pos, const std::string& what) const {
    int line = 1, col = 1;
    for (std::size_t i = 0; i < pos && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        col = 1;
      } else {
        ++col;
      }
    }
    throw TemplateError(name + ":" + std::to_string(line) + ":" + std::to_string(col) + ": " + what);
  }

  const TemplateValue* lookup(const std::string& key) const {
    for (auto it = scopes.rbegin(); it != scopes.rend(); ++it) {
      auto found = (*it)->find(key);
      if (found != (*it)->end()) return &found->second;
    }
    return nullptr;
  }

  // Renders text[begin, end) into out. Sections are matched by scanning for their closing tag at the same depth.
  void render(std::size_t begin, std::size_t end, std::string& out) {
    std::size_t pos = begin;
    while (pos < end) {
      std::size_t open = text.find("{{", pos);
      if (open == std::string::npos || open >= end) {
        out.append(text, pos, end - pos);
        return;
      }
      out.append(text, pos, open - pos);
      std::size_t close = text.find("}}", open + 2);
      if (close == std::string::npos || close + 2 > end) fail(open, "unterminated '{{'");
      std::string tag = text.substr(open + 2, close - open - 2);
      std::size_t after = close + 2;
      if (tag.empty()) fail(open, "empty placeholder '{{}}'");
      if (tag[0] == '!') {
        pos = after;
        continue;
      }
      if (tag[0] == '/') fail(open, "'{{" + tag + "}}' closes a section that is not open");
      if (tag[0] == '#') {
        std::string key = tag.substr(1);
        std::size_t section_end = find_section_end(key, after, end, open);
        const TemplateValue* v = lookup(key);
        if (!v) fail(open, "unknown list '" + key + "'");
        const auto* list = std::get_if<TemplateList>(&v->value);
        if (!list) fail(open, "'" + key + "' is a string, used as a list");
        for (const TemplateDict& item : *list) {
          scopes.push_back(&item);
          render(after, section_end, out);
          scopes.pop_back();
        }
        pos = section_end + key.size() + 5;  // past "{{/key}}"
        continue;
      }
      const TemplateValue* v = lookup(tag);
      if (!v) fail(open, "unknown placeholder '" + tag + "'");
      const auto* s = std::get_if<std::string>(&v->value);
      if (!s) fail(open, "'" + tag + "' is a list, used as a string");
      out += *s;
      pos = after;
    }
  }

  // Position of the "{{/key}}" that closes a section opened before `from` (nested sections of the same name
  // are counted).
  std::size_t find_section_end(const std::string& key, std::size_t from, std::size_t end, std::size_t open) const {
    const std::string opener = "{{#" + key + "}}", closer = "{{/" + key + "}}";
    int depth = 1;
    std::size_t pos = from;
    while (true) {
      std::size_t next_close = text.find(closer, pos);
      if (next_close == std::string::npos || next_close >= end) fail(open, "section '" + key + "' is not closed");
      std::size_t next_open = text.find(opener, pos);
      if (next_open != std::string::npos && next_open < next_close) {
        ++depth;
        pos = next_open + opener.size();
        continue;
      }
      if (--depth == 0) return next_close;
      pos = next_close + closer.size();
    }
  }
};

}  // namespace

std::string render_template(const std::string& text, const TemplateDict& values, const std::string& template_name) {
  Renderer r{text, template_name, {&values}};
  std::string out;
  out.reserve(text.size() * 2);
  r.render(0, text.size(), out);
  return out;
}

std::string render_embedded(const std::string& name, const TemplateDict& values) {
  return render_template(embedded_template(name), values, name);
}

}  // namespace mbgen::emit
