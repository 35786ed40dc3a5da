// Khodakovsky & Schröder's editing session ("Fine level feature editing for subdivision
// surfaces", §2.6): features are definitions kept apart from the surface and re-applied to it, so
// the user adds, moves, re-parameterizes and deletes them one step at a time, and a step
// recomputes only the region its features reach (FeaturedSurface::set_region_evaluation;
// papers/khodakovsky-schroder/README.md, "Design steps"). A FeatureSession owns the prepared
// problem — the Loop hierarchy without features, the featured surface with what region
// re-evaluation reuses (the levels' operators, perturbations, visible targets and limit fit), each
// drawn level's surface for placing curves, the finest level's rest faces for the fold check —
// and advances by steps. Each step places what it draws (nothing changes if a drawing cannot be
// placed), evaluates, and measures its own result: where each feature was placed against where
// it was asked, the finest vertices it moved, and faces turned over. The whole profile check
// (measure(): achieved heights, widths and profile per feature, features.csv's numbers) costs
// about a whole evaluation and is made on request.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fairshape/core/summary.h"
#include "fairshape/feature/feature_drawing.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/mesh/orientation.h"

namespace fairshape {

//! One change a step makes to the session's features.
struct FeatureEdit {
  enum class Kind { Add, Replace, SetParams, Remove };
  Kind kind = Kind::Add;
  int id = -1;                      // Replace, SetParams, Remove: the feature's id
  feature::FeatureDrawing drawing;  // Add, Replace: the feature as drawn (placed by the step)
  feature::FeatureParams params;    // SetParams: its new profile (radius, height, crease, ...)
  static FeatureEdit add(feature::FeatureDrawing d);
  //! Moved or redrawn: a new drawing for the same feature (its id kept).
  static FeatureEdit replace(int id, feature::FeatureDrawing d);
  //! The same curve with other profile parameters (width, height, crease, ...).
  static FeatureEdit set_params(int id, const feature::FeatureParams& q);
  static FeatureEdit remove(int id);
};

//! Where a drawn feature was placed against where it was asked.
struct FeaturePlacement {
  int id = -1;
  std::string name;
  int level = 0;
  int points = 0;       // control points on the level
  double farthest = 0;  // the farthest placed world point from the point asked (world units; 0 for
                        // surface points and placement tools)
  double allowed = 0;   // max_distance × the bounding-box diagonal: the farthest placing accepts
};

//! The whole profile check, as a run reports it (features.csv, runs.csv's termination).
struct FeatureMeasurement {
  //! converged; constraints_unmet naming the first feature that misses its tolerance on the
  //! surface its profile_on decides (profile_measure.h); folded (outranks a miss, keeps its message).
  SolveSummary summary;
  std::vector<feature::FeatureMeasure> features;  // per feature, in id order
  FoldReport folds;                               // the finest level against the surface without features
  double check_s = 0;
};

//! What a step asks to be checked: the cheap checks always; the profiles (about the cost of a
//! whole evaluation) on request — an interactive front end asks for them when a drag ends.
enum class FeatureChecks { Cheap, Profiles };

//! One step's result.
struct FeatureStep {
  //! converged, or folded naming where the finest level turned over against the surface
  //! without features (with FeatureChecks::Profiles: the measurement's verdict).
  SolveSummary summary;
  std::vector<int> added, moved, changed, removed;  // feature ids, in the order of the edits
  std::vector<FeaturePlacement> placed;             // every drawing the step placed
  feature::EvaluationReport evaluation;             // region or whole, and what it recomputed
  long long vertices_changed = -1;  // finest vertices the step moved by > 1e-12 × the diagonal (−1: first step)
  double max_change = 0;            // the largest move of a finest vertex (0 on the first step)
  FoldReport folds;                 // every finest face against the surface without features
  std::optional<FeatureMeasurement> profiles;  // with FeatureChecks::Profiles
  double place_s = 0, solve_s = 0, check_s = 0;  // placing the drawings; evaluating; the checks
  //! The session's surface with every feature applied, valid until its next step.
  const MultiresSurface* surface = nullptr;
};

struct FeatureSessionOptions {
  Backend backend = Backend::Optimized;
  feature::ProfileTarget profile_target = feature::ProfileTarget::Limit;
  bool region_steps = true;  // false: every step evaluates the whole hierarchy
};

class FeatureSession {
 public:
  //! \throw InvalidInput unless the hierarchy is Loop.
  FeatureSession(MultiresSurface original, const FeatureSessionOptions& options);
  // The featured surface and the caches point into each other's meshes: not copied or moved.
  FeatureSession(const FeatureSession&) = delete;
  FeatureSession& operator=(const FeatureSession&) = delete;

  // ---- Steps: each places its drawings, evaluates where they reach, checks the result.
  //! The edits, evaluated once. Every drawing is placed and every id checked first, so a drawing
  //! that cannot be placed changes nothing. \throw InvalidInput naming the feature (a point off
  //! the surface, an unknown id, an invalid parameter), InvalidConfig for a feature narrower than
  //! two finest edges; InvalidInput / FlatnessError from the evaluation (then the session holds
  //! the edits, and its next evaluation is whole: replace or remove the feature named).
  FeatureStep apply(std::vector<FeatureEdit> edits, FeatureChecks checks = FeatureChecks::Cheap);
  FeatureStep add(feature::FeatureDrawing f, FeatureChecks checks = FeatureChecks::Cheap);
  FeatureStep replace(int id, feature::FeatureDrawing f, FeatureChecks checks = FeatureChecks::Cheap);
  FeatureStep set_params(int id, const feature::FeatureParams& q, FeatureChecks checks = FeatureChecks::Cheap);
  FeatureStep remove(int id, FeatureChecks checks = FeatureChecks::Cheap);
  //! A step without edits: evaluates what stage_add and edit_original() left (the first step of a run).
  FeatureStep evaluate(FeatureChecks checks = FeatureChecks::Cheap);

  // ---- Set-up before a step.
  //! The drawing placed on the surface as it is now and added; evaluated by the next step (a run
  //! places its first features before the coarse edit that carries them). Returns its id.
  //! \throw as apply() does for placing.
  int stage_add(feature::FeatureDrawing f);
  //! The surface without features, to edit (a coarse edit carries every feature: they are
  //! attached by face and barycentric coordinates); the next step evaluates the whole hierarchy.
  MultiresSurface& edit_original();
  const MultiresSurface& original() const { return surface_.original(); }

  // ---- On request.
  //! The profile of every feature measured (features.csv) and the folds, with their verdict.
  FeatureMeasurement measure();
  //! The features of the coarsest featured level applied to the surface without features (what
  //! can be checked before a run; FeaturedSurface::check_coarsest_features).
  void check_coarsest_features() const { surface_.check_coarsest_features(); }

  // ---- State.
  const std::map<int, feature::FeatureCurve>& features() const { return surface_.features(); }
  int levels() const { return surface_.original().levels(); }
  //! The surface with every feature applied (evaluates what is staged).
  const MultiresSurface& surface() { return surface_.result(); }
  //! The featured surface (its base curves, operators and targets, for exports).
  feature::FeaturedSurface& featured() { return surface_; }

 private:
  void place(feature::FeatureDrawing& f, FeatureStep& step);
  const feature::TriangleSurface& drawn_on(int level);
  double diagonal();
  void check_step(FeatureStep& step, FeatureChecks checks);
  const RestFaces& rest_faces();

  feature::FeaturedSurface surface_;
  // Built from the surface without features as it is, dropped when it is edited (edit_original()).
  std::map<int, feature::TriangleSurface> drawn_on_;  // per level: its normals and closest-point tree
  std::optional<double> diagonal_;                    // of the finest level without features
  std::optional<RestFaces> rest_faces_;               // the finest faces without features
  MatrixX3 previous_;                                 // the finest level after the last step
  FeatureStep staged_;                                // what stage_add placed, reported by the next step
  bool changed_ = true;                               // something to evaluate since the last step
};

}  // namespace fairshape
