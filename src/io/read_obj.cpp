// Wavefront OBJ: v, f (v, v/vt, v//vn, v/vt/vn, negative = relative), l; vt/vn/g/o/s/usemtl/mtllib
// are accepted and not needed; any other statement is skipped with a warning.
#include <map>

#include "io/mesh_io.h"
#include "io/text_scanner.h"

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
    } else {
      ++skipped[std::string(kw.substr(0, 32))];
    }
  }
  for (const auto& [kw, n] : skipped)
    out.warnings.push_back(name + ": skipped " + std::to_string(n) + " unsupported '" + kw + "' statement(s)");
  out.vertices = Eigen::Map<const MatrixX3>(coords.data(), static_cast<Eigen::Index>(coords.size() / 3), 3);
  return out;
}

}  // namespace fairshape
