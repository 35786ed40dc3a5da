// Feature curves in a multiresolution Loop surface (Khodakovsky & Schröder, "Fine level feature
// editing for subdivision surfaces", §2.5–2.6). The underlying surface is never modified: the
// features are kept as definitions, and evaluation applies them level by level, coarse to fine —
// level l is synthesized from the perturbed level l − 1 with the surface's own details in local
// frames, then perturbed by the features drawn on level l. So a feature can be edited, moved or
// deleted without loss, finer features follow coarser ones, and an edit of the base surface
// carries every feature with it (curves are attached to the surface by face and barycentric
// coordinates). Finally the finest level is set so that the visible surface (the limit, or the
// finest control points: ProfileTarget) carries every feature's profile exactly, whatever level it
// was drawn on (visible_profile.h); ProfileTarget::DrawnLevel stops at the paper's step.
#pragma once

#include <map>
#include <set>
#include <vector>

#include "fairshape/feature/perturbation.h"
#include "fairshape/feature/visible_profile.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape::feature {

//! What the last evaluation recomputed (a design step's cost): the whole hierarchy, or the
//! region the changed features reach (FeaturedSurface::set_region_evaluation).
struct EvaluationReport {
  bool region = false;                   // false: the whole hierarchy was evaluated
  std::vector<std::vector<int>> vertices;  // per level, the vertices recomputed (region only)
  long long vertices_recomputed = 0;     // over all levels (the whole hierarchy's count when full)
};

class FeaturedSurface {
 public:
  //! \throw InvalidInput unless the hierarchy is Loop.
  FeaturedSurface(MultiresSurface surface, Backend backend, ProfileTarget target = ProfileTarget::Limit);
  ProfileTarget profile_target() const { return target_; }

  int add(FeatureCurve curve);  // returns the feature's id
  void replace(int id, FeatureCurve curve);
  void remove(int id);
  const std::map<int, FeatureCurve>& features() const { return features_; }

  //! The surface without features (edit it, e.g. set_base_positions + synthesize, through this).
  //! The next evaluation is then of the whole hierarchy.
  MultiresSurface& original() { dirty_ = true; original_changed_ = true; return original_; }
  const MultiresSurface& original() const { return original_; }

  //! The surface with every feature applied. \throw InvalidInput / FlatnessError for a feature
  //! that cannot be applied (the message names it).
  const MultiresSurface& result();
  //! The features of the coarsest level that has any, applied to the unperturbed surface
  //! (their base curves followed on it, their perturbation and its flatness checked) without
  //! evaluating: what can be checked before a run. Finer features are drawn on the perturbed
  //! surface, so only result() checks them.
  //! \throw InvalidInput / FlatnessError as result() would for those features.
  void check_coarsest_features() const;
  //! The perturbation applied on a level by the last evaluation (empty when none).
  const LevelPerturbation& perturbation(int level);
  //! The base curves of the last evaluation (for output), per feature id.
  const std::map<int, BaseCurve>& base_curves();
  //! The levels' operators of the last evaluation (coarse to fine) and the visible targets
  //! they compose to (visible_profile.h; computed for every ProfileTarget, so that the
  //! drawn-level semantics can be measured against them too).
  const std::vector<LevelOperator>& operators();
  const VisibleTargets& visible_targets();

  //! Region-limited re-evaluation (default on): after an evaluation, when only features were
  //! added, replaced or removed, the next one recomputes only what they reach — on the level of
  //! a changed feature its old and new neighbourhoods (every vertex within its reach, the
  //! largest feature height and three of its own longest edges of the curve), on each finer level the
  //! vertices whose subdivision stencil and local frame read a recomputed one, there the
  //! features whose neighbourhood meets them (rebuilt on the changed surface, their old and new
  //! neighbourhoods added), and for the limit target the blocks of the least-squares fit those
  //! rows meet. Every other vertex of every level keeps its value bit for bit; the recomputed
  //! ones equal a whole evaluation to rounding. Off: every evaluation is of the whole hierarchy.
  void set_region_evaluation(bool on) { region_evaluation_ = on; }
  const EvaluationReport& last_evaluation() const { return report_; }

 private:
  // The base curves of features `ids` on `mesh` (one level) and the perturbation they make.
  struct LevelFeatures {
    std::vector<BaseCurve> curves;
    LevelPerturbation perturbation;
  };
  LevelFeatures apply_on(const SurfaceMesh& mesh, const std::vector<int>& ids) const;
  void evaluate_or_update();
  void evaluate();
  void evaluate_region();
  void changed(int id) { pending_.insert(id); }
  std::vector<int> features_on(int level) const;
  MultiresSurface original_, result_;
  Backend backend_;
  ProfileTarget target_;
  std::vector<LevelOperator> operators_;
  VisibleTargets visible_;
  std::map<int, FeatureCurve> features_;
  std::map<int, BaseCurve> base_curves_;
  std::vector<LevelPerturbation> perturbations_;
  int next_id_ = 0;
  bool dirty_ = true;
  // Region evaluation: features changed since the last evaluation, whether the original was
  // (then the next evaluation is whole), the limit fit and which limit points it moved.
  bool region_evaluation_ = true, original_changed_ = true, evaluated_ = false;
  std::set<int> pending_;
  MatrixX3 limit_fit_;
  std::vector<char> limit_moving_;
  EvaluationReport report_;
};

}  // namespace fairshape::feature
