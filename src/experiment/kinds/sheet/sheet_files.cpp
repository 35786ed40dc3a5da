#include "fairshape/experiment/kinds/sheet/sheet_files.h"

#include <filesystem>
#include <memory>

#include "fairshape/bspline/sheet_file.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/run_outputs.h"

namespace fairshape {
namespace fs = std::filesystem;


SheetSpec read_sheet_from_file(Config& c, const std::vector<std::string>& search_dirs) {
  SheetSpec s;
  s.name = c.get<std::string>("name", "sheet", "name constraints and curves refer to");
  const std::string given = c.require<std::string>("file", "a saved sheet (.sheet) to start from");
  s.file = c.documenting() ? given : resolve_input(given, search_dirs, c.key_path("file"));
  // The file holds the exact surface; a second description of it could only disagree.
  for (const char* key : {"spans", "degree", "geometry", "size", "origin", "u_axis", "v_axis"})
    if (c.has(key))
      throw InvalidConfig(c.key_path(key) + ": comes from the file '" + given +
                          "' (a sheet read with `file:` keeps the shape it was saved with; `refine` may refine it further)");
  for (const auto& r : c.get<std::vector<std::vector<int>>>("refine", {}, "spans refined up front: [[level, i, j], ...]")) {
    if (r.size() != 3) throw InvalidConfig(c.key_path("refine") + ": expected [level, i, j] entries");
    s.refine.push_back({r[0], r[1], r[2]});
  }
  c.check_no_unknown_keys();
  try {
    s.loaded = std::make_shared<const bspline::VariationalSheet>(bspline::load_sheet(s.file));
  } catch (const Error& e) {
    throw InvalidConfig(c.key_path("file") + ": " + e.what());
  }
  s.shape = s.loaded->surface().shape();
  if (!s.refine.empty()) {
    // Spans the file's layers do not have are a config error, found before anything runs.
    bspline::VariationalSheet trial = *s.loaded;
    try {
      trial.refine(s.refine);
    } catch (const InvalidInput& e) {
      throw InvalidConfig(c.key_path("refine") + ": " + e.what() + " (of the sheet in " + given + ")");
    }
  }
  return s;
}

bspline::VariationalSheet initial_sheet(const SheetSpec& s) {
  if (s.loaded) return *s.loaded;
  const bspline::HierarchicalSurface surface(s.shape);
  return bspline::VariationalSheet(s.shape, bspline::initial_coefficients(s.placement, surface));
}

std::vector<std::string> sheet_input_files(const SheetRunSpec& spec) {
  std::vector<std::string> files;
  for (const SheetSpec& s : spec.sheets)
    if (!s.file.empty()) files.push_back(s.file);
  return files;
}

void write_sheet_files(const RunOutputs& out, const std::vector<SheetSpec>& specs,
                       const std::vector<bspline::VariationalSheet>& sheets, int step) {
  const fs::path dir = fs::path(out.dir) / "sheets";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw OutputError(dir.string() + ": cannot create the folder: " + ec.message());
  const std::string prefix = out.run_id + (step < 0 ? "" : "_step" + std::to_string(step)) + "_";
  for (std::size_t k = 0; k < sheets.size(); ++k)
    bspline::save_sheet(sheets[k], (dir / (prefix + file_name_part(specs[k].name) + bspline::kSheetFileExtension)).string());
}

}  // namespace fairshape
