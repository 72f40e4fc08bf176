// A minimal XML reader: elements, attributes and character data of one document held in memory
// (comments, declarations and DOCTYPE skipped, CDATA rejected), with errors that name the file
// and line. Enough for the VTU files packlab and VTK/ParaView write; not a general XML library.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace packlab::io::detail {

struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<std::size_t> children;  // indices into XmlDocument::elements_
  std::size_t start = 0;              // offset of the start tag's '<', for line numbers
  std::size_t content_begin = 0;      // just after the start tag
  std::size_t content_end = 0;        // at the end tag's '<'
  std::size_t end = 0;                // just after the end tag

  const std::string* attribute(std::string_view key) const {
    for (const auto& [k, v] : attributes)
      if (k == key) return &v;
    return nullptr;
  }
};

class XmlDocument {
 public:
  XmlDocument(std::string text, std::filesystem::path path);  // parses; InputError on bad XML

  const XmlElement& root() const { return elements_.front(); }
  const XmlElement& element(std::size_t index) const { return elements_[index]; }
  std::string_view text() const { return text_; }
  std::vector<const XmlElement*> children(const XmlElement& parent, std::string_view name) const;
  // The one child called `name`: nullptr when absent, an error when repeated.
  const XmlElement* child(const XmlElement& parent, std::string_view name) const;
  const XmlElement& required_child(const XmlElement& parent, std::string_view name) const;

  [[noreturn]] void fail_at(std::size_t offset, std::string_view message) const;

 private:
  void parse();
  std::size_t skip_past(std::size_t from, std::string_view terminator, std::string_view what) const;
  std::string read_name(std::size_t& p) const;
  std::size_t read_start_tag(std::size_t lt, std::vector<std::size_t>& open);
  std::string decode_entities(std::string_view raw, std::size_t offset) const;
  void append_code_point(std::string& out, std::string_view entity, std::size_t offset) const;

  std::string text_;
  std::filesystem::path path_;
  std::vector<XmlElement> elements_;
};

// Escapes & < > " for an attribute value or character data.
std::string xml_escape(std::string_view text);

}  // namespace packlab::io::detail
