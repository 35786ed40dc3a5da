// One variational sheet of Welch & Witkin: a hierarchical B-spline surface with its current
// and rest control vectors, the objective of §4.1 and the constraints of §4.2 assembled into
// a QuadraticProgram, and the automatic refinement of §4.4 driven by constraint error.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "fairshape/bspline/hierarchical_surface.h"
#include "fairshape/bspline/surface_constraints.h"
#include "fairshape/bspline/thin_plate_energy.h"
#include "fairshape/qp/qp_solver.h"

namespace fairshape::bspline {

enum class ShapeMetric {
  ThinPlate,     // eq. 4 (with rest_shape: eq. 6)
  Displacement,  // |p − p̂|², the control-point metric §4.1 criticizes
};

struct SheetEnergy {
  TensionWeights weights;
  ShapeMetric metric = ShapeMetric::ThinPlate;
  bool rest_shape = false;  // eq. 6 about the stored rest shape instead of eq. 4 about 0
};

struct SheetConstraint {
  //! Offset: w(u, v) − w(other) = target (§4.2.1). Region: w = surface + target over the
  //! rectangle from (u, v) to other (§4.2.2, bspline/region_constraint.h).
  enum class Kind { Point, Tangent, Normal, Curve, Offset, Region } kind = Kind::Point;
  double u = 0, v = 0;
  int direction = 0;  // tangent: 0 = D_u, 1 = D_v
  Vec3 target = Vec3::Zero();  // point / tangent target, normal direction, offset, region shift
  Eigen::Vector2d other = Eigen::Vector2d::Zero();  // offset: the point it is offset from; region: far corner
  CurveAttachment curve;
  CurveFormulation formulation = CurveFormulation::Mortar;
  CurveQuadrature quadrature = CurveQuadrature::Exact;  // the paper's formulation only
  //! A curve that is a ribbon (§5): its position rows and the cross-tangent rows of
  //! bspline/ribbon_constraint.h, whose target is `cross`, or `surface`'s cross derivative.
  bool ribbon = false;
  Vec3 cross = Vec3::Zero();
  //! Region: the target surface (before the shift); ribbon: the surface whose cross
  //! derivative is held (null: `cross`).
  std::shared_ptr<const SurfaceTrace> surface;
  std::string label;  // for messages: "constraints[2]"
};

class VariationalSheet {
 public:
  VariationalSheet(const SheetShape& shape, Eigen::MatrixXd initial);
  //! A sheet over an already refined surface with its current and rest control points (a
  //! sheet read back from a file, bspline/sheet_file.h). \throw InvalidInput for P or rest
  //! not dof_count × 3.
  VariationalSheet(HierarchicalSurface surface, Eigen::MatrixXd P, Eigen::MatrixXd rest);
  const HierarchicalSurface& surface() const { return surface_; }
  const Eigen::MatrixXd& coefficients() const { return P_; }
  void set_coefficients(Eigen::MatrixXd P);
  const Eigen::MatrixXd& rest() const { return rest_; }
  //! "Install the current shape as rest shape" (§5); melt() goes back to a remembered one.
  void install_rest_shape() { rest_ = P_; }
  void remember_rest_shape() { remembered_ = rest_; }
  void melt() { rest_ = remembered_; }
  //! Refines the given spans (widened as HierarchicalSurface::refine documents); every stored
  //! control vector is carried into the new basis exactly. Returns the spans added.
  int refine(const std::vector<SpanId>& spans);

  //! The thin-plate H (eq. 5) and its square root K for these weights on this surface, kept
  //! until the surface is refined or other weights are asked for: a design session's steps
  //! (a drag, an added constraint) keep the surface, and assembling H was most of such a step
  //! (at 32 × 32 spans, 104 of 122 ms with a 0.8 ms solve; papers/welch-witkin/README.md).
  //! K is assembled on first use (square_root()): only QR-penalty factors it, and at depth it
  //! is as large as H (papers/welch-witkin/README.md, "Memory of deep refinement").
  struct ThinPlate {
    TensionWeights weights;
    Backend backend = Backend::Optimized;
    SparseMatrix H;
    mutable std::shared_ptr<const SparseMatrix> K;  // null until asked for
  };
  const ThinPlate& thin_plate(const TensionWeights& weights, Backend backend) const;
  //! K of thin_plate(weights, backend), assembled once per surface and weights.
  const SparseMatrix& thin_plate_square_root(const TensionWeights& weights, Backend backend) const;

 private:
  HierarchicalSurface surface_;
  Eigen::MatrixXd P_, rest_, remembered_;
  // Shared by copies (the same surface) until one of them refines.
  mutable std::shared_ptr<const ThinPlate> thin_plate_;
};

//! The program of one sheet: H, f of the energy and the stacked constraint rows, over the
//! control points' n × 3 coordinates, or over the stacked unknowns [x; y; z] (3n × 1, H and K
//! block-diagonal) when a constraint couples the coordinates (normals).
//! \throw InvalidInput from the constraints (domain, degenerate normals, ...).
//! square_root: whether the program carries K (QR-penalty factors [μA; K]; KKT and range space
//! never read it, and without it QR-penalty derives one from H).
qp::QuadraticProgram assemble(const VariationalSheet& sheet, const SheetEnergy& energy,
                              const std::vector<SheetConstraint>& constraints, Backend backend, bool square_root = true);

//! Q of the sheet's current coefficients: ½pᵀHp (eq. 4), or ½(p − p̂)ᵀH(p − p̂) about the rest
//! shape (eq. 6, the displacement metric), from the program assemble() built for it.
double objective_value(const VariationalSheet& sheet, const SheetEnergy& energy, const qp::QuadraticProgram& program);

//! Constraint error per leaf cell (§4.4): point-to-point distances at the points, and
//! curve-to-curve distances |w(c(t)) − D(t)| sampled along each curve, the largest per cell;
//! every leaf cell is listed (0 where no constraint acts).
struct CellError {
  SpanId cell;
  double error;
};
std::vector<CellError> constraint_errors(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints);
//! The same with the curve constraints' targets given as functions of t instead of their
//! polylines (a variational curve's X(t), bspline/joined_design.h): target(i, t) for
//! constraints[i].
using CurveTarget = std::function<Vec3(std::size_t constraint, double t)>;
std::vector<CellError> constraint_errors(const VariationalSheet& sheet, const std::vector<SheetConstraint>& constraints,
                                         const CurveTarget& target);
double max_error(const std::vector<CellError>& errors);

struct RefinementOptions {
  double tolerance = 0;  // 0: no refinement
  int max_level = 4;
  int max_rounds = 8;
  //! After the solve (and any refinement, unless it met its tolerance): a weak curve constraint
  //! with a pointwise error above curve_error_factor × its error alone on the sheet there and
  //! whose error under refinement tends to a limit above curve_limit_share of what is left and
  //! above curve_conflict_tolerance × the surface's size (bspline/curve_fidelity.h) ends
  //! constraints_unmet: another constraint holds the surface off the curve. curve_limit_share 0:
  //! no check.
  double curve_error_factor = 2;
  double curve_limit_share = 0.5;
  double curve_conflict_tolerance = 1e-3;
  //! A tangent or normal on a weak curve's path whose derivative differs from the curve's slope
  //! there by more than this (a slope: world length per design length) is a conflict
  //! (bspline/slope_conflict.h): constraints_unmet.
  double curve_slope_tolerance = 1e-3;
  //! Whether this solve runs the resolution probe (curve_fidelity.h: an alone solve and two
  //! refined solves per curve, many times the step's own solve). The exact conflict checks
  //! (positions, slopes) run on every solve whatever this says.
  bool curve_probe = true;
};

//! The spans whose refinement §4.4 asks for: those holding a cell with error above the
//! tolerance whose next layer is within max_level.
std::vector<SpanId> spans_to_refine(const HierarchicalSurface& s, const std::vector<CellError>& errors, const RefinementOptions& refinement);

struct DesignReport {
  qp::QpReport qp;
  double energy = 0, analyze_s = 0, solve_s = 0, max_constraint_error = 0;
  //! The weak curve constraint with the worst pointwise error: that error, the constraint's error
  //! alone on the sheet, its error with the spans along the curve one level finer and the
  //! extrapolated limit under refinement (bspline/curve_fidelity.h; 0 where not computed).
  double curve_error = 0, curve_alone_error = 0, curve_error_refined = 0, curve_error_limit = 0;
  int rounds = 0, spans_refined = 0;
  Eigen::Index constraint_rows = 0;                     // of the last solve's program
  std::vector<std::vector<CellError>> errors_per_round;  // every solve with an answer, in order
  //! The sheet as the first solve left it, when refinement followed (Figure 3's unrefined surface).
  std::shared_ptr<const VariationalSheet> unrefined;
  std::string message;
};

//! Solve; then, while some cell's constraint error exceeds the tolerance and the depth allows,
//! refine those cells' spans and solve again (warm: the refined sheet keeps its shape).
DesignReport solve_sheet(VariationalSheet& sheet, const SheetEnergy& energy, const std::vector<SheetConstraint>& constraints,
                         qp::QpSolver& solver, const RefinementOptions& refinement, Backend backend);

//! The a-posteriori estimate §4.4 mentions but the paper did not implement: the same problem
//! solved once more with every leaf cell refined one level, compared with the current solution.
struct ObjectiveErrorEstimate {
  double energy_change = 0;    // |Q − Q_finer| / |Q_finer|
  double surface_change = 0;   // max |w − w_finer| over a grid of samples
  int finer_dofs = 0;
  std::string message;         // non-empty when the finer solve failed
};
ObjectiveErrorEstimate estimate_objective_error(const VariationalSheet& sheet, const SheetEnergy& energy,
                                                const std::vector<SheetConstraint>& constraints, qp::QpSolver& solver,
                                                Backend backend);

}  // namespace fairshape::bspline
