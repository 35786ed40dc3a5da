// Wavefront OBJ: v, f (v, v/vt, v//vn, v/vt/vn, negative = relative), l, and OpenSubdiv's
// `t crease` / `t corner` sharpness tags; vt/vn/g/o/s/usemtl/mtllib are accepted and not
// needed; any other statement (other `t` tags too) is skipped with a warning.
#include <cstdint>
#include <map>

#include "fairshape/io/mesh_io.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape {
namespace {

using io::internal::TextScanner;

// Resolves one index token ("7", "-1", "7/2", "7//3") to a 0-based vertex id.
int resolve_index(const TextScanner& s, std::string_view tok, long long n_vertices) {
  const std::string_view head = tok.substr(0, tok.find('/'));
  const long long i = s.to_integer(head, "a vertex index");
  long long zero_based = i > 0 ? i - 1 : n_vertices + i;  // negative: relative to the end
  if (i == 0 || zero_based < 0 || zero_based >= n_vertices)
    s.fail("vertex index " + std::to_string(i) + " is out of range (" + std::to_string(n_vertices) +
           " vertices defined so far)");
  return static_cast<int>(zero_based);
}

// OpenSubdiv's tag statement "t NAME nint/nfloat/nstring ints... floats... strings...";
// crease (ints in pairs, one float for all pairs or one per pair) and corner (one float for
// all vertices or one per vertex) become sharpness tags; the caller skips any other name.
bool parse_sharpness_tag(const TextScanner& s, std::vector<SharpnessTag>& out) {
  const auto& t = s.tokens();
  if (t.size() < 3 || (t[1] != "crease" && t[1] != "corner")) return false;
  const bool corner = t[1] == "corner";
  const std::string_view counts = t[2];
  const auto slash1 = counts.find('/'), slash2 = counts.find('/', slash1 + 1);
  if (slash1 == std::string_view::npos || slash2 == std::string_view::npos)
    s.fail("a '" + std::string(t[1]) + "' tag needs counts written nint/nfloat/nstring, got '" +
           std::string(counts) + "'");
  const long long ni = s.to_integer(counts.substr(0, slash1), "a tag's integer count");
  const long long nf = s.to_integer(counts.substr(slash1 + 1, slash2 - slash1 - 1), "a tag's float count");
  const long long ns = s.to_integer(counts.substr(slash2 + 1), "a tag's string count");
  const long long per = corner ? 1 : 2, items = ni / per;
  if (ni <= 0 || ni % per != 0 || ns != 0 || !(nf == 1 || nf == items))
    s.fail("a '" + std::string(t[1]) + "' tag needs " + (corner ? "n vertex ids" : "2n vertex ids (edges as pairs)") +
           " and 1 or n sharpness values, got counts " + std::string(counts));
  if (static_cast<long long>(t.size()) != 3 + ni + nf)
    s.fail("a '" + std::string(t[1]) + "' tag with counts " + std::string(counts) + " needs " +
           std::to_string(ni + nf) + " values, got " + std::to_string(t.size() - 3));
  for (long long i = 0; i < items; ++i) {
    SharpnessTag tag;
    tag.corner = corner;
    tag.line = s.line();
    const long long a = s.to_integer(t[3 + per * i], "a tag's vertex id");
    const long long b = corner ? 0 : s.to_integer(t[3 + per * i + 1], "a tag's vertex id");
    if (a < 0 || b < 0 || a > INT32_MAX || b > INT32_MAX) s.fail("tag vertex ids are 0-based and must be >= 0");
    tag.a = static_cast<int>(a);
    tag.b = corner ? -1 : static_cast<int>(b);
    tag.sharpness = s.to_double(t[3 + ni + (nf == 1 ? 0 : i)], "a sharpness value");
    out.push_back(tag);
  }
  return true;
}

}  // namespace

MeshFile parse_obj(std::string_view text, const std::string& name) {
  TextScanner s(text, name);
  std::vector<double> coords;
  MeshFile out;
  std::map<std::string, int> skipped;
  while (s.next_line()) {
    const auto& t = s.tokens();
    const std::string_view kw = t[0];
    if (kw == "v") {
      if (t.size() < 4 || t.size() > 5) s.fail("a vertex needs 3 coordinates (and an optional w)");
      for (int k = 1; k <= 3; ++k) coords.push_back(s.to_double(t[k], "a vertex coordinate"));
    } else if (kw == "f" || kw == "l") {
      const std::size_t min_size = kw == "f" ? 3 : 2;
      if (t.size() - 1 < min_size)
        s.fail(std::string(kw == "f" ? "a face" : "a line") + " needs at least " +
               std::to_string(min_size) + " vertices, got " + std::to_string(t.size() - 1));
      std::vector<int> ids;
      for (std::size_t k = 1; k < t.size(); ++k)
        ids.push_back(resolve_index(s, t[k], static_cast<long long>(coords.size() / 3)));
      (kw == "f" ? out.faces : out.lines).push_back(std::move(ids));
    } else if (kw == "vt" || kw == "vn" || kw == "vp" || kw == "g" || kw == "o" || kw == "s" ||
               kw == "usemtl" || kw == "mtllib") {
      continue;  // attributes and grouping: not part of the geometry fairshape edits
    } else if (kw == "t" && parse_sharpness_tag(s, out.sharpness)) {
      continue;
    } else {
      std::string what(kw.substr(0, 32));
      if (kw == "t" && t.size() > 1) what.append(" ").append(t[1].substr(0, 32));  // name the tag
      ++skipped[what];
    }
  }
  for (const auto& [kw, n] : skipped)
    out.warnings.push_back(name + ": skipped " + std::to_string(n) + " unsupported '" + kw + "' statement(s)");
  out.vertices = Eigen::Map<const MatrixX3>(coords.data(), static_cast<Eigen::Index>(coords.size() / 3), 3);
  return out;
}

}  // namespace fairshape
