// An experiment's output folder as the harness keeps it: one writer at a time (an advisory
// lock), tables whose rows for a run are committed together (the run's rows of the other
// tables first, its runs.csv row last, so a killed run leaves at most rows that the next
// start rolls back), no temporaries left behind, and nothing written outside it.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "fairshape/experiment/run_outputs.h"

namespace fairshape {

//! The column layout of every table of one experiment: run_id, the swept parameters and the
//! kind's identity columns come first in each.
struct TableLayout {
  std::vector<std::string> key_columns;  // run_id, swept parameters, identity columns
  std::vector<std::string> runs_columns;  // key_columns + the kind's metrics
  std::vector<TableSchema> tables;        // the kind's other tables, full columns
};

//! Where a table of an output folder lives: `<dir>/<name>.csv` (runs.csv is the table "runs").
inline std::filesystem::path table_path(const std::filesystem::path& dir, const std::string& name) {
  return dir / (name + ".csv");
}

class OutputFolder {
 public:
  //! Takes the folder's lock. \throw InvalidConfig when another process holds it.
  explicit OutputFolder(std::filesystem::path dir);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path runs_csv() const { return table_path(dir_, "runs"); }
  std::filesystem::path table_csv(const std::string& name) const { return table_path(dir_, name); }

  //! Removes every result a previous sweep left (for --force).
  void clear_results();
  //! Removes temporaries left by killed writers (anything named *.tmp.<pid>.<n>).
  void remove_temporaries() const;
  //! The run_ids of runs.csv (after cutting a partly written last row). \throw InvalidConfig
  //! when its columns differ from `layout`'s.
  std::set<std::string> finished_runs(const TableLayout& layout) const;
  //! Removes runs.csv rows whose termination is not a success; returns how many.
  //! `only_output_failures`: only the runs whose outputs could not be written (output_failed).
  std::size_t drop_failed_runs(bool only_output_failures = false);
  //! Removes the rows of the other tables whose run has no runs.csv row (a run killed
  //! between committing its table rows and its row), and those of the runs in `also`
  //! (crashed runs, whose row the supervisor wrote). Only while no worker writes.
  void roll_back_orphan_rows(const TableLayout& layout, const std::set<std::string>& also = {}) const;

 private:
  std::filesystem::path dir_;
  int lock_fd_ = -1;
};

//! The run_ids runs.csv in `dir` holds (a partly written last row left out).
std::set<std::string> recorded_runs(const std::filesystem::path& dir);

//! Appends one run to the tables in `dir`: its rows of the other tables, then its runs.csv row.
void commit_run(const std::filesystem::path& dir, const TableLayout& layout, const std::vector<std::string>& key_fields,
                const std::vector<std::string>& runs_row, const RunTables& tables);

//! results/<name>/<UTC time>_<commit>, with results/<name>/latest pointing at it (a symlink is
//! replaced; anything else named latest is left alone).
std::filesystem::path default_out_dir(const std::string& name);

}  // namespace fairshape
