// One surface-edit run (Boier-Martin et al.), parsed and validated from its resolved YAML.
// Building a SurfaceEditSpec is the validation step: it looks every component up, reads every key (rejecting unknown
// ones and out-of-range values) and checks input files exist, before anything is computed.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "fairshape/core/backend.h"
#include "fairshape/design/edit_assembly.h"
#include "fairshape/design/edit_solve.h"
#include "fairshape/design/multilevel_edit.h"
#include "fairshape/design/regional_edit.h"
#include "fairshape/design/rotation_aware_edit.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/run_basics.h"
#include "fairshape/subdivision/scheme.h"
#include "fairshape/experiment/vtk_policy.h"

namespace fairshape {

struct EnergyTerm {
  std::string type;
  double weight = 1.0;
  std::shared_ptr<Energy> energy;  // shared with the sessions built from this spec
};

struct ConstraintTerm {
  std::string type;
  std::shared_ptr<Constraint> constraint;
  Influence influence;  // influence_level, influence_rings (design/influence.h)
};

enum class Formulation { Displacement, Position };
enum class Representation { Mesh, CatmullClark, Loop };  // the mesh itself, or its subdivision surface
enum class InitialGuess { Zero, Random };
//! single-level: the solver on the edit level alone; the others: Boier-Martin et al. §5's ladder.
enum class AccuracyMode { SingleLevel, Interactive, Improved, Converged };

struct OutputOptions {
  VtkPolicy vtk = VtkPolicy::Final;
  int vtk_every = 10;
  bool iterations = true;
  bool final_mesh = true;
  bool reference_solution = true;  // error_vs_reference against a tight direct solve
  bool system = false;             // the assembled problem as Matrix Market (system_export.h)
};

// problem.accuracy: Boier-Martin et al. §5's ladder (design/multilevel_edit.h), or the
// configured solver on the edit level alone.
struct AccuracyOptions {
  AccuracyMode mode = AccuracyMode::SingleLevel;
  int coarse_level = 0;                                      // where interactive solves directly
  ConstraintMode coarse_constraint_mode = ConstraintMode::Kkt;  // kkt | paper, on the coarse level
  // improved: gauss_seidel | sor (the paper's sweeps) | multigrid | multigrid_cg (cycles over
  // the levels below: the default, because sweeps leave the smooth error where the coarse
  // solve's prolongation put it — Figure 8's table in papers/boier-martin/README.md)
  std::string relaxation = "multigrid_cg";
  int relaxation_sweeps = 2;                // improved: per level; 10 when the relaxation is a sweep
  double relaxation_omega = 1.5;            // improved with sor
  int drag_steps = 1;                       // > 1: the handles dragged in this many steps
  bool multilevel() const { return mode != AccuracyMode::SingleLevel; }
  Accuracy ladder() const;  // the ladder's mode (multilevel() only)
};


//! One design step of a run: what changes before it is solved.
struct EditStepSpec {
  std::optional<double> scale;                    // every target scale × its configured value
  std::vector<std::pair<int, Vec3>> offsets;      // handle (constraint index) → its offset from rest
  std::optional<AccuracyMode> accuracy;           // §5's mode of this step (default problem.accuracy)
};

struct SurfaceEditSpec : RunBasics {
  std::string mesh_path;
  Representation representation = Representation::Mesh;
  int levels = 0;                          // uniform subdivision steps of the input mesh
  double max_memory_gb = 8.0;              // refuse refinements estimated to need more (refine_uniform)
  int remesh_base_faces = 0;               // > 0: remesh the input into a hierarchy with details
  bool remesh_triangle_base = false;       // remesh_base: triangles (a Catmull-Clark base not paired into quads)
  int edit_level = -1;                     // where the problem is solved (-1: the finest)
  double crease_angle = 0;                 // > 0: edges with a sharper dihedral angle (degrees) become creases
  ConstraintMode constraint_mode = ConstraintMode::Kkt;
  //! The energies and constraints as the design module takes them (pointers into this spec).
  EditTerms edit_terms() const;
  //! Set while a run solves its edit again with frame rows for its `auto` normals, after their
  //! tangent rows gave a reversed normal (run_one.cpp); not a config key.
  bool frame_rows_for_auto_normals = false;
  //! system_key, told apart when frame rows replace the tangent rows (another problem).
  std::string problem_key() const { return system_key + (frame_rows_for_auto_normals ? "|frame rows" : ""); }
  //! The QP modes: problem.<mode>, the options of that mode's solver (src/qp's schema).
  YAML::Node qp_options;
  Config qp_config() const;
  AccuracyOptions accuracy;
  RotationAwareOptions rotations;  // problem.rotation_iterations / rotation_tolerance
  //! Regional edits: how far the result may miss its constraints, × the bounding-box diagonal.
  double constraint_tolerance = kDefaultConstraintTolerance;
  BoundaryMode boundary = BoundaryMode::EdgeOnly;
  LoopWeights loop_weights = LoopWeights::Loop;
  CreaseMethod crease_method = CreaseMethod::Uniform;  // how semi-sharp creases decay
  //! The subdivision of a catmull-clark or loop representation.
  SubdivisionOptions subdivision() const;
  std::vector<EnergyTerm> energies;
  std::vector<ConstraintTerm> constraints;
  Formulation formulation = Formulation::Displacement;
  std::string solver_type;
  InitialGuess initial_guess = InitialGuess::Zero;
  std::shared_ptr<Solver> solver;
  OutputOptions output;
  //! The run's design steps, each solved by the session in turn (surface_edit_session.h): the
  //! `steps:` list, or problem.drag_steps' equal steps (one step of scale 1 without either).
  std::vector<EditStepSpec> steps;
  bool scheduled = false;  // `steps:` given
  std::string system_key;  // equal for runs that solve the same linear system

  //! \param search_dirs where relative input paths are looked up after the working directory.
  //! Every key a run of this kind reads, with its default and doc (document_keys).
  static std::vector<OptionDoc> keys();
  static SurfaceEditSpec from_config(const YAML::Node& run_config, const Components& c,
                             const std::vector<std::string>& search_dirs);
  //! The edit of a hierarchy given in memory (the Python module): `input` holds only
  //! `edit_level`; mesh_path stays empty and the hierarchy's own rules are recorded.
  static SurfaceEditSpec from_config(const YAML::Node& run_config, const Components& c, const MultiresSurface& given);
};

//! One item of `constraints:` (its type, options and region of influence), as a run reads it;
//! also a constraint a session adds. \throw InvalidConfig naming the key.
ConstraintTerm read_constraint_term(Config& item, const Components& c, Backend backend);

//! Whether the run's linear solver (the solver block) takes part in its solve.
bool solver_is_used(const SurfaceEditSpec& s);

}  // namespace fairshape
