#include "fairshape/io/vtk_checks.h"

#include <expat.h>
#include <vtkObject.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>
#include <istream>
#include <streambuf>
#include <string_view>

#include "fairshape/core/error.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape::io::internal {
namespace {

// The largest mesh fairshape reads; absolute, since compressed payloads can be far smaller
// than what they hold.
constexpr unsigned long long kMaxVtkElements = 100'000'000;
// The largest array: the points of that mesh, 3 coordinates each.
constexpr unsigned long long kMaxVtkValues = 3 * kMaxVtkElements;
// VTK allocates one block-sized buffer whatever the blocks hold; its writers use 32 KiB.
constexpr unsigned long long kMaxCompressionBlock = 1ULL << 26;  // 64 MiB
// zlib expands at most 1032:1.
constexpr long double kMaxExpansion = 1032.0L;
// VTK's reader works per component even for an empty array (5e7 components of 0 tuples took
// longer than the fuzzer's 10 s); fairshape writes at most 3 and no mesh array needs 1024.
constexpr unsigned long long kMaxVtkComponents = 1024;

// An istream over bytes already in memory (vtkXMLDataParser reads a stream), without a copy.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(const std::string& s) {
    char* b = const_cast<char*>(s.data());  // read only: std::streambuf has no const form
    setg(b, b, b + s.size());
  }

 protected:
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    const off_type size = egptr() - eback();
    const off_type base = dir == std::ios_base::beg ? 0 : dir == std::ios_base::cur ? gptr() - eback() : size;
    if (base + off < 0 || base + off > size) return pos_type(off_type(-1));
    setg(eback(), eback() + base + off, egptr());
    return pos_type(base + off);
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
    return seekoff(off_type(pos), std::ios_base::beg, which);
  }
};

// VTK's own parser for its files (expat underneath; it stops where <AppendedData>'s raw
// bytes begin), keeping where a syntax error is instead of printing it.
class HeaderParser : public vtkXMLDataParser {
 public:
  static HeaderParser* New();
  vtkTypeMacro(HeaderParser, vtkXMLDataParser)
  long error_line = 0;
  std::string error;

 protected:
  HeaderParser() = default;
  void ReportXmlParseError() override {
    auto* parser = static_cast<XML_Parser>(this->Parser);
    error_line = static_cast<long>(XML_GetCurrentLineNumber(parser));
    error = XML_ErrorString(XML_GetErrorCode(parser));
  }
};
vtkStandardNewMacro(HeaderParser);

// Standard base64 (VTK's encoding of binary data); stops at the first character outside it.
std::string decode_base64(std::string_view text) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned value = 0;
  int bits = 0;
  for (char c : text) {
    const std::size_t k = alphabet.find(c);
    if (k == std::string::npos) break;
    value = (value << 6) | static_cast<unsigned>(k);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((value >> bits) & 0xFF));
    }
  }
  return out;
}

// How the file encodes its binary arrays (attributes of <VTKFile> and <AppendedData>).
struct Encoding {
  bool big_endian = false;
  std::size_t word = 4;  // header_type UInt32 or UInt64
  bool compressed = false;
};

class Checker {
 public:
  Checker(const std::string& bytes, const std::string& path) : bytes_(bytes), path_(path) {}

  void check(vtkXMLDataElement* root, std::vector<std::string>* pieces) {
    if (!root || std::strcmp(root->GetName(), "VTKFile") != 0)
      throw ParseError(path_, 1, std::string("not a VTK XML file (its root element is <") +
                                     (root ? root->GetName() : "") + ">, not <VTKFile>)");
    const char* order = root->GetAttribute("byte_order");
    enc_.big_endian = order && std::string_view(order) == "BigEndian";
    const char* header = root->GetAttribute("header_type");
    enc_.word = header && std::string_view(header) == "UInt64" ? 8 : 4;
    enc_.compressed = root->GetAttribute("compressor") != nullptr;
    appended_ = find_appended(root);
    walk(root, 1, pieces);
  }

 private:
  [[noreturn]] void fail(vtkXMLDataElement* e, const std::string& problem) const {
    throw ParseError(path_, line_of(static_cast<std::size_t>(std::max<vtkTypeInt64>(e->GetXMLByteIndex(), 0))), problem);
  }
  long line_of(std::size_t byte) const {
    return 1 + static_cast<long>(std::count(bytes_.begin(), bytes_.begin() + static_cast<std::ptrdiff_t>(std::min(byte, bytes_.size())), '\n'));
  }
  std::string describe(vtkXMLDataElement* e) const {
    std::string out = "<";
    out.append(e->GetName());
    if (const char* name = e->GetAttribute("Name")) out.append(" Name=\"").append(std::string(name).substr(0, 40)).append("\"");
    return out.append(">");
  }

  // One past the '>' that ends the start tag at `from` (quotes respected: '>' may sit in a value).
  std::size_t end_of_tag(std::size_t from) const {
    char quote = 0;
    for (std::size_t i = from; i < bytes_.size(); ++i) {
      const char c = bytes_[i];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        return i + 1;
      }
    }
    return std::string::npos;
  }

  // Where the appended bytes begin (after the '_' marker), or npos without <AppendedData>.
  std::size_t find_appended(vtkXMLDataElement* root) {
    vtkXMLDataElement* a = root->FindNestedElementWithName("AppendedData");
    if (!a) return std::string::npos;
    const char* encoding = a->GetAttribute("encoding");
    appended_base64_ = !encoding || std::string_view(encoding) != "raw";
    const std::size_t close = end_of_tag(static_cast<std::size_t>(std::max<vtkTypeInt64>(a->GetXMLByteIndex(), 0)));
    const std::size_t marker = close == std::string::npos ? close : bytes_.find('_', close);
    if (marker == std::string::npos) fail(a, "<AppendedData> without its '_' marker");
    return marker + 1;
  }

  // Every NumberOf… attribute is a count up to the largest mesh (VTK allocates for it).
  void check_counts(vtkXMLDataElement* e) const {
    for (int i = 0; i < e->GetNumberOfAttributes(); ++i) {
      const std::string_view name = e->GetAttributeName(i);
      if (name.rfind("NumberOf", 0) != 0) continue;
      (void)count(e, std::string(name).c_str(), 0);
    }
  }
  unsigned long long count(vtkXMLDataElement* e, const char* name, unsigned long long fallback) const {
    const char* raw = e->GetAttribute(name);
    if (!raw) return fallback;
    std::string_view v = raw;
    while (!v.empty() && std::isspace(static_cast<unsigned char>(v.front()))) v.remove_prefix(1);
    while (!v.empty() && std::isspace(static_cast<unsigned char>(v.back()))) v.remove_suffix(1);
    unsigned long long n = 0;
    const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), n);
    if (v.empty() || ec != std::errc() || end != v.data() + v.size() || n > kMaxVtkElements)
      fail(e, std::string(e->GetName()) + " " + name + "=\"" + std::string(raw).substr(0, 24) + "\" is not a count up to " +
                  std::to_string(kMaxVtkElements) + " (the largest mesh fairshape reads)");
    return n;
  }

  // `tuples`: how many tuples the enclosing element gives its arrays.
  void walk(vtkXMLDataElement* e, unsigned long long tuples, std::vector<std::string>* pieces) {
    check_counts(e);
    const std::string_view name = e->GetName();
    if (pieces)
      if (const char* file = e->GetAttribute("file")) pieces->emplace_back(file);
    if (name == "DataArray" || name == "Array") check_array(e, count(e, "NumberOfTuples", tuples));
    for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) {
      vtkXMLDataElement* child = e->GetNestedElement(i);
      const std::string_view c = child->GetName();
      unsigned long long t = tuples;
      if (name == "Piece") {
        const unsigned long long cells = count(e, "NumberOfVerts", 0) + count(e, "NumberOfLines", 0) +
                                         count(e, "NumberOfStrips", 0) + count(e, "NumberOfPolys", 0) +
                                         count(e, "NumberOfCells", 0);
        if (c == "Points" || c == "PointData") t = count(e, "NumberOfPoints", 0);
        else if (c == "CellData") t = cells;
        else if (c == "Verts" || c == "Lines" || c == "Strips" || c == "Polys") t = std::max<unsigned long long>(count(e, ("NumberOf" + std::string(c)).c_str(), 0), 1);
      }
      walk(child, t, pieces);
    }
  }

  void check_array(vtkXMLDataElement* e, unsigned long long tuples) {
    const char* raw = e->GetAttribute("NumberOfComponents");
    const unsigned long long components = count(e, "NumberOfComponents", 1);
    if (raw && components == 0) fail(e, describe(e) + " has NumberOfComponents=\"0\" (an array needs at least 1)");
    // Every value takes at least a byte of the file unless compressed, and compression expands
    // at most kMaxExpansion-fold: an array the file cannot hold is a corrupt header.
    const long double holdable = enc_.compressed ? kMaxExpansion * bytes_.size() + 4096.0L : static_cast<long double>(bytes_.size());
    const unsigned long long values = components * tuples;  // both at most 10^8: no overflow
    if (values > kMaxVtkValues || values > holdable)
      fail(e, describe(e) + ": " + std::to_string(components) + " components x " + std::to_string(tuples) +
                  " tuples is more than " + (values > kMaxVtkValues ? std::to_string(kMaxVtkValues) + " values (the largest array fairshape reads)"
                                                                    : "this " + std::to_string(bytes_.size()) + "-byte file can hold") +
                  " (corrupt file?)");
    if (components > kMaxVtkComponents)
      fail(e, describe(e) + ": " + std::to_string(components) + " components is more than " +
                  std::to_string(kMaxVtkComponents) + " (the most fairshape reads in one array)");
    const char* format = e->GetAttribute("format");
    if (!format) return;
    // VTK reads a format it does not know as appended data (found by fuzz_read_vtp: 2.7 GB
    // from `format="appende`"`): only the three it documents pass.
    if (std::string_view(format) != "ascii" && std::string_view(format) != "binary" && std::string_view(format) != "appended")
      fail(e, describe(e) + ": format=\"" + std::string(format).substr(0, 24) + "\" is not ascii, binary or appended");
    if (std::string_view(format) == "appended") {
      if (appended_ == std::string::npos) fail(e, describe(e) + " is appended data, but the file has no <AppendedData>");
      const char* offset = e->GetAttribute("offset");
      const std::string value = offset ? offset : "";
      if (value.empty() || value.size() > 15 || value.find_first_not_of("0123456789") != std::string::npos)
        fail(e, "appended-data offset '" + value.substr(0, 24) + "' is not a byte offset");
      const std::size_t at = appended_ + std::stoull(value);
      if (at > bytes_.size()) fail(e, "an appended array's header starts past the end of the file (corrupt file?)");
      check_header(e, "an appended", std::string_view(bytes_).substr(at), appended_base64_);
    } else if (std::string_view(format) == "binary") {
      const std::size_t start = static_cast<std::size_t>(std::max<vtkTypeInt64>(e->GetXMLByteIndex(), 0));
      const std::size_t close = end_of_tag(start);
      if (close == std::string::npos || bytes_[close - 2] == '/') return;  // no inline data: VTK reads none
      std::size_t from = close;
      while (from < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[from]))) ++from;
      const std::size_t to = std::min(bytes_.find('<', from), bytes_.size());
      check_header(e, "an inline", std::string_view(bytes_).substr(from, to - from), true);
    }
  }

  // A binary array's header (its byte count, or for compressed data the block count and
  // sizes) must describe bytes that follow it, or VTK allocates what a corrupt header claims
  // (found by fuzz_read_vtp: 2.7 GB from a 3 KB file). `data` runs from the header to the
  // end of what the array may hold; base64 headers are encoded on their own, so they are
  // decoded header by header.
  void check_header(vtkXMLDataElement* e, const std::string& which, std::string_view data, bool base64) const {
    const std::size_t word = enc_.word;
    const auto bad = [&](const std::string& what) { fail(e, which + " array's header " + what + " (" + describe(e) + "; corrupt file?)"); };
    // `count` header words at the start of `data` (base64: the unit holding `total` words).
    const auto words = [&](std::size_t count, std::size_t total) {
      std::string raw;
      if (base64) {
        const std::size_t chars = (total * word + 2) / 3 * 4;
        if (chars > data.size()) bad("lies past the end of the file");
        raw = decode_base64(data.substr(0, chars));
      } else {
        if (count * word > data.size()) bad("lies past the end of the file");
        raw = std::string(data.substr(0, count * word));
      }
      if (raw.size() < count * word) bad("is cut short");
      std::vector<unsigned long long> out(count, 0);
      for (std::size_t k = 0; k < count; ++k)
        for (std::size_t b = 0; b < word; ++b) {  // most significant byte first, in the file's byte order
          const auto byte = static_cast<unsigned char>(raw[k * word + (enc_.big_endian ? b : word - 1 - b)]);
          out[k] = (out[k] << 8) | byte;
        }
      return out;
    };
    // What the file holds after the header, as decoded bytes.
    const long double held = base64 ? data.size() * 0.75L : static_cast<long double>(data.size());
    if (!enc_.compressed) {
      if (words(1, 1)[0] > held) bad("claims more bytes than the file holds");
      return;
    }
    const auto head = words(3, 3);
    const unsigned long long blocks = head[0], block = head[1], last = head[2];
    if (blocks > held / word) bad("claims more compressed blocks than the file holds");
    const auto all = words(3 + static_cast<std::size_t>(blocks), 3 + static_cast<std::size_t>(blocks));
    long double stored = 0;
    for (std::size_t b = 0; b < blocks; ++b) stored += all[3 + b];
    const long double expanded = blocks == 0 ? 0.0L : (blocks - 1.0L) * block + (last ? last : block);
    if (stored > held || expanded > kMaxExpansion * stored + 4096.0L || block > kMaxCompressionBlock)
      bad("is inconsistent with the compressed data that follows");
    // VTK divides by the block size and takes the last block as at most one block (found by
    // fuzz_read_vtp: a zero block size is a division by zero).
    if (blocks > 0 && (block == 0 || last > block)) bad("gives a block size of 0 or a last block larger than a block");
  }

  const std::string& bytes_;
  const std::string& path_;
  Encoding enc_;
  std::size_t appended_ = std::string::npos;
  bool appended_base64_ = true;
};

}  // namespace

std::string checked_vtk_text(const std::string& path, std::vector<std::string>* pieces) {
  // VTK prints its own errors on stderr; fairshape reports every failure itself.
  vtkObject::GlobalWarningDisplayOff();
  std::string text = read_whole_file(path);
  ViewBuffer buffer(text);
  std::istream in(&buffer);
  vtkNew<HeaderParser> parser;
  parser->SetStream(&in);
  parser->SetIgnoreCharacterData(1);  // inline data is found by position, not copied
  if (!parser->Parse())
    throw ParseError(path, parser->error_line,
                     "not a well-formed VTK XML file: " + (parser->error.empty() ? std::string("unreadable XML") : parser->error));
  Checker(text, path).check(parser->GetRootElement(), pieces);
  return text;
}

}  // namespace fairshape::io::internal
