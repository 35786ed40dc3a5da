#include "fairshape/core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>

#include "fairshape/core/error.h"

namespace fairshape {
namespace fs = std::filesystem;

fs::path temporary_sibling(const fs::path& target) {
  static std::atomic<int> counter{0};
  fs::path tmp = target;
  tmp += ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  return tmp;
}

static void fsync_file(const fs::path& p) {
  int fd = ::open(p.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

void commit_path(const fs::path& tmp, const fs::path& target) {
  if (fs::is_regular_file(tmp)) fsync_file(tmp);
  std::error_code ec;
  if (fs::is_directory(tmp) && fs::exists(target)) fs::remove_all(target, ec);
  fs::rename(tmp, target, ec);
  if (ec) throw OutputError(target.string() + ": cannot move finished output into place: " + ec.message());
}

AtomicFile::AtomicFile(fs::path target, bool binary)
    : target_(std::move(target)), tmp_(temporary_sibling(target_)) {
  if (target_.has_parent_path() && !fs::exists(target_.parent_path())) {
    throw OutputError(target_.string() + ": cannot write: folder '" +
                  target_.parent_path().string() + "' does not exist");
  }
  out_.open(tmp_, binary ? std::ios::out | std::ios::binary : std::ios::out);
  if (!out_) throw OutputError(target_.string() + ": cannot open for writing");
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    out_.close();
    std::error_code ec;
    fs::remove(tmp_, ec);
  }
}

void AtomicFile::commit() {
  out_.flush();
  if (!out_) throw OutputError(target_.string() + ": write failed (disk full?)");
  out_.close();
  commit_path(tmp_, target_);
  committed_ = true;
}

void write_atomically(const fs::path& target, const std::function<void(std::ostream&)>& write,
                      bool binary) {
  AtomicFile f(target, binary);
  write(f.stream());
  f.commit();
}

}  // namespace fairshape
