#include "fairshape/energy/ring_coupling.h"

#include <cstdint>
#include <limits>

#include "fairshape/core/error.h"

namespace fairshape {

void check_ring_coupling(const SurfaceMesh& mesh, const std::string& energy) {
  std::int64_t entries = 0;
  for (int v = 0; v < mesh.n_vertices(); ++v) {
    if (mesh.is_isolated(v)) continue;
    const int valence = mesh.valence(v);
    if (valence > kMaxCoupledValence)
      throw InvalidInput(energy + ": vertex " + std::to_string(v) + " has valence " + std::to_string(valence) +
                         "; the energy couples its whole one-ring ((valence + 1)^2 entries of H) and accepts valence up to " +
                         std::to_string(kMaxCoupledValence) + " (split the fan, or use membrane)");
    entries += static_cast<std::int64_t>(valence + 1) * (valence + 1);
  }
  if (entries > std::numeric_limits<int>::max())
    throw InvalidInput(energy + ": H would hold about " + std::to_string(entries) +
                       " entries, more than a 32-bit sparse matrix can index");
}

}  // namespace fairshape
