#include "fairshape/experiment/kinds/surface_edit/system_export.h"

#include <filesystem>
#include <sstream>

#include "fairshape/core/atomic_file.h"
#include "fairshape/io/matrix_market.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/problem/least_squares.h"

namespace fs = std::filesystem;

namespace fairshape {
namespace {

void write_indices(const std::vector<int>& ids, const std::string& path) {
  write_atomically(path, [&](std::ostream& os) {
    for (int v : ids) os << v << '\n';
  });
}

}  // namespace

void write_edit_system(const EditProblem& p, const MultiresSurface& h, int level, const std::string& folder,
                       const Eigen::MatrixXd* paper_solution) {
  fs::create_directories(folder);
  const auto file = [&](const std::string& name) { return (fs::path(folder) / name).string(); };
  std::ostringstream readme;  // (a stream: GCC 12 warns falsely on "literal" + std::string chains)
  readme << "The assembled problem of this run (fairshape output.system), Matrix Market, 1-based in the files:\n"
            "  minimize 1/2 tr(D^T H D) - tr(g^T D) over the edit level's deformation D (n x 3, one column per coordinate)\n"
            "  subject to A D = C"
         << (p.constraints.coupled() ? " and A_coupled vec(D) = C_coupled (vec stacks x, y, z)" : "")
         << "\nH.mtx (n x n, symmetric: lower triangle), g.mtx (n x 3), A.mtx (m x n), C.mtx (m x 3)\n";
  write_matrix_market(p.H, file("H.mtx"), true);
  write_matrix_market(p.g, file("g.mtx"));
  write_matrix_market(p.constraints.A, file("A.mtx"));
  write_matrix_market(p.constraints.C, file("C.mtx"));
  if (p.constraints.coupled()) {
    write_matrix_market(p.constraints.A_coupled, file("A_coupled.mtx"));
    write_matrix_market(Eigen::MatrixXd(p.constraints.C_coupled), file("C_coupled.mtx"));
    readme << "A_coupled.mtx (q x 3n), C_coupled.mtx (q x 1)\n";
  }
  for (int l = 0; l < level; ++l) {
    std::ostringstream name;
    name << 'P' << l + 1 << ".mtx";
    write_matrix_market(h.subdivision_operator(l), file(name.str()));
    readme << name.str() << ": subdivision from level " << l << " to level " << l + 1 << " (P" << level
           << " ends at the edit level)\n";
  }
  if (paper_solution && !p.constraints.coupled()) {
    // The paper's split (Boier-Martin et al. §4.3): every vertex a constraint row reaches is
    // held at its minimum-norm value; the rest is the SPD system the linear solver saw.
    ConstrainedSystem s{p.H, p.g, reached_columns(p.constraints.A), {}};
    s.fixed_values.resize(static_cast<Eigen::Index>(s.fixed.size()), p.g.cols());
    for (std::size_t k = 0; k < s.fixed.size(); ++k) s.fixed_values.row(static_cast<Eigen::Index>(k)) = paper_solution->row(s.fixed[k]);
    const ReducedSystem r = reduce(s);
    write_matrix_market(r.A, file("A_free.mtx"), true);
    write_matrix_market(r.b, file("b_free.mtx"));
    write_matrix_market(r.fixed_values, file("D_constrained.mtx"));
    write_indices(r.free, file("free.txt"));
    write_indices(r.fixed, file("constrained.txt"));
    readme <<
        "Paper mode's reduced system: A_free.mtx (symmetric) D_free = b_free.mtx, the free vertices in free.txt and the\n"
        "constrained ones in constrained.txt (0-based vertex ids, one per line), held at D_constrained.mtx\n";
  }
  write_atomically(file("README.txt"), [&](std::ostream& os) { os << readme.str(); });
}

}  // namespace fairshape
