#include "packlab/io/xml.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <string_view>
#include <system_error>
#include <unordered_set>

#include "packlab/core/error.hpp"
#include "packlab/io/packing_io.hpp"

namespace packlab::io::detail {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

}  // namespace

XmlDocument::XmlDocument(std::string text, std::filesystem::path path)
    : text_(std::move(text)), path_(std::move(path)) {
  parse();
}

std::vector<const XmlElement*> XmlDocument::children(const XmlElement& parent, std::string_view name) const {
  std::vector<const XmlElement*> found;
  for (const std::size_t c : parent.children)
    if (elements_[c].name == name) found.push_back(&elements_[c]);
  return found;
}

const XmlElement* XmlDocument::child(const XmlElement& parent, std::string_view name) const {
  const auto found = children(parent, name);
  if (found.size() > 1) fail_at(found[1]->start, fmt::format("second <{}> inside <{}>", name, parent.name));
  return found.empty() ? nullptr : found.front();
}

const XmlElement& XmlDocument::required_child(const XmlElement& parent, std::string_view name) const {
  const XmlElement* found = child(parent, name);
  if (!found) fail_at(parent.start, fmt::format("<{}> has no <{}> element", parent.name, name));
  return *found;
}

void XmlDocument::fail_at(std::size_t offset, std::string_view message) const {
  const auto line =
      1 + std::count(text_.begin(),
                     text_.begin() + static_cast<std::ptrdiff_t>(std::min(offset, text_.size())), '\n');
  fail_input(fmt::format("{}:{}: {}", path_.string(), line, message));
}

void XmlDocument::parse() {
  std::size_t pos = text_.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // UTF-8 byte order mark
  std::vector<std::size_t> open;
  bool root_closed = false;
  while (true) {
    const std::size_t lt = text_.find('<', pos);
    const std::size_t text_end = lt == std::string::npos ? text_.size() : lt;
    if (open.empty() && !trim(std::string_view(text_).substr(pos, text_end - pos)).empty())
      fail_at(pos, "text outside the root element: not an XML file?");
    if (lt == std::string::npos) break;
    const std::string_view rest = std::string_view(text_).substr(lt);
    if (rest.starts_with("<!--")) {
      pos = skip_past(lt + 4, "-->", "comment");
    } else if (rest.starts_with("<?")) {
      pos = skip_past(lt + 2, "?>", "declaration");
    } else if (rest.starts_with("<![CDATA[")) {
      fail_at(lt, "CDATA sections are not supported");
    } else if (rest.starts_with("<!")) {
      pos = skip_past(lt + 2, ">", "declaration");
    } else if (rest.starts_with("</")) {
      std::size_t p = lt + 2;
      const std::string name = read_name(p);
      while (p < text_.size() && is_space(text_[p])) ++p;
      if (p >= text_.size() || text_[p] != '>')
        fail_at(lt, fmt::format("end tag </{}> is not closed with '>'", name));
      if (open.empty()) fail_at(lt, fmt::format("end tag </{}> without a start tag", name));
      XmlElement& element = elements_[open.back()];
      if (element.name != name)
        fail_at(lt, fmt::format("end tag </{}> does not match <{}>", name, element.name));
      element.content_end = lt;
      element.end = p + 1;
      open.pop_back();
      if (open.empty()) root_closed = true;
      pos = p + 1;
    } else {
      if (root_closed) fail_at(lt, "a second root element");
      pos = read_start_tag(lt, open);
    }
  }
  if (!open.empty())
    fail_at(text_.size(),
            fmt::format("file ends inside <{}> (truncated file?)", elements_[open.back()].name));
  if (elements_.empty()) fail_at(text_.size(), "no XML element: not a VTU file");
}

std::size_t XmlDocument::skip_past(std::size_t from, std::string_view terminator, std::string_view what) const {
  const std::size_t end = text_.find(terminator, from);
  if (end == std::string::npos) fail_at(from, fmt::format("{} is not closed (truncated file?)", what));
  return end + terminator.size();
}

std::string XmlDocument::read_name(std::size_t& p) const {
  const std::size_t begin = p;
  while (p < text_.size() && !is_space(text_[p]) && text_[p] != '>' && text_[p] != '/' && text_[p] != '=' &&
         text_[p] != '<' && text_[p] != '"' && text_[p] != '\'')
    ++p;
  if (p == begin) fail_at(begin, "expected a name in a tag");
  return text_.substr(begin, p - begin);
}

std::size_t XmlDocument::read_start_tag(std::size_t lt, std::vector<std::size_t>& open) {
  std::size_t p = lt + 1;
  XmlElement element;
  element.start = lt;
  element.name = read_name(p);
  bool self_closing = false;
  // The keys seen so far, as views into text_ (which never changes), so that the check for a
  // repeated attribute stays linear in the number of attributes.
  std::unordered_set<std::string_view> keys;
  while (true) {
    while (p < text_.size() && is_space(text_[p])) ++p;
    if (p >= text_.size())
      fail_at(lt, fmt::format("tag <{}> is not closed (truncated file?)", element.name));
    if (text_[p] == '>') {
      ++p;
      break;
    }
    if (text_.compare(p, 2, "/>") == 0) {
      p += 2;
      self_closing = true;
      break;
    }
    const std::size_t key_begin = p;
    std::string key = read_name(p);
    const std::string_view key_in_text = std::string_view(text_).substr(key_begin, p - key_begin);
    while (p < text_.size() && is_space(text_[p])) ++p;
    if (p >= text_.size() || text_[p] != '=') fail_at(p, fmt::format("attribute {} has no '=value'", key));
    ++p;
    while (p < text_.size() && is_space(text_[p])) ++p;
    if (p >= text_.size() || (text_[p] != '"' && text_[p] != '\''))
      fail_at(p, fmt::format("value of attribute {} is not quoted", key));
    const std::size_t close = text_.find(text_[p], p + 1);
    if (close == std::string::npos) fail_at(p, fmt::format("value of attribute {} is not closed", key));
    const std::string_view raw = std::string_view(text_).substr(p + 1, close - p - 1);
    if (raw.find('<') != std::string_view::npos)
      fail_at(p, fmt::format("'<' in the value of attribute {}", key));
    if (!keys.insert(key_in_text).second) fail_at(p, fmt::format("attribute {} appears twice", key));
    element.attributes.emplace_back(std::move(key), decode_entities(raw, p));
    p = close + 1;
  }
  element.content_begin = element.content_end = p;
  if (self_closing) element.end = p;
  const std::size_t index = elements_.size();
  if (!open.empty()) elements_[open.back()].children.push_back(index);
  elements_.push_back(std::move(element));
  if (!self_closing) open.push_back(index);
  return p;
}

std::string XmlDocument::decode_entities(std::string_view raw, std::size_t offset) const {
  std::string out;
  std::size_t k = 0;
  while (k < raw.size()) {
    if (raw[k] != '&') {
      out += raw[k++];
      continue;
    }
    const std::size_t semicolon = raw.find(';', k);
    if (semicolon == std::string_view::npos) fail_at(offset, "'&' without ';' in an attribute value");
    const std::string_view entity = raw.substr(k + 1, semicolon - k - 1);
    if (entity == "amp")
      out += '&';
    else if (entity == "lt")
      out += '<';
    else if (entity == "gt")
      out += '>';
    else if (entity == "quot")
      out += '"';
    else if (entity == "apos")
      out += '\'';
    else if (entity.starts_with('#'))
      append_code_point(out, entity, offset);
    else
      fail_at(offset, fmt::format("unknown entity &{};", entity));
    k = semicolon + 1;
  }
  return out;
}

void XmlDocument::append_code_point(std::string& out, std::string_view entity, std::size_t offset) const {
  const bool hex = entity.size() > 1 && (entity[1] == 'x' || entity[1] == 'X');
  const std::string_view digits = entity.substr(hex ? 2 : 1);
  unsigned long code = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), code, hex ? 16 : 10);
  if (digits.empty() || ec != std::errc() || ptr != digits.data() + digits.size() || code == 0 ||
      code > 0x10FFFF)
    fail_at(offset, fmt::format("bad character reference &{};", entity));
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

std::string xml_escape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace packlab::io::detail
