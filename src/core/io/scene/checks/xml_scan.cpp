// The XML scan (xml_scan.h) over libxml2's SAX2 parser.

#include "xml_scan.h"

#include <libxml/parser.h>
#include <libxml/parserInternals.h>

#include <cstring>
#include <exception>
#include <mutex>
#include <new>

namespace primo::detail {

namespace {

std::string_view view(const xmlChar* text) {
  return text ? std::string_view(reinterpret_cast<const char*>(text)) : std::string_view();
}

// What one parse keeps between libxml2's callbacks. No exception may cross libxml2's C frames:
// a callback that fails keeps the exception and stops the parser, and scan_xml rethrows it.
struct SaxState {
  XmlScan* scan = nullptr;
  const std::function<int(char*, int)>* read = nullptr;
  xmlParserCtxtPtr context = nullptr;
  // Per open element: has its text (pugixml's text()) not begun, is it running, is it over.
  enum Text : uint8_t { kNotYet, kRunning, kOver };
  std::vector<Text> text;
  std::vector<XmlAttribute> attributes;
  std::vector<std::string> names;  // "prefix:local" of elements and attributes, reused
  std::string refusal;             // a rule of the scan itself (entities)
  std::string first_error;         // libxml2's first fatal error
  std::exception_ptr exception;

  void line() { scan->line = context && context->input ? context->input->line : 0; }
  void stop_if_refused() {
    if ((!scan->refusal.empty() || !refusal.empty() || exception) && context)
      xmlStopParser(context);
  }
  // A comment, a processing instruction, a child element or its end ends the text run of the
  // element it is in.
  void boundary() {
    if (!text.empty() && text.back() == kRunning) text.back() = kOver;
  }
};

SaxState& state_of(void* user) { return *static_cast<SaxState*>(user); }

template <typename Body>
void guarded(SaxState& s, Body body) {
  if (s.exception || !s.scan->refusal.empty() || !s.refusal.empty()) return;
  try {
    s.line();
    body();
  } catch (...) {
    s.exception = std::current_exception();
  }
  s.stop_if_refused();
}

void on_start(void* user, const xmlChar* local, const xmlChar* prefix, const xmlChar* /*uri*/,
              int /*namespaces*/, const xmlChar** /*namespace_pairs*/, int count, int /*defaulted*/,
              const xmlChar** values) {
  SaxState& s = state_of(user);
  s.boundary();
  s.text.push_back(SaxState::kNotYet);
  guarded(s, [&] {
    // Names as pugixml gives them: "prefix:local".
    s.names.resize(size_t(count) + 1);
    auto qualified = [&](size_t slot, const xmlChar* p, const xmlChar* l) -> std::string_view {
      if (!p) return view(l);
      s.names[slot].assign(view(p)).append(":").append(view(l));
      return s.names[slot];
    };
    s.attributes.clear();
    for (int a = 0; a < count; ++a) {
      const xmlChar* const* at = values + 5 * a;  // local, prefix, uri, value, end
      XmlAttribute attribute;
      attribute.name = qualified(size_t(a) + 1, at[1], at[0]);
      attribute.local = view(at[0]);
      attribute.uri = view(at[2]);
      attribute.value =
          std::string_view(reinterpret_cast<const char*>(at[3]), size_t(at[4] - at[3]));
      s.attributes.push_back(attribute);
    }
    s.scan->open(qualified(0, prefix, local), s.attributes);
  });
}

void on_end(void* user, const xmlChar*, const xmlChar*, const xmlChar*) {
  SaxState& s = state_of(user);
  if (!s.text.empty()) s.text.pop_back();
  guarded(s, [&] { s.scan->close(); });
  s.boundary();
}

void on_characters(void* user, const xmlChar* chars, int length) {
  SaxState& s = state_of(user);
  if (s.text.empty() || s.text.back() == SaxState::kOver) return;
  std::string_view piece(reinterpret_cast<const char*>(chars), size_t(length));
  if (s.text.back() == SaxState::kNotYet) {
    // pugixml drops character data that is all whitespace: the text begins at the first
    // character that is not (leading whitespace splits no number).
    size_t first = 0;
    while (first < piece.size() && is_xml_space(piece[first])) ++first;
    if (first == piece.size()) return;
    piece.remove_prefix(first);
    s.text.back() = SaxState::kRunning;
  }
  guarded(s, [&] { s.scan->text(piece); });
}

void on_cdata(void* user, const xmlChar* chars, int length) {
  SaxState& s = state_of(user);
  if (s.text.empty()) return;
  if (s.text.back() != SaxState::kNotYet) {
    s.boundary();
    return;
  }
  s.text.back() = SaxState::kOver;  // a CDATA section is the text, whitespace or not
  std::string_view piece(reinterpret_cast<const char*>(chars), size_t(length));
  guarded(s, [&] { s.scan->text(piece); });
}

void on_comment(void* user, const xmlChar*) { state_of(user).boundary(); }
void on_instruction(void* user, const xmlChar*, const xmlChar*) { state_of(user).boundary(); }

// An entity declaration: the only way an XML file can ask a parser to expand text (billion
// laughs, external files). pugixml expands none; this scan refuses them all.
void on_entity(void* user, const xmlChar* name, int, const xmlChar*, const xmlChar*, xmlChar*) {
  SaxState& s = state_of(user);
  if (s.refusal.empty())
    s.refusal = "it declares XML entities ('" + std::string(view(name)) +
                "'), which it may not use; the format has none";
  s.stop_if_refused();
}

void on_error(void* user, xmlErrorPtr error) {
  SaxState& s = state_of(user);
  if (!error || error->level != XML_ERR_FATAL || !s.first_error.empty()) return;
  std::string message = error->message ? error->message : "unknown error";
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  s.first_error = "libxml2, line " + std::to_string(error->line) + ": " + message;
  if (message.rfind("Excessive depth in document", 0) == 0)
    s.first_error = "its XML is nested deeper than " + std::to_string(xmlParserMaxDepth) +
                    " elements (libxml2's limit)";
  else
    s.first_error = "its XML is not well-formed (" + s.first_error + ")";
}

// The reader's bytes; a failure ends the input (libxml2 would print an I/O error itself).
int on_read(void* context, char* buffer, int length) {
  SaxState& s = state_of(context);
  try {
    return std::max((*s.read)(buffer, length), 0);
  } catch (...) {
    if (!s.exception) s.exception = std::current_exception();
    return 0;
  }
}

// libxml2 reports a few errors outside any parser context on its generic channel, stderr by
// default; the core prints nothing.
void on_generic_error(void*, const char*, ...) {}

int on_close(void*) { return 0; }

}  // namespace

std::string scan_xml(const std::function<int(char*, int)>& read, XmlScan& scan) {
  static std::once_flag initialized;
  std::call_once(initialized, [] { xmlInitParser(); });
  SaxState s;
  s.scan = &scan;
  s.read = &read;
  // Only the callbacks below: no tree is built, no entity is resolved or loaded, no external
  // subset is read, and errors reach on_error instead of stderr.
  xmlSAXHandler sax;
  std::memset(&sax, 0, sizeof sax);
  sax.initialized = XML_SAX2_MAGIC;
  sax.startElementNs = on_start;
  sax.endElementNs = on_end;
  sax.characters = on_characters;
  sax.ignorableWhitespace = on_characters;
  sax.cdataBlock = on_cdata;
  sax.comment = on_comment;
  sax.processingInstruction = on_instruction;
  sax.entityDecl = on_entity;
  sax.serror = on_error;
  // A pull parser over a reader: its depth limit holds (libxml2's push parser has none).
  xmlParserCtxtPtr context =
      xmlCreateIOParserCtxt(&sax, &s, on_read, on_close, &s, XML_CHAR_ENCODING_NONE);
  if (!context) throw std::bad_alloc();
  s.context = context;
  xmlCtxtUseOptions(context, XML_PARSE_NONET);
  const xmlGenericErrorFunc generic_error = xmlGenericError;
  void* const generic_error_context = xmlGenericErrorContext;
  xmlSetGenericErrorFunc(nullptr, on_generic_error);
  xmlParseDocument(context);
  xmlSetGenericErrorFunc(generic_error_context, generic_error);
  const bool well_formed = context->wellFormed != 0;
  s.context = nullptr;
  // libxml2 keeps the entities a DTD declares in a document of its own when the handler does
  // not (its "SAX compatibility mode"); the context does not free it.
  if (context->myDoc) xmlFreeDoc(context->myDoc);
  context->myDoc = nullptr;
  xmlFreeParserCtxt(context);
  if (s.exception) std::rethrow_exception(s.exception);
  if (!scan.refusal.empty()) return scan.refusal;
  if (!s.refusal.empty()) return s.refusal;
  if (!well_formed) return s.first_error.empty() ? "its XML is not well-formed" : s.first_error;
  return "";
}

}  // namespace primo::detail
