#pragma once
// Test helper: a small, strict scanner for the SVG and HTML that io/pictures
// writes (well-formed markup: every element closed, attributes quoted,
// <script>/<style> content raw). No std::regex: it overflows the stack under
// ASan on large inputs.

#include <cstddef>
#include <cstdlib>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace fabmesh::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;  ///< entity references decoded
  std::string text;                               ///< direct text content, decoded
  int parent = -1;                                ///< index in the scan, -1 for the root
  std::string attr(const std::string& key) const {
    const auto it = attributes.find(key);
    return it == attributes.end() ? std::string() : it->second;
  }
  bool has_class(const std::string& c) const {
    const std::string all = " " + attr("class") + " ";
    return all.find(" " + c + " ") != std::string::npos;
  }
};

/// Decodes &amp; &lt; &gt; &quot; &#39; and numeric references (to UTF-8).
inline std::string decode_entities(std::string_view s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    const std::size_t end = s.find(';', i);
    if (end == std::string_view::npos) throw std::runtime_error("xml: unterminated entity");
    const std::string name(s.substr(i + 1, end - i - 1));
    if (name == "amp")
      out += '&';
    else if (name == "lt")
      out += '<';
    else if (name == "gt")
      out += '>';
    else if (name == "quot")
      out += '"';
    else if (name == "apos")
      out += '\'';
    else if (!name.empty() && name[0] == '#') {
      const unsigned long code = name.size() > 1 && name[1] == 'x'
                                     ? std::strtoul(name.c_str() + 2, nullptr, 16)
                                     : std::strtoul(name.c_str() + 1, nullptr, 10);
      if (code < 0x80) {
        out += static_cast<char>(code);
      } else if (code < 0x800) {
        out += static_cast<char>(0xC0 | (code >> 6));
        out += static_cast<char>(0x80 | (code & 0x3F));
      } else {
        out += static_cast<char>(0xE0 | (code >> 12));
        out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (code & 0x3F));
      }
    } else {
      throw std::runtime_error("xml: unknown entity &" + name + ";");
    }
    i = end;
  }
  return out;
}

/// HTML elements that never have content (a browser's serialisation writes them without "/>").
inline bool is_void_html(const std::string& name) {
  for (const char* v :
       {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "wbr"}) {
    if (name == v) return true;
  }
  return false;
}

/// Every element of `doc` in document order. Throws std::runtime_error on
/// malformed markup (unclosed or mismatched tags, a bare '<' or '&'). With
/// `html`, void elements (img, meta, ...) need no "/>".
inline std::vector<XmlElement> scan_xml(std::string_view doc, bool html = false) {
  std::vector<XmlElement> elements;
  std::vector<int> open;
  std::size_t i = 0;
  auto fail = [&](const std::string& what) {
    throw std::runtime_error("xml: " + what + " at offset " + std::to_string(i));
  };
  auto skip_to = [&](std::string_view end) {
    const std::size_t at = doc.find(end, i);
    if (at == std::string_view::npos) fail("unterminated construct");
    i = at + end.size();
  };
  while (i < doc.size()) {
    if (doc[i] != '<') {
      const std::size_t next = std::min(doc.find('<', i), doc.size());
      const std::string text = decode_entities(doc.substr(i, next - i));
      if (!open.empty()) elements[open.back()].text += text;
      i = next;
      continue;
    }
    if (doc.substr(i, 4) == "<!--") {
      skip_to("-->");
    } else if (doc.substr(i, 2) == "<?" || doc.substr(i, 2) == "<!") {
      skip_to(">");
    } else if (doc.substr(i, 2) == "</") {
      const std::size_t end = doc.find('>', i);
      if (end == std::string_view::npos) fail("unterminated end tag");
      const std::string name(doc.substr(i + 2, end - i - 2));
      if (open.empty() || elements[open.back()].name != name) fail("mismatched </" + name + ">");
      open.pop_back();
      i = end + 1;
    } else {
      XmlElement e;
      std::size_t j = i + 1;
      while (j < doc.size() && doc[j] != ' ' && doc[j] != '>' && doc[j] != '/' && doc[j] != '\n') ++j;
      e.name = std::string(doc.substr(i + 1, j - i - 1));
      bool self_closing = false;
      while (true) {
        while (j < doc.size() && (doc[j] == ' ' || doc[j] == '\n' || doc[j] == '\t')) ++j;
        if (j >= doc.size()) fail("unterminated tag");
        if (doc[j] == '>') break;
        if (doc.substr(j, 2) == "/>") {
          self_closing = true;
          ++j;
          break;
        }
        const std::size_t eq = doc.find('=', j);
        if (eq == std::string_view::npos || eq + 1 >= doc.size()) fail("attribute without value");
        const char quote = doc[eq + 1];
        if (quote != '"' && quote != '\'') fail("unquoted attribute");
        const std::size_t close = doc.find(quote, eq + 2);
        if (close == std::string_view::npos) fail("unterminated attribute");
        const std::string key(doc.substr(j, eq - j));
        const std::string_view raw = doc.substr(eq + 2, close - eq - 2);
        if (raw.find('<') != std::string_view::npos) fail("'<' in an attribute value");
        if (e.attributes.count(key)) fail("repeated attribute " + key);
        e.attributes[key] = decode_entities(raw);
        j = close + 1;
      }
      i = j + 1;
      e.parent = open.empty() ? -1 : open.back();
      elements.push_back(std::move(e));
      const int index = static_cast<int>(elements.size()) - 1;
      const std::string& name = elements.back().name;
      if (self_closing || (html && is_void_html(name))) continue;
      if (name == "script" || name == "style") {  // raw text up to the end tag
        const std::size_t end = doc.find("</" + name + ">", i);
        if (end == std::string_view::npos) fail("unterminated " + name);
        elements.back().text = std::string(doc.substr(i, end - i));
        i = end + name.size() + 3;
        continue;
      }
      open.push_back(index);
    }
  }
  if (!open.empty()) throw std::runtime_error("xml: <" + elements[open.back()].name + "> is never closed");
  return elements;
}

/// The elements of `all` with tag `name` (any tag when empty) and class `cls` (any when empty).
inline std::vector<const XmlElement*> select(const std::vector<XmlElement>& all, const std::string& name,
                                             const std::string& cls = "") {
  std::vector<const XmlElement*> out;
  for (const XmlElement& e : all) {
    if ((name.empty() || e.name == name) && (cls.empty() || e.has_class(cls))) out.push_back(&e);
  }
  return out;
}

/// True when element `index` lies inside an element of `all` with class `cls`.
inline bool inside_class(const std::vector<XmlElement>& all, int index, const std::string& cls) {
  for (int p = all[index].parent; p >= 0; p = all[p].parent) {
    if (all[p].has_class(cls)) return true;
  }
  return false;
}

}  // namespace fabmesh::test
