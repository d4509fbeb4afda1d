#pragma once
// XML read as a stream of what Assimp's XML reader (pugixml) would see, for the checks before
// Assimp (the COLLADA file, a 3MF's model part): libxml2's SAX2 pull parser with its own limits
// in force, no network, no DTD loaded, no entity substituted, no tree built.

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace primo::detail {

// XML's whitespace (its S production).
inline bool is_xml_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// An attribute as Assimp's XML reader (pugixml) names it: "prefix:local" or "local".
struct XmlAttribute {
  std::string_view name;   // as written
  std::string_view local;  // without its prefix
  std::string_view uri;    // its namespace ("" for none)
  std::string_view value;  // with entity and character references replaced
};

// What a scan is told, in document order. Element names are as written ("prefix:local"), as
// pugixml gives them to Assimp.
class XmlScan {
 public:
  virtual ~XmlScan() = default;
  virtual void open(std::string_view name, const std::vector<XmlAttribute>& attributes) = 0;
  // Pieces of the element's text as pugixml's text() gives it to Assimp: its first child that
  // is a CDATA section or character data not all whitespace (leading whitespace left out).
  virtual void text(std::string_view piece) = 0;
  virtual void close() = 0;
  // A rule the file breaks, set by the scan to stop reading ("" while none).
  std::string refusal;
  // The line being read (set by scan_xml before each call), for messages.
  int line = 0;
};

// Reads the XML that `read` returns (it fills the buffer and returns the bytes written, 0 at
// the end; on an error it keeps the reason and returns 0) with libxml2's SAX2 parser: no network,
// no DTD loaded, no entity substituted, none of libxml2's limits lifted (XML_PARSE_HUGE off:
// elements nested deeper than 256, names longer than 50,000 bytes, attribute values over 10 MB).
// Returns "" when the document was read to its end, else the rule that stopped it: the scan's
// refusal, "its XML is nested deeper than 256 elements (libxml2's limit)", "it declares XML
// entities (...)", "its XML is not well-formed (libxml2, line 3: ...)".
std::string scan_xml(const std::function<int(char*, int)>& read, XmlScan& scan);

}  // namespace primo::detail
