#include "fairshape/bspline/sheet_file.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_set>

#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/atomic_file.h"
#include "fairshape/core/error.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape::bspline {
namespace {

using io::internal::TextScanner;

// The shortest text that reads back to the same double (std::to_chars' guarantee), so a
// saved sheet reloads bit for bit without printing 17 digits for every 0.5.
void put(std::ostream& out, double x) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out << ' ';
  out.write(buf, r.ptr - buf);
}

// The fewest bytes a record can take, for bounding counts by the bytes left before allocating.
constexpr std::size_t kSpanLineBytes = 6;    // "s 0 0\n"
constexpr std::size_t kControlLineBytes = 20;  // "c 0 0 0 0 0 0 0 0 0\n"

// The next record, which must be `key` followed by `values` tokens; `where` (e.g. "layer 1,
// span 3 of 12") says which record of a list was expected, so a wrong count is plain.
void expect(TextScanner& sc, const char* key, std::size_t values, const char* shape, const std::string& where = "") {
  const std::string at = where.empty() ? "" : where + ": ";
  if (!sc.next_line()) sc.fail(at + "file ends early: expected '" + shape + "'");
  const auto& t = sc.tokens();
  if (t[0] != key) sc.fail(at + "expected '" + shape + "', got '" + std::string(t[0].substr(0, 40)) + "'");
  if (t.size() != values + 1)
    sc.fail(at + "'" + key + "' takes " + std::to_string(values) + " value" + (values == 1 ? "" : "s") + " ('" + shape +
            "'), got " + std::to_string(t.size() - 1));
}

int int_in(const TextScanner& sc, std::string_view tok, const char* what, long long lo, long long hi) {
  const long long v = sc.to_integer(tok, what);
  if (v < lo || v > hi)
    sc.fail(std::string(what) + " is " + std::to_string(v) + ", outside [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<int>(v);
}

SheetShape read_shape(TextScanner& sc) {
  if (!sc.next_line()) sc.fail("empty file: not a fairshape sheet file");
  const auto& t = sc.tokens();
  const std::string expected = "format " + std::string(kSheetFormatName) + " " + std::to_string(kSheetFormatVersion);
  if (t[0] != "format" || t.size() != 3 || t[1] != kSheetFormatName)
    sc.fail("not a fairshape sheet file: the first line must be '" + expected + "'");
  const long long version = sc.to_integer(t[2], "the format version");
  if (version != kSheetFormatVersion)
    sc.fail("format version " + std::to_string(version) + " is not supported (this build reads version " +
            std::to_string(kSheetFormatVersion) + ")");

  SheetShape shape;
  const long long most = HierarchicalSurface::kMaxBaseSpans;
  expect(sc, "spans", 2, "spans <spans_u> <spans_v>");
  shape.spans_u = int_in(sc, sc.tokens()[1], "spans_u", 1, most);
  shape.spans_v = int_in(sc, sc.tokens()[2], "spans_v", 1, most);
  if (static_cast<long long>(shape.spans_u) * shape.spans_v > most)
    sc.fail("a sheet of " + std::to_string(shape.spans_u) + " x " + std::to_string(shape.spans_v) +
            " base spans is above the limit of " + std::to_string(most));
  expect(sc, "degree", 1, "degree <r>");
  shape.degree = int_in(sc, sc.tokens()[1], "degree", kMinDegree, kMaxDegree);
  expect(sc, "periodic_u", 1, "periodic_u true|false");
  const std::string_view periodic = sc.tokens()[1];
  if (periodic != "true" && periodic != "false")
    sc.fail("periodic_u is 'true' or 'false', got '" + std::string(periodic.substr(0, 40)) + "'");
  shape.periodic_u = periodic == "true";
  if (shape.periodic_u && shape.spans_u < shape.degree + 1)
    sc.fail("a sheet periodic in u needs at least degree + 1 = " + std::to_string(shape.degree + 1) + " spans in u (got " +
            std::to_string(shape.spans_u) + ")");
  expect(sc, "span_size", 2, "span_size <u> <v>");
  for (int k = 0; k < 2; ++k) {
    shape.span_size[k] = sc.to_double(sc.tokens()[1 + k], k == 0 ? "span_size u" : "span_size v");
    if (!(shape.span_size[k] > 0)) sc.fail("span_size must be positive");
  }
  // The spline space only grows under refinement, so the file holds at least the base layer's
  // control points: a short file cannot make us build a huge base grid.
  const long long base = static_cast<long long>(shape.periodic_u ? shape.spans_u : shape.spans_u + shape.degree) *
                         (shape.spans_v + shape.degree);
  if (static_cast<unsigned long long>(base) > sc.remaining_bytes() / kControlLineBytes)
    sc.fail("a sheet of " + std::to_string(shape.spans_u) + " x " + std::to_string(shape.spans_v) + " base spans has at least " +
            std::to_string(base) + " control points, more than the " + std::to_string(sc.remaining_bytes()) +
            " bytes that follow can hold (file truncated?)");
  return shape;
}

// Layers 1.. (layer 0 is always the whole base grid and is not listed), checked record by
// record so that every error names its line.
std::vector<std::vector<SpanId>> read_layers(TextScanner& sc, const HierarchicalSurface& base) {
  std::vector<std::vector<SpanId>> layers{base.spans(0)};
  expect(sc, "layers", 1, "layers <count, the base layer included>");
  const int count = int_in(sc, sc.tokens()[1], "the layer count", 1, HierarchicalSurface::kMaxLevel + 1);
  if (!base.level_fits(count - 1))
    sc.fail(std::to_string(count) + " layers: layer " + std::to_string(count - 1) + " of a sheet of " +
            std::to_string(base.shape().spans_u) + " x " + std::to_string(base.shape().spans_v) +
            " base spans would have more spans than an int counts");
  std::unordered_set<std::int64_t> coarse, fine;  // Ω_{L−1}, Ω_L as i · spans_v(L) + j
  for (const SpanId& s : layers[0]) coarse.insert(static_cast<std::int64_t>(s.i) * base.spans_v(0) + s.j);
  for (int level = 1; level < count; ++level) {
    const std::string where = "layer " + std::to_string(level);
    expect(sc, "layer", 2, "layer <level> <span count>", where);
    if (sc.to_integer(sc.tokens()[1], "the layer's level") != level)
      sc.fail("expected layer " + std::to_string(level) + " next (layers are listed in order from 1), got layer " +
              std::string(sc.tokens()[1].substr(0, 40)));
    const long long n = sc.to_count(sc.tokens()[2], "the span count", kSpanLineBytes);
    if (n == 0) sc.fail(where + " lists no spans (leave the layer out)");
    const int nu = base.spans_u(level), nv = base.spans_v(level);
    layers.emplace_back();
    fine.clear();
    for (long long k = 0; k < n; ++k) {
      expect(sc, "s", 2, "s <i> <j>", where + ", span " + std::to_string(k + 1) + " of " + std::to_string(n));
      const SpanId s{level, int_in(sc, sc.tokens()[1], "span i", 0, nu - 1), int_in(sc, sc.tokens()[2], "span j", 0, nv - 1)};
      const auto name = [&] { return where + " span (" + std::to_string(s.i) + ", " + std::to_string(s.j) + ")"; };
      if (!coarse.count(static_cast<std::int64_t>(s.i / 2) * base.spans_v(level - 1) + s.j / 2))
        sc.fail(name() + " is not nested: its parent (" + std::to_string(s.i / 2) + ", " + std::to_string(s.j / 2) +
                ") is not a span of layer " + std::to_string(level - 1));
      if (!fine.insert(static_cast<std::int64_t>(s.i) * nv + s.j).second) sc.fail(name() + " is listed twice");
      layers.back().push_back(s);
    }
    coarse.swap(fine);
  }
  return layers;
}

}  // namespace

void write_sheet(std::ostream& out, const VariationalSheet& sheet) {
  const HierarchicalSurface& s = sheet.surface();
  const SheetShape& shape = s.shape();
  const Eigen::MatrixXd &P = sheet.coefficients(), &rest = sheet.rest();
  if (!P.allFinite() || !rest.allFinite())
    throw OutputError("sheet file: the sheet has non-finite control points; nothing written");
  out << "# A hierarchical B-spline sheet of fairshape (configs/README.md, \"Sheet files\").\n";
  out << "format " << kSheetFormatName << ' ' << kSheetFormatVersion << '\n';
  out << "spans " << shape.spans_u << ' ' << shape.spans_v << '\n';
  out << "degree " << shape.degree << '\n';
  out << "periodic_u " << (shape.periodic_u ? "true" : "false") << '\n';
  out << "span_size";
  put(out, shape.span_size.x());
  put(out, shape.span_size.y());
  out << "\nlayers " << s.level_count() << '\n';
  if (s.level_count() > 1) out << "# layer <level> <count>, then its spans: s <i> <j>  (layer 0 is the whole base grid)\n";
  for (int level = 1; level < s.level_count(); ++level) {
    out << "layer " << level << ' ' << s.span_count(level) << '\n';
    for (const SpanId& span : s.spans(level)) out << "s " << span.i << ' ' << span.j << '\n';
  }
  out << "dofs " << s.dof_count() << '\n';
  out << "# c <level> <i> <j> <x> <y> <z> <rest x> <rest y> <rest z>, in dof order\n";
  for (int k = 0; k < s.dof_count(); ++k) {
    const ControlId& c = s.dofs()[k];
    out << "c " << c.level << ' ' << c.i << ' ' << c.j;
    for (int d = 0; d < 3; ++d) put(out, P(k, d));
    for (int d = 0; d < 3; ++d) put(out, rest(k, d));
    out << '\n';
  }
}

void save_sheet(const VariationalSheet& sheet, const std::string& path) {
  write_atomically(path, [&](std::ostream& out) { write_sheet(out, sheet); });
}

VariationalSheet parse_sheet(std::string_view text, const std::string& name) {
  TextScanner sc(text, name);
  const SheetShape shape = read_shape(sc);
  std::vector<std::vector<SpanId>> layers;
  std::optional<HierarchicalSurface> surface;
  try {
    const HierarchicalSurface base(shape);
    layers = read_layers(sc, base);
    surface = HierarchicalSurface::from_layers(shape, layers);
  } catch (const InvalidInput& e) {  // read_shape and read_layers checked all this already
    sc.fail(e.what());
  }

  // The unknowns, matched to the rebuilt surface by ControlId: a file in another dof order
  // (written by another numbering) still reads back the same surface.
  expect(sc, "dofs", 1, "dofs <count>");
  const long long n = sc.to_count(sc.tokens()[1], "the dof count", kControlLineBytes);
  if (n != surface->dof_count())
    sc.fail("dofs " + std::to_string(n) + ", but the layers above define " + std::to_string(surface->dof_count()) +
            " unknowns");
  Eigen::MatrixXd P(n, 3), rest(n, 3);
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  const int most = std::numeric_limits<int>::max();
  for (long long k = 0; k < n; ++k) {
    expect(sc, "c", 9, "c <level> <i> <j> <x> <y> <z> <rest x> <rest y> <rest z>",
           "control point " + std::to_string(k + 1) + " of " + std::to_string(n));
    const auto& t = sc.tokens();
    const ControlId c{int_in(sc, t[1], "control level", 0, surface->level_count() - 1), int_in(sc, t[2], "control i", 0, most),
                      int_in(sc, t[3], "control j", 0, most)};
    const auto id = [&] {
      return "control point (level " + std::to_string(c.level) + ", " + std::to_string(c.i) + ", " + std::to_string(c.j) + ")";
    };
    // dof_index keys (i, j) as one integer, so an out-of-range j could alias another control
    // point: the dof found must be this very one.
    const int d = surface->dof_index(c);
    const bool same = d >= 0 && surface->dofs()[d].level == c.level && surface->dofs()[d].i == c.i && surface->dofs()[d].j == c.j;
    if (!same) sc.fail(id() + " is not an unknown of the surface the layers define");
    if (seen[d]) sc.fail(id() + " is listed twice");
    seen[d] = 1;
    static const char* const what[6] = {"x", "y", "z", "rest x", "rest y", "rest z"};
    for (int a = 0; a < 3; ++a) {
      P(d, a) = sc.to_double(t[4 + a], what[a]);
      rest(d, a) = sc.to_double(t[7 + a], what[3 + a]);
    }
  }
  if (sc.next_line()) sc.fail("unexpected '" + std::string(sc.tokens()[0].substr(0, 40)) + "' after the last control point");
  return VariationalSheet(std::move(*surface), std::move(P), std::move(rest));
}

VariationalSheet load_sheet(const std::string& path) { return parse_sheet(io::internal::read_whole_file(path), path); }

}  // namespace fairshape::bspline
