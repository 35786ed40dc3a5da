// Atomic output: write to a temporary file beside the target, then rename over it, so a
// reader (or an interrupted run) only ever sees the old file or the complete new one.
#pragma once

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

namespace fairshape {

class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target, bool binary = false);
  ~AtomicFile();  // removes the temporary if commit() was not reached
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  const std::filesystem::path& temporary_path() const { return tmp_; }
  void commit();  // flush, fsync, rename; throws IOError

 private:
  std::filesystem::path target_, tmp_;
  std::ofstream out_;
  bool committed_ = false;
};

// Convenience: AtomicFile + a writer callback + commit.
void write_atomically(const std::filesystem::path& target,
                      const std::function<void(std::ostream&)>& write, bool binary = false);
std::filesystem::path temporary_sibling(const std::filesystem::path& target);
// Renames a finished temporary file or directory over target (fsyncing files first).
void commit_path(const std::filesystem::path& tmp, const std::filesystem::path& target);

}  // namespace fairshape
