#include "experiment/run_outputs.h"

#include <cctype>
#include <filesystem>

namespace fairshape {
namespace fs = std::filesystem;

std::string RunOutputs::final_path() const {
  if (single_run) return (fs::path(dir) / "final.obj").string();
  fs::create_directories(fs::path(dir) / "final");
  return (fs::path(dir) / "final" / (run_id + ".obj")).string();
}

std::string file_name_part(const std::string& name) {
  std::string out = name;
  for (char& ch : out)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '.' && ch != '_' && ch != '-') ch = '_';
  return out;
}

void create_run_folders(const std::string& dir) { fs::create_directories(fs::path(dir) / "vtk"); }

}  // namespace fairshape
