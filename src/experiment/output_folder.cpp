#include "fairshape/experiment/output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstring>
#include <fstream>

#include "fairshape/core/error.h"
#include "fairshape/core/summary.h"
#include "fairshape/experiment/run_metadata.h"
#include "fairshape/io/csv.h"

namespace fairshape {
namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse_link(const fs::path& link) {
  throw InvalidConfig(link.string() + ": a symbolic link inside the output folder; fairshape writes nothing outside " +
                      "--out and would write through it: remove the link, or use another --out");
}

// The writers follow symbolic links (a linked vtk/ or final/ puts results elsewhere, a linked
// table is appended to wherever it points): any link inside the folder is refused before
// anything is written. The folder itself may be a link: --out names where results go.
void refuse_links_inside(const fs::path& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    if (it->is_symlink()) refuse_link(it->path());
  if (ec) throw InvalidConfig(dir.string() + ": cannot list the folder: " + ec.message());
}

}  // namespace

OutputFolder::OutputFolder(fs::path dir) : dir_(std::move(dir)) {
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
    throw InvalidConfig("--out " + dir_.string() + ": exists and is not a folder");
  fs::create_directories(dir_, ec);
  if (ec) throw InvalidConfig("--out " + dir_.string() + ": cannot create the folder: " + ec.message());
  const fs::path lock = dir_ / ".lock";
  // O_NOFOLLOW: a .lock that is a symbolic link is refused before anything is written through
  // it (even by a run refused later); O_NONBLOCK: a FIFO named .lock does not hang the open.
  lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
  if (lock_fd_ < 0 && errno == ELOOP) refuse_link(lock);
  if (lock_fd_ < 0) throw InvalidConfig(dir_.string() + ": cannot write to the folder: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(lock_fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw InvalidConfig(lock.string() + ": not a regular file (fairshape's lock file): remove it, or use another --out");
  }
  if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
    char buf[32] = {};
    const ssize_t n = ::pread(lock_fd_, buf, sizeof buf - 1, 0);
    std::string holder(buf, n > 0 ? static_cast<std::size_t>(n) : 0);
    holder = holder.substr(0, holder.find('\n'));
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw InvalidConfig(dir_.string() + ": another fairshape run is writing to this folder" +
                        (holder.empty() ? "" : " (pid " + holder + ")") +
                        "; wait for it, or use another --out");
  }
  try {  // once this run holds the folder: another run may be creating and removing files in it
    refuse_links_inside(dir_);
  } catch (...) {
    ::close(lock_fd_);
    lock_fd_ = -1;
    throw;
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(lock_fd_, 0) == 0 && ::write(lock_fd_, pid.data(), pid.size()) < 0) {}
}

OutputFolder::~OutputFolder() {
  if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void OutputFolder::clear_results() {
  for (const auto& entry : fs::directory_iterator(dir_)) {
    const std::string name = entry.path().filename().string();
    if (name == ".lock") continue;
    fs::remove_all(entry.path());
  }
}

void OutputFolder::remove_temporaries() const {
  std::error_code ec;
  std::vector<fs::path> doomed;
  for (auto it = fs::recursive_directory_iterator(dir_, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.find(".tmp.") != std::string::npos) doomed.push_back(it->path());
  }
  for (const auto& p : doomed) fs::remove_all(p, ec);
}

std::set<std::string> OutputFolder::finished_runs(const TableLayout& layout) const {
  std::set<std::string> done;
  if (!fs::exists(runs_csv())) return done;
  truncate_partial_tail(runs_csv().string());
  const CsvTable t = read_csv(runs_csv().string());
  if (t.header.empty()) return done;
  if (t.header != layout.runs_columns)
    throw InvalidConfig(runs_csv().string() + ": its columns differ from this config's; resume it with the same "
                        "config and --set options, or use another --out");
  for (const auto& r : t.rows) done.insert(r[0]);
  return done;
}

std::size_t OutputFolder::drop_failed_runs(bool only_output_failures) {
  if (!fs::exists(runs_csv())) return 0;
  CsvTable t = read_csv(runs_csv().string(), true);
  const int term = t.column("termination");
  if (term < 0) return 0;
  const std::size_t before = t.rows.size();
  std::erase_if(t.rows, [&](const std::vector<std::string>& r) {
    try {
      const Termination t = termination_from_string(r[term]);
      return only_output_failures ? t == Termination::OutputFailed : !is_success(t);
    } catch (const Error&) {
      return true;  // a termination this build does not know: run it again
    }
  });
  if (t.rows.size() != before) write_csv(t, runs_csv().string());
  return before - t.rows.size();
}

std::set<std::string> recorded_runs(const fs::path& dir) {
  std::set<std::string> ids;
  const fs::path runs = table_path(dir, "runs");
  if (fs::exists(runs))
    for (const auto& r : read_csv(runs.string(), true).rows) ids.insert(r[0]);
  return ids;
}

void OutputFolder::roll_back_orphan_rows(const TableLayout& layout, const std::set<std::string>& also) const {
  const std::set<std::string> done = recorded_runs(dir_);
  for (const auto& schema : layout.tables) {
    const fs::path path = table_csv(schema.name);
    if (!fs::exists(path)) continue;
    CsvTable t = read_csv(path.string(), true);
    if (t.header.empty()) continue;
    if (t.header != schema.columns)
      throw InvalidConfig(path.string() + ": its columns differ from this config's; resume it with the same "
                          "config and --set options, or use another --out");
    std::erase_if(t.rows, [&](const std::vector<std::string>& r) { return !done.count(r[0]) || also.count(r[0]); });
    // Rewritten also when a killed writer left a partial last record behind.
    write_csv(t, path.string());
  }
}

void commit_run(const fs::path& dir, const TableLayout& layout, const std::vector<std::string>& key_fields,
                const std::vector<std::string>& runs_row, const RunTables& tables) {
  for (const auto& table : tables.rows()) {
    const std::string& name = table.first;
    const auto& rows = table.second;
    const auto schema = std::find_if(layout.tables.begin(), layout.tables.end(),
                                     [&name](const TableSchema& s) { return s.name == name; });
    FAIRSHAPE_ASSERT(schema != layout.tables.end(), "a run wrote to table '" + name + "' its kind did not declare");
    std::vector<std::vector<std::string>> full;
    for (const auto& r : rows) {
      FAIRSHAPE_ASSERT(key_fields.size() + r.size() == schema->columns.size(), "row width differs from table " + name);
      full.push_back(key_fields);
      full.back().insert(full.back().end(), r.begin(), r.end());
    }
    CsvAppender(table_path(dir, name).string()).append_table_rows(schema->columns, full);
  }
  CsvAppender(table_path(dir, "runs").string()).append_table_rows(layout.runs_columns, {runs_row});
}

fs::path default_out_dir(const std::string& name) {
  const fs::path base = fs::path("results") / name;
  const fs::path dir = base / (utc_timestamp("%Y%m%d-%H%M%S") + "_" + git_short_sha());
  fs::create_directories(dir);
  const fs::path link = base / "latest";
  std::error_code ec;
  if (fs::is_symlink(fs::symlink_status(link, ec))) fs::remove(link, ec);
  if (!fs::exists(fs::symlink_status(link, ec))) fs::create_directory_symlink(dir.filename(), link, ec);
  return dir;
}

}  // namespace fairshape
