#include "fairshape/experiment/run_outputs.h"

#include <cctype>
#include <filesystem>
#include <map>

#include "fairshape/core/error.h"

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

void check_distinct_file_names(const std::vector<std::pair<std::string, std::string>>& keyed_names) {
  std::map<std::string, std::string> first_key;
  for (const auto& [key, name] : keyed_names) {
    const auto [it, fresh] = first_key.emplace(file_name_part(name), key);
    if (!fresh)
      throw InvalidConfig(key + ": '" + name + "' would be written to the same file as " + it->second + " (file names keep letters, " +
                          "digits, '.', '_' and '-'; other characters become '_'): choose another name");
  }
}

void create_run_folders(const std::string& dir) { fs::create_directories(fs::path(dir) / "vtk"); }

}  // namespace fairshape
