#include "fairshape/render/render_source.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <vector>

#include "fairshape/core/error.h"
#include "fairshape/core/input_file.h"
#include "fairshape/io/csv.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_convert.h"
#include "fairshape/io/vtk_io.h"

namespace fairshape::render {
namespace fs = std::filesystem;
namespace {

int parse_index(const std::string& text, const std::string& what) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    throw InvalidInput(what + ": '" + text + "' is not a number (0, 1, ...)");
  return std::stoi(text);
}

// `wanted` of `count` items (-1: the last).
int pick(int wanted, int count, const std::string& path, const std::string& what) {
  if (count == 0) throw InvalidInput(path + ": holds no " + what);
  if (wanted < 0) return count - 1;
  if (wanted >= count)
    throw InvalidInput(path + ": no " + what + " " + std::to_string(wanted) + " (it has " + what + "s 0.." +
                       std::to_string(count - 1) + ")");
  return wanted;
}

vtkSmartPointer<vtkPolyData> curve_polydata(const Polyline& c) {
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  for (int i = 0; i < c.n_points(); ++i) pts->InsertNextPoint(c.points(i, 0), c.points(i, 1), c.points(i, 2));
  pd->SetPoints(pts);
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell(c.closed ? c.n_points() + 1 : c.n_points());
  for (int i = 0; i < c.n_points(); ++i) lines->InsertCellPoint(i);
  if (c.closed) lines->InsertCellPoint(0);
  pd->SetLines(lines);
  return pd;
}

// A mesh file, or an OBJ holding only polylines (a curve run's output).
vtkSmartPointer<vtkPolyData> load_geometry_file(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".vtp") return io::internal::read_checked_polydata(path);
  if (ext == ".obj") {
    const MeshFile f = read_mesh_file(path);
    if (f.faces.empty() && !f.lines.empty()) return curve_polydata(read_polyline(path));
  }
  if (ext != ".obj" && ext != ".off" && ext != ".ply")
    throw IOError(path + ": cannot render '" + ext + "' (valid: .vtp, .vtm, .pvd, .obj, .off, .ply, or a result folder)");
  return io::internal::to_polydata(read_mesh(path), path);
}

// A result's overlay is the file beside it named <stem>_constraints.vtp (a run's, a step's).
std::string overlay_beside(const std::string& path) {
  const fs::path p(path), o = p.parent_path() / (p.stem().string() + "_constraints.vtp");
  return p.extension() == ".vtp" && fs::is_regular_file(o) ? o.string() : "";
}

// The (time, file) entries of a ParaView collection, files relative to it.
std::vector<std::string> pvd_files(const std::string& path) {
  const std::string text = read_regular_file(path, 16u << 20);  // a collection is a short list
  std::vector<std::string> files;
  for (std::size_t pos = text.find("<DataSet"); pos != std::string::npos; pos = text.find("<DataSet", pos + 1)) {
    const std::size_t end = text.find('>', pos);
    const std::size_t f = text.find("file=\"", pos);
    if (end == std::string::npos || f == std::string::npos || f > end) throw InvalidInput(path + ": a DataSet without file=");
    const std::size_t close = text.find('"', f + 6);
    files.push_back((fs::path(path).parent_path() / text.substr(f + 6, close - f - 6)).string());
  }
  return files;
}

// A result folder's runs: id -> its swept parameters ("key=value, ..."; runs.csv's columns
// between run_id and implementation), in the table's order.
std::vector<std::pair<std::string, std::string>> runs_of(const fs::path& dir) {
  std::vector<std::pair<std::string, std::string>> runs;
  if (!fs::exists(dir / "runs.csv")) return runs;
  const CsvTable t = read_csv((dir / "runs.csv").string(), true);
  const int id = t.column("run_id"), end = t.column("implementation");
  if (id < 0) return runs;
  for (const auto& row : t.rows) {
    std::string params;
    for (int c = id + 1; c < end; ++c)
      params.append(params.empty() ? "" : ", ").append(t.header[static_cast<std::size_t>(c)]).append("=").append(row[static_cast<std::size_t>(c)]);
    runs.emplace_back(row[static_cast<std::size_t>(id)], params);
  }
  return runs;
}

// The geometry a run left: its result .vtp, a curve run's last final stage, or final.obj.
RenderSource run_source(const fs::path& dir, std::string run) {
  const auto runs = runs_of(dir);  // runs.csv read once
  std::vector<std::string> ids;
  for (const auto& r : runs) ids.push_back(r.first);
  if (run.empty()) {
    if (ids.size() > 1) {
      std::string list;
      for (std::size_t k = 0; k < std::min<std::size_t>(ids.size(), 8); ++k) list.append(k ? ", " : "").append(ids[k]);
      throw InvalidInput(dir.string() + ": holds " + std::to_string(ids.size()) + " runs; name one with --run ID or " +
                         dir.string() + "@ID (" + list + (ids.size() > 8 ? ", ..." : "") + ")");
    }
    if (ids.size() == 1) run = ids.front();
    if (ids.empty() && !fs::exists(dir / "final.obj"))
      throw InvalidInput(dir.string() + ": not a result folder (no runs.csv, no final.obj); name a run with " +
                         dir.string() + "@ID for a folder whose vtk/ holds <ID>.vtp");
  } else if (!ids.empty() && std::find(ids.begin(), ids.end(), run) == ids.end()) {
    throw InvalidInput(dir.string() + ": no run '" + run + "' in its runs.csv");
  }
  const fs::path vtk = dir / "vtk";
  std::vector<fs::path> candidates{vtk / (run + ".vtp")};
  std::vector<fs::path> curve_finals;
  if (fs::is_directory(vtk))
    for (const auto& e : fs::directory_iterator(vtk)) {
      const std::string name = e.path().filename().string();
      if (name.rfind(run + "_edit", 0) == 0 && name.size() > 10 && name.substr(name.size() - 10) == "_final.vtp")
        curve_finals.push_back(e.path());
    }
  std::sort(curve_finals.begin(), curve_finals.end());
  if (!curve_finals.empty()) candidates.push_back(curve_finals.back());
  candidates.push_back(dir / "final" / (run + ".obj"));
  candidates.push_back(dir / "final.obj");
  for (const fs::path& c : candidates)
    if (!run.empty() || c == dir / "final.obj")
      if (fs::is_regular_file(c)) {
        RenderSource s{c.string(), load_geometry_file(c.string()), "", "", ""};
        const fs::path levels = vtk / (run + "_levels.vtm");
        if (fs::is_regular_file(levels)) s.levels_path = levels.string();
        s.overlay_path = overlay_beside(c.string());
        for (const auto& [rid, params] : runs)
          if (rid == run) s.parameters = params;
        return s;
      }
  throw IOError(dir.string() + ": no geometry for run '" + run + "' (looked for vtk/<run>.vtp, a curve's final stage, "
                "final/<run>.obj and final.obj)");
}

}  // namespace

vtkSmartPointer<vtkPolyData> load_overlay(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".vtp") return io::internal::read_checked_polydata(path);
  if (ext != ".obj") throw IOError(path + ": an overlay is a .vtp or an .obj of polylines or points");
  const MeshFile f = read_mesh_file(path);
  if (!f.lines.empty()) return curve_polydata(read_polyline(path));
  if (f.vertices.rows() == 0) throw InvalidInput(path + ": an overlay with no points");
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  for (Eigen::Index i = 0; i < f.vertices.rows(); ++i) pts->InsertNextPoint(f.vertices(i, 0), f.vertices(i, 1), f.vertices(i, 2));
  pd->SetPoints(pts);
  return pd;
}

vtkSmartPointer<vtkPolyData> load_level(const std::string& levels_path, int level) {
  const std::vector<SurfaceMesh> blocks = read_vtm(levels_path);
  const int b = pick(level, static_cast<int>(blocks.size()), levels_path, "level");
  return io::internal::to_polydata(blocks[static_cast<std::size_t>(b)], levels_path);
}

RenderSource load_render_source(const std::string& spec, const SourceChoice& choice) {
  std::string path = spec, selector;
  SourceChoice c = choice;
  if (const std::size_t at = spec.rfind('@'); at != std::string::npos && !fs::exists(spec)) {
    path = spec.substr(0, at);
    selector = spec.substr(at + 1);
  }
  const auto conflict = [&](const std::string& option, const std::string& value) {
    throw InvalidInput(spec + ": '@" + selector + "' and " + option + " " + value + " choose differently: give one");
  };
  if (fs::is_directory(path)) {
    if (!selector.empty() && !c.run.empty() && c.run != selector) conflict("--run", c.run);
    if (!selector.empty()) c.run = selector;
    return run_source(path, c.run);
  }
  if (!fs::exists(path)) throw IOError(path + ": no such file or folder");
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".vtm") {
    if (!selector.empty()) {
      const int b = parse_index(selector, path + "@");
      if (c.block >= 0 && c.block != b) conflict("--block", std::to_string(c.block));
      c.block = b;
    }
    return {path, load_level(path, c.block), path, "", ""};
  }
  if (ext == ".pvd") {
    if (!selector.empty()) {
      const int k = parse_index(selector, path + "@");
      if (c.step >= 0 && c.step != k) conflict("--step", std::to_string(c.step));
      c.step = k;
    }
    const std::vector<std::string> files = pvd_files(path);
    const std::string& file = files[static_cast<std::size_t>(pick(c.step, static_cast<int>(files.size()), path, "step"))];
    return {file, load_geometry_file(file), "", overlay_beside(file), ""};
  }
  if (!selector.empty())
    throw InvalidInput(spec + ": '@" + selector + "' chooses a block of a .vtm, a step of a .pvd or a run of a folder");
  return {path, load_geometry_file(path), "", overlay_beside(path), ""};
}

}  // namespace fairshape::render
