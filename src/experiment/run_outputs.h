// What one run hands back to the harness besides its runs.csv row: the rows of its other
// tables (buffered, so the harness writes them together with the run's row and a killed run
// never leaves half of them behind) and where its geometry goes.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace fairshape {

using MetricRow = std::map<std::string, std::string>;

//! A table a run kind writes beside runs.csv: `<name>.csv` with these columns after the
//! columns the harness puts first (run_id, the swept parameters, the solver columns).
struct TableSchema {
  std::string name;                  // "iterations", "steps", "cells"
  std::vector<std::string> columns;  // the kind's own columns
};

class RunTables {
 public:
  //! One row of `table` (its kind's own columns, in schema order).
  void add(const std::string& table, std::vector<std::string> row) { rows_[table].push_back(std::move(row)); }
  const std::map<std::string, std::vector<std::vector<std::string>>>& rows() const { return rows_; }

 private:
  std::map<std::string, std::vector<std::vector<std::string>>> rows_;
};

//! A user-given name (a sheet, a curve, a feature) as part of a file name: anything but letters,
//! digits, '.', '_' and '-' becomes '_', so no name ("../x", "a/b") can place a file outside the
//! run's folders.
std::string file_name_part(const std::string& name);

//! (key, name) pairs of one kind of output (sheets, curves, features). \throw InvalidConfig
//! naming both keys when two names make the same file-name part ("a/b" and "a_b"): one file
//! would silently overwrite the other.
void check_distinct_file_names(const std::vector<std::pair<std::string, std::string>>& keyed_names);

//! The folders every run may write into (vtk/), created under an output folder.
void create_run_folders(const std::string& dir);

struct RunOutputs {
  std::string dir;  // the experiment's output folder
  std::string run_id;
  bool single_run = true;            // final.obj, or final/<run_id>.obj in a sweep
  RunTables* tables = nullptr;       // null: the run's table rows are not kept
  //! Where the run's final geometry goes (creates final/ in a sweep).
  std::string final_path() const;
  void add_row(const std::string& table, std::vector<std::string> row) const {
    if (tables) tables->add(table, std::move(row));
  }
};

}  // namespace fairshape
