// Stanford PLY, ascii and binary (little and big endian): the `vertex` element's x, y, z
// and the `face` element's vertex_indices (or vertex_index) list; other elements and
// properties are read past.
#include <bit>
#include <cmath>
#include <cstring>
#include <memory>
#include <sstream>

#include "fairshape/io/mesh_io.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape {
namespace {

std::string format_value(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

using io::internal::TextScanner;

enum class PlyType { I8, U8, I16, U16, I32, U32, F32, F64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::F32;
  bool is_list = false;
  PlyType count_type = PlyType::U8;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

std::size_t type_size(PlyType t) {
  static constexpr std::size_t sizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return sizes[static_cast<int>(t)];
}

PlyType parse_type(const TextScanner& s, std::string_view name) {
  static const std::pair<const char*, PlyType> table[] = {
      {"char", PlyType::I8},    {"int8", PlyType::I8},     {"uchar", PlyType::U8},
      {"uint8", PlyType::U8},   {"short", PlyType::I16},   {"int16", PlyType::I16},
      {"ushort", PlyType::U16}, {"uint16", PlyType::U16},  {"int", PlyType::I32},
      {"int32", PlyType::I32},  {"uint", PlyType::U32},    {"uint32", PlyType::U32},
      {"float", PlyType::F32},  {"float32", PlyType::F32}, {"double", PlyType::F64},
      {"float64", PlyType::F64}};
  for (const auto& [n, t] : table)
    if (name == n) return t;
  s.fail("unknown PLY property type '" + std::string(name.substr(0, 20)) + "'");
}

// Where property values come from: ascii tokens or binary bytes.
class ValueSource {
 public:
  virtual ~ValueSource() = default;
  virtual double next(PlyType t) = 0;
  virtual std::size_t remaining() const = 0;
  virtual std::size_t min_bytes(PlyType t) const = 0;
  [[noreturn]] virtual void fail(const std::string& problem) const = 0;
};

class AsciiSource : public ValueSource {
 public:
  explicit AsciiSource(TextScanner& s) : s_(s) {}
  double next(PlyType t) override {
    while (k_ >= s_.tokens().size()) {
      if (!s_.next_line()) s_.fail("file ends in the middle of the data");
      k_ = 0;
    }
    const std::string_view tok = s_.tokens()[k_++];
    return t == PlyType::F32 || t == PlyType::F64 ? s_.to_double(tok, "a property value")
                                                  : static_cast<double>(s_.to_integer(tok, "an integer property"));
  }
  // Bytes after this line plus the tokens still unread on it (each at least 2 bytes).
  std::size_t remaining() const override {
    return s_.remaining_bytes() + 2 * (s_.tokens().size() - std::min(k_, s_.tokens().size()));
  }
  std::size_t min_bytes(PlyType) const override { return 2; }
  void fail(const std::string& p) const override { s_.fail(p); }

 private:
  TextScanner& s_;
  std::size_t k_ = 0;
};

class BinarySource : public ValueSource {
 public:
  BinarySource(std::string_view bytes, bool big_endian, std::string file)
      : b_(bytes), swap_(big_endian != (std::endian::native == std::endian::big)), file_(std::move(file)) {}
  double next(PlyType t) override {
    const std::size_t n = type_size(t);
    if (pos_ + n > b_.size()) fail("file ends in the middle of the binary data");
    unsigned char raw[8];
    std::memcpy(raw, b_.data() + pos_, n);
    pos_ += n;
    if (swap_) std::reverse(raw, raw + n);
    switch (t) {
      case PlyType::I8: return static_cast<double>(static_cast<std::int8_t>(raw[0]));
      case PlyType::U8: return raw[0];
      case PlyType::I16: return load<std::int16_t>(raw);
      case PlyType::U16: return load<std::uint16_t>(raw);
      case PlyType::I32: return load<std::int32_t>(raw);
      case PlyType::U32: return load<std::uint32_t>(raw);
      case PlyType::F32: return load<float>(raw);
      case PlyType::F64: return load<double>(raw);
    }
    return 0;
  }
  std::size_t remaining() const override { return b_.size() - pos_; }
  std::size_t min_bytes(PlyType t) const override { return type_size(t); }
  void fail(const std::string& p) const override {
    throw ParseError(file_, 0, "byte " + std::to_string(pos_) + " of the data: " + p);
  }

 private:
  template <class T>
  static double load(const unsigned char* raw) {
    T v;
    std::memcpy(&v, raw, sizeof(T));
    return static_cast<double>(v);
  }
  std::string_view b_;
  std::size_t pos_ = 0;
  bool swap_;
  std::string file_;
};

std::size_t min_element_bytes(const PlyElement& e, const ValueSource& src) {
  std::size_t n = 0;
  for (const auto& p : e.properties) n += src.min_bytes(p.is_list ? p.count_type : p.type);
  return std::max<std::size_t>(n, 1);
}

std::vector<PlyElement> parse_header(TextScanner& s, std::string* format) {
  if (!s.next_line() || s.tokens()[0] != "ply") s.fail("not a PLY file (first line must be 'ply')");
  std::vector<PlyElement> elements;
  while (true) {
    if (!s.next_line()) s.fail("header has no 'end_header'");
    const auto& t = s.tokens();
    if (t[0] == "end_header") break;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() < 2) s.fail("format line needs a format name");
      *format = std::string(t[1]);
      if (*format != "ascii" && *format != "binary_little_endian" && *format != "binary_big_endian")
        s.fail("unknown PLY format '" + *format + "' (valid: ascii, binary_little_endian, binary_big_endian)");
    } else if (t[0] == "element") {
      if (t.size() != 3) s.fail("element line must be 'element NAME COUNT'");
      const long long n = s.to_integer(t[2], "an element count");
      if (n < 0 || n > INT32_MAX) s.fail("element count " + std::to_string(n) + " out of range");
      elements.push_back({std::string(t[1]), n, {}});
    } else if (t[0] == "property") {
      if (elements.empty()) s.fail("property before any element");
      PlyProperty p;
      if (t.size() == 5 && t[1] == "list") {
        p.is_list = true;
        p.count_type = parse_type(s, t[2]);
        p.type = parse_type(s, t[3]);
        p.name = t[4];
      } else if (t.size() == 3) {
        p.type = parse_type(s, t[1]);
        p.name = t[2];
      } else {
        s.fail("property line must be 'property TYPE NAME' or 'property list CTYPE TYPE NAME'");
      }
      elements.back().properties.push_back(p);
    } else {
      s.fail("unknown header keyword '" + std::string(t[0].substr(0, 20)) + "'");
    }
  }
  if (format->empty()) s.fail("header has no 'format' line");
  return elements;
}

void read_body(const std::vector<PlyElement>& elements, ValueSource& src, MeshFile& out) {
  std::vector<double> coords;
  for (const auto& e : elements) {
    if (static_cast<std::size_t>(e.count) > src.remaining() / min_element_bytes(e, src) + 1)
      src.fail("element '" + e.name + "' declares " + std::to_string(e.count) +
               " items but the remaining data is too short (truncated file or wrong count)");
    int xyz[3] = {-1, -1, -1};
    int face_list = -1;
    for (std::size_t k = 0; k < e.properties.size(); ++k) {
      const auto& p = e.properties[k];
      if (!p.is_list && (p.name == "x" || p.name == "y" || p.name == "z")) xyz[p.name[0] - 'x'] = static_cast<int>(k);
      if (p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index")) face_list = static_cast<int>(k);
    }
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0))
      src.fail("element 'vertex' lacks an x, y or z property");
    if (is_face && face_list < 0) src.fail("element 'face' lacks a 'vertex_indices' list");
    for (long long i = 0; i < e.count; ++i) {
      double pos[3] = {0, 0, 0};
      for (std::size_t k = 0; k < e.properties.size(); ++k) {
        const auto& p = e.properties[k];
        if (!p.is_list) {
          const double v = src.next(p.type);
          for (int c = 0; c < 3; ++c)
            if (is_vertex && xyz[c] == static_cast<int>(k)) pos[c] = v;
          continue;
        }
        // Counts and indices may be stored as floats: only whole, finite values mean anything
        // (a NaN or 3.7 would be undefined or silently truncated as an integer).
        const double n = src.next(p.count_type);
        if (!std::isfinite(n) || n != std::floor(n)) src.fail("list length " + format_value(n) + " is not a whole number");
        if (n < 0 || n > static_cast<double>(src.remaining()) / src.min_bytes(p.type) + 1)
          src.fail("list length " + format_value(n) + " is impossible");
        std::vector<int> ids(static_cast<std::size_t>(n));
        for (auto& id : ids) {
          const double v = src.next(p.type);
          if (!std::isfinite(v) || v != std::floor(v)) src.fail("vertex index " + format_value(v) + " is not a whole number");
          id = v >= 0 && v <= INT32_MAX ? static_cast<int>(v) : -1;
        }
        if (is_face && face_list == static_cast<int>(k)) out.faces.push_back(std::move(ids));
      }
      if (is_vertex) coords.insert(coords.end(), pos, pos + 3);
    }
  }
  out.vertices = Eigen::Map<const MatrixX3>(coords.data(), static_cast<Eigen::Index>(coords.size() / 3), 3);
  const int nv = static_cast<int>(out.vertices.rows());
  for (std::size_t f = 0; f < out.faces.size(); ++f)
    for (int id : out.faces[f])
      if (id < 0 || id >= nv)
        src.fail("face " + std::to_string(f) + " references vertex " + std::to_string(id) +
                 ", out of range [0, " + std::to_string(nv) + ")");
}

// The newline ending the header's `end_header` line (npos: none). A comment that mentions
// end_header is not the end of the header.
std::size_t header_end(std::string_view bytes) {
  for (std::size_t pos = 0; pos < bytes.size();) {
    const std::size_t nl = bytes.find('\n', pos);
    std::string_view line = bytes.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line == "end_header") return nl;
    if (nl == std::string_view::npos) break;
    pos = nl + 1;
  }
  return std::string_view::npos;
}

}  // namespace

MeshFile parse_ply(std::string_view bytes, const std::string& name) {
  const std::size_t nl = header_end(bytes);
  TextScanner header(bytes.substr(0, nl == std::string_view::npos ? bytes.size() : nl + 1), name);
  std::string format;
  const auto elements = parse_header(header, &format);
  MeshFile out;
  const std::string_view body = bytes.substr(nl + 1);
  std::unique_ptr<ValueSource> src;
  std::unique_ptr<TextScanner> ascii;
  if (format == "ascii") {
    ascii = std::make_unique<TextScanner>(body, name, header.line() + 1);
    src = std::make_unique<AsciiSource>(*ascii);
  } else {
    src = std::make_unique<BinarySource>(body, format == "binary_big_endian", name);
  }
  read_body(elements, *src, out);
  return out;
}

}  // namespace fairshape
