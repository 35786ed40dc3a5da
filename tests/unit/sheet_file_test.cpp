// Sheet files (bspline/sheet_file.h): a saved sheet reads back exactly, and a malformed or
// hostile file is refused with a message naming the file, the line and the problem.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <random>
#include <sstream>
#include <tuple>

#include "fairshape/bspline/sheet_file.h"
#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/core/config.h"
#include "fairshape/core/error.h"
#include "fairshape/qp/qp_solver.h"
#include "test_support.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

void check_same_layers_and_dofs(const HierarchicalSurface& a, const HierarchicalSurface& b) {
  REQUIRE(a.level_count() == b.level_count());
  for (int level = 0; level < a.level_count(); ++level) {
    const auto sa = a.spans(level), sb = b.spans(level);
    REQUIRE(sa.size() == sb.size());
    for (std::size_t k = 0; k < sa.size(); ++k) CHECK((sa[k].i == sb[k].i && sa[k].j == sb[k].j));
  }
  REQUIRE(a.dof_count() == b.dof_count());
  for (int k = 0; k < a.dof_count(); ++k) {
    const ControlId &x = a.dofs()[k], &y = b.dofs()[k];
    CHECK((x.level == y.level && x.i == y.i && x.j == y.j));
  }
}

void check_same_sheet(const VariationalSheet& a, const VariationalSheet& b) {
  const SheetShape &sa = a.surface().shape(), &sb = b.surface().shape();
  CHECK(sa.spans_u == sb.spans_u);
  CHECK(sa.spans_v == sb.spans_v);
  CHECK(sa.degree == sb.degree);
  CHECK(sa.periodic_u == sb.periodic_u);
  CHECK(sa.span_size == sb.span_size);
  check_same_layers_and_dofs(a.surface(), b.surface());
  CHECK(same_bits(a.coefficients(), b.coefficients()));
  CHECK(same_bits(a.rest(), b.rest()));
}

std::string text_of(const VariationalSheet& sheet) {
  std::ostringstream out;
  write_sheet(out, sheet);
  return out.str();
}

// An 8 x 6 plane, a few spans refined to layer 2, a rest shape of its own, solved with a
// point pulled up: every part of a sheet file is exercised.
VariationalSheet designed_sheet() {
  SheetShape shape{8, 6, 3, false};
  shape.span_size = {0.25, 1.0 / 3.0};
  SheetPlacement plane;
  plane.size_u = 2;
  plane.size_v = 2;
  VariationalSheet sheet(shape, initial_coefficients(plane, HierarchicalSurface(shape)));
  sheet.refine({{0, 2, 2}, {0, 3, 2}});
  sheet.refine({{1, 5, 5}});
  REQUIRE(sheet.surface().level_count() == 3);
  Eigen::MatrixXd bumped = sheet.coefficients();
  bumped(3, 2) += 0.1;
  sheet.set_coefficients(bumped);
  sheet.install_rest_shape();  // a rest shape that is not the current one after the solve
  SheetEnergy energy;
  energy.weights.alpha = 0.1 * Eigen::Matrix2d::Identity();
  // Corners held, one point pulled up: the sheet bends (one point alone would only move it).
  std::vector<SheetConstraint> points;
  for (const auto& [u, v, lift] : {std::tuple{2.7, 2.9, 0.4}, {0.0, 0.0, 0.0}, {8.0, 0.0, 0.0}, {0.0, 6.0, 0.0}, {8.0, 6.0, 0.0}}) {
    SheetConstraint c;
    c.u = u;
    c.v = v;
    c.target = sheet.surface().position(sheet.coefficients(), u, v) + Vec3(0, 0, lift);
    points.push_back(c);
  }
  Config none;
  auto kkt = qp::qp_solver_registry().create("kkt", Backend::Optimized, none);
  const DesignReport r = solve_sheet(sheet, energy, points, *kkt, {}, Backend::Optimized);
  REQUIRE(r.qp.summary.termination == Termination::Converged);
  return sheet;
}

double thin_plate(const VariationalSheet& s) {
  const SparseMatrix H = thin_plate_hessian(s.surface(), TensionWeights{}, Backend::Reference);
  return (s.coefficients().transpose() * (H * s.coefficients())).trace();
}

// The problem `text` is refused for, as the message says it ("mem.sheet:<line>: ...").
std::string refusal(const std::string& text) {
  try {
    (void)parse_sheet(text, "mem.sheet");
  } catch (const ParseError& e) {
    return e.what();
  }
  return "(accepted)";
}

std::string replace_line(std::string text, const std::string& starting_with, const std::string& by) {
  const std::size_t at = text.find("\n" + starting_with);
  REQUIRE(at != std::string::npos);
  const std::size_t end = text.find('\n', at + 1);
  return text.replace(at + 1, end - at - 1, by);
}

}  // namespace

TEST_CASE("a refined, solved sheet written and read back is the same sheet bit for bit", "[bspline][sheet_file]") {
  const VariationalSheet sheet = designed_sheet();
  const std::string text = text_of(sheet);
  const VariationalSheet back = parse_sheet(text, "mem.sheet");
  check_same_sheet(sheet, back);
  CHECK(text_of(back) == text);  // writing again changes nothing
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(0, 8), v(0, 6);
  for (int k = 0; k < 200; ++k) {
    const double a = u(gen), b = v(gen);
    const Vec3 x = sheet.surface().position(sheet.coefficients(), a, b), y = back.surface().position(back.coefficients(), a, b);
    CHECK((x.array() == y.array()).all());
  }
  CHECK(thin_plate(sheet) == thin_plate(back));
  CHECK(thin_plate(sheet) > 0);

  // Through a file, as runs do.
  const std::string path = (test::scratch_dir("sheet_file_round_trip") / "designed.sheet").string();
  save_sheet(sheet, path);
  check_same_sheet(sheet, load_sheet(path));
}

TEST_CASE("refining a reloaded sheet equals refining the original", "[bspline][sheet_file]") {
  VariationalSheet sheet = designed_sheet();
  VariationalSheet back = parse_sheet(text_of(sheet), "mem.sheet");
  const std::vector<SpanId> more{{2, 10, 10}, {1, 9, 2}, {0, 6, 5}};
  for (const SpanId& s : more) REQUIRE(sheet.surface().has_span(s));
  CHECK(sheet.refine(more) == back.refine(more));
  check_same_sheet(sheet, back);
}

TEST_CASE("a periodic sheet and a file in another dof order read back the same sheet", "[bspline][sheet_file]") {
  SheetShape shape{6, 4, 3, true};
  SheetPlacement cylinder;
  cylinder.geometry = SheetGeometry::Cylinder;
  VariationalSheet sheet(shape, initial_coefficients(cylinder, HierarchicalSurface(shape)));
  sheet.refine({{0, 0, 1}, {0, 5, 1}});  // across the seam
  check_same_sheet(sheet, parse_sheet(text_of(sheet), "cyl.sheet"));

  // The control-point records reversed: matched by (level, i, j), not by position.
  std::istringstream in(text_of(sheet));
  std::vector<std::string> head, records;
  for (std::string line; std::getline(in, line);) (line.rfind("c ", 0) == 0 ? records : head).push_back(line);
  std::reverse(records.begin(), records.end());
  std::string shuffled;
  for (const auto* part : {&head, &records})
    for (const std::string& line : *part) shuffled += line + "\n";
  check_same_sheet(sheet, parse_sheet(shuffled, "shuffled.sheet"));
}

TEST_CASE("malformed sheet files are refused naming the file, the line and the problem", "[bspline][sheet_file]") {
  VariationalSheet sheet({4, 4, 3, false}, Eigen::MatrixXd::Zero(49, 3));
  sheet.refine({{0, 1, 1}});
  sheet.refine({{1, 3, 3}});
  const std::string good = text_of(sheet);
  REQUIRE(refusal(good) == "(accepted)");
  const std::string first_c = good.substr(good.find("\nc ") + 1, good.find('\n', good.find("\nc ") + 1) - good.find("\nc ") - 1);
  const std::string first_id = first_c.substr(0, first_c.find(' ', first_c.find(' ', first_c.find(' ', 2) + 1) + 1));
  struct Case {
    std::string text, says;
  };
  const std::vector<Case> cases{
      {"", "empty file"},
      {"OFF\n3 1 0\n", "mem.sheet:1: not a fairshape sheet file"},
      {replace_line(good, "format", "format fairshape-sheet 2"), "format version 2 is not supported (this build reads version 1)"},
      {replace_line(good, "periodic_u", "color red"), "mem.sheet:5: expected 'periodic_u true|false', got 'color'"},
      {replace_line(good, "degree", "degree 3 4"), "'degree' takes 1 value"},
      {replace_line(good, "degree", "degree 9"), "degree is 9, outside [2, 5]"},
      {replace_line(good, "span_size", "span_size 1 -2"), "span_size must be positive"},
      {replace_line(good, "span_size", "span_size nan 1"), "span_size u is not finite"},
      {replace_line(good, "c ", first_id + " inf 0 0 0 0 0"), "x is not finite"},
      {replace_line(good, "c ", first_id + " 0 0 0 0 -nan 0"), "rest y is not finite"},
      {replace_line(good, "c ", first_id + " 1e999 0 0 0 0 0"), "expected a number for x"},
      {replace_line(good, "layer 1", "layer 1 0"), "layer 1 lists no spans"},
      {replace_line(good, "layer 1", "layer 1 1000000000"), "bytes follow"},
      {replace_line(good, "layer 2", "layer 3 1"), "expected layer 2 next"},
      {replace_line(good, "s ", "s 99 0"), "span i is 99, outside [0, 7]"},
      {replace_line(good, "dofs", "dofs 3"), "dofs 3, but the layers above define"},
      {replace_line(good, "c ", "c 0 50 50 0 0 0 0 0 0"), "control point (level 0, 50, 50) is not an unknown"},
      {replace_line(good, "c ", "c 0 0 0 0 0 0"), "'c' takes 9 values"},
      {good + "c 0 0 0 0 0 0 0 0 0\n", "after the last control point"},
      {good.substr(0, good.rfind('\n', good.size() / 2) + 1), "file truncated or count wrong"},
      {good.substr(0, good.rfind('\n', good.size() - 2) + 1), "control point " + std::to_string(sheet.surface().dof_count()) + " of " +
                                                      std::to_string(sheet.surface().dof_count()) + ": file ends early"},
      {replace_line(good, "spans", "spans 512 512"), "more than the"},  // the largest base, in a small file
      {replace_line(good, "spans", "spans 1024 1024"), "above the limit of 262144"},
      {replace_line(good, "spans", "spans 0 4"), "spans_u is 0, outside"},
      {replace_line(good, "layers", "layers 14"), "the layer count is 14, outside [1, 13]"},
  };
  for (const Case& c : cases) {
    INFO(c.says);
    const std::string message = refusal(c.text);
    CHECK_THAT(message, Catch::Matchers::Contains(c.says));
    CHECK_THAT(message, Catch::Matchers::Contains("mem.sheet"));
  }
  // A layer-2 span whose parent is not a layer-1 span, and a span listed twice.
  const std::size_t layer2 = good.find("\nlayer 2 ");
  const std::size_t first_s = good.find("\ns ", layer2) + 1;
  const std::size_t end_s = good.find('\n', first_s);
  CHECK_THAT(refusal(std::string(good).replace(first_s, end_s - first_s, "s 15 15")), Catch::Matchers::Contains("is not nested"));
  const std::size_t second_s = end_s + 1;
  CHECK_THAT(refusal(std::string(good).replace(second_s, good.find('\n', second_s) - second_s, good.substr(first_s, end_s - first_s))),
             Catch::Matchers::Contains("is listed twice"));
  // A control point listed twice (the count then misses another).
  const std::size_t second_c = good.find("\nc ", good.find("\nc ") + 1) + 1;
  CHECK_THAT(refusal(std::string(good).replace(second_c, good.find('\n', second_c) - second_c, first_c)),
             Catch::Matchers::Contains("is listed twice"));
  // (level 0, i, j + 7) has the key of (level 0, i + 1, j) on this 7-wide control grid: a
  // lookup by key alone would take it for that unknown.
  int alias = 0;
  while (sheet.surface().dofs()[alias].level != 0 || sheet.surface().dofs()[alias].i < 1) ++alias;
  const ControlId& a = sheet.surface().dofs()[alias];
  CHECK_THAT(refusal(replace_line(good, "c " + std::to_string(a.level) + " " + std::to_string(a.i) + " " + std::to_string(a.j) + " ",
                                  "c 0 " + std::to_string(a.i - 1) + " " + std::to_string(a.j + 7) + " 0 0 0 0 0 0")),
             Catch::Matchers::Contains("is not an unknown"));
  // A missing file is an IOError naming it.
  CHECK_THROWS_WITH(load_sheet("/nonexistent/floor.sheet"), Catch::Matchers::Contains("/nonexistent/floor.sheet"));
}

TEST_CASE("truncated and corrupted sheet files never crash", "[bspline][sheet_file]") {
  VariationalSheet sheet({4, 4, 2, false}, Eigen::MatrixXd::Zero(36, 3));
  sheet.refine({{0, 2, 1}});
  const std::string good = text_of(sheet);
  int accepted = 0;
  for (std::size_t n = 0; n <= good.size(); n += 3) {
    try {
      (void)parse_sheet(good.substr(0, n), "cut.sheet");
      ++accepted;
    } catch (const Error&) {  // anything else fails the test
    }
  }
  std::mt19937 gen(5);
  for (int k = 0; k < 300; ++k) {
    std::string bad = good;
    bad[std::uniform_int_distribution<std::size_t>(0, bad.size() - 1)(gen)] = "0-9 \n#x."[k % 8];
    try {
      (void)parse_sheet(bad, "flip.sheet");
    } catch (const Error&) {
    }
  }
  CHECK(accepted <= 2);  // the whole file, perhaps without its final newline
}

TEST_CASE("from_layers refuses layers that are not a hierarchy", "[bspline][sheet_file]") {
  const SheetShape shape{4, 4, 3, false};
  const HierarchicalSurface base(shape);
  const std::vector<SpanId> layer0 = base.spans(0);
  CHECK_THROWS_WITH(HierarchicalSurface::from_layers(shape, {layer0, {{1, 2, 2}}, {{2, 0, 0}}}),
                    Catch::Matchers::Contains("is not nested"));
  CHECK_THROWS_WITH(HierarchicalSurface::from_layers(shape, {std::vector<SpanId>(layer0.begin(), layer0.end() - 1)}),
                    Catch::Matchers::Contains("whole 4 x 4 base grid"));
  CHECK_THROWS_WITH(HierarchicalSurface::from_layers(shape, {layer0, {{1, 8, 0}}}), Catch::Matchers::Contains("outside"));
  CHECK_THROWS_AS(HierarchicalSurface::from_layers(shape, {layer0, {}}), InvalidInput);
  CHECK(HierarchicalSurface::from_layers(shape, {layer0, {{1, 2, 2}}}).level_count() == 2);
}
