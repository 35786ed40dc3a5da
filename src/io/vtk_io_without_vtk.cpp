// vtk_io.h for a fairshape configured with FAIRSHAPE_WITH_VTK=OFF: every VTK file is refused
// with how to get it, so a reader or writer chosen by a file's extension fails clearly instead
// of at link time or silently.
#include "fairshape/core/error.h"
#include "fairshape/io/vtk_io.h"

namespace fairshape {
namespace {

[[noreturn]] void without_vtk(const std::string& path) {
  throw InvalidInput(path + ": VTK files (.vtp, .vtm, .pvd) need a fairshape built with VTK "
                     "(FAIRSHAPE_WITH_VTK=ON, Debian's libvtk9-dev); use .obj, .off or .ply");
}

}  // namespace

void write_vtp(const SurfaceMesh&, const std::string& path) { without_vtk(path); }
void write_vtp(const Polyline&, const DataArrays&, const std::string& path) { without_vtk(path); }
void write_vtp(const MatrixX3&, const std::vector<std::vector<int>>&, const DataArrays&, const std::string& path) {
  without_vtk(path);
}
SurfaceMesh read_vtp(const std::string& path) { without_vtk(path); }
void write_vtm(const std::vector<NamedMesh>&, const std::string& path) { without_vtk(path); }
std::vector<SurfaceMesh> read_vtm(const std::string& path) { without_vtk(path); }
void write_pvd(const std::vector<std::pair<double, std::string>>&, const std::string& path) { without_vtk(path); }

}  // namespace fairshape
