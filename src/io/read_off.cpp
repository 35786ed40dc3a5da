// Object File Format: "OFF" (or COFF / NOFF / CNOFF: per-vertex colours or normals after the
// coordinates, ignored), counts "nv nf ne", vertices, then faces "k i0 .. i(k-1) [colour]".
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape {

MeshFile parse_off(std::string_view text, const std::string& name) {
  io::internal::TextScanner s(text, name);
  if (!s.next_line()) s.fail("empty file (expected an 'OFF' header)");
  std::vector<std::string_view> head = s.tokens();
  const std::string_view magic = head[0];
  if (magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF")
    s.fail("not an OFF file: first keyword is '" + std::string(magic.substr(0, 16)) + "', expected OFF");
  head.erase(head.begin());
  if (head.empty()) {  // counts on their own line
    if (!s.next_line()) s.fail("missing the vertex/face/edge counts line");
    head = s.tokens();
  }
  if (head.size() < 2) s.fail("expected 'vertices faces [edges]' counts");
  const long long nv = s.to_count(head[0], "the vertex count", 6);
  const long long nf = s.to_count(head[1], "the face count", 8);
  if (nv > INT32_MAX || nf > INT32_MAX) s.fail("counts exceed 2^31");

  MeshFile out;
  out.vertices.resize(nv, 3);
  for (long long v = 0; v < nv; ++v) {
    if (!s.next_line())
      s.fail("file ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    const auto& t = s.tokens();
    if (t.size() < 3) s.fail("vertex " + std::to_string(v) + " needs 3 coordinates");
    for (int k = 0; k < 3; ++k) out.vertices(v, k) = s.to_double(t[k], "a vertex coordinate");
  }
  out.faces.reserve(nf);
  for (long long f = 0; f < nf; ++f) {
    if (!s.next_line())
      s.fail("file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const auto& t = s.tokens();
    const long long k = s.to_integer(t[0], "the face size");
    if (k < 3) s.fail("face " + std::to_string(f) + " has " + std::to_string(k) + " vertices (need at least 3)");
    if (static_cast<long long>(t.size()) - 1 < k)
      s.fail("face " + std::to_string(f) + " declares " + std::to_string(k) + " vertices but lists " +
             std::to_string(t.size() - 1));
    std::vector<int> ids(k);
    for (long long i = 0; i < k; ++i) {
      const long long id = s.to_integer(t[i + 1], "a vertex index");
      if (id < 0 || id >= nv)
        s.fail("face " + std::to_string(f) + " references vertex " + std::to_string(id) +
               ", out of range [0, " + std::to_string(nv) + ")");
      ids[i] = static_cast<int>(id);
    }
    out.faces.push_back(std::move(ids));
  }
  return out;
}

}  // namespace fairshape
