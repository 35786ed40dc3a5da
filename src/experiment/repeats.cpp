#include "fairshape/experiment/repeats.h"

#include <algorithm>
#include <set>

#include "fairshape/experiment/metric_format.h"

namespace fairshape {
namespace fs = std::filesystem;

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Empty or non-numeric cells are skipped.
std::vector<double> values_of(const std::vector<MetricRow>& rows, const std::string& column) {
  std::vector<double> out;
  for (const auto& r : rows) {
    const auto it = r.find(column);
    if (it == r.end() || it->second.empty()) continue;
    try {
      out.push_back(std::stod(it->second));
    } catch (const std::exception&) {
    }
  }
  return out;
}

// The execution whose time_s is the median (the first when no row has one).
std::size_t median_execution(const std::vector<MetricRow>& rows) {
  std::vector<std::pair<double, std::size_t>> times;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const auto it = rows[k].find("time_s");
    if (it == rows[k].end() || it->second.empty()) return 0;
    try {
      times.emplace_back(std::stod(it->second), k);
    } catch (const std::exception&) {
      return 0;
    }
  }
  std::sort(times.begin(), times.end());
  return times[(times.size() - 1) / 2].second;
}

}  // namespace

std::vector<std::string> measured_by_name(const std::vector<std::string>& metric_columns) {
  std::vector<std::string> out;
  for (const auto& c : metric_columns)
    if (ends_with(c, "_s") || ends_with(c, "_mb")) out.push_back(c);
  return out;
}

MetricRow run_repeated(int repeat, const std::vector<std::string>& measured_columns, const RunOutputs& out,
                       const std::function<MetricRow(const RunOutputs&)>& execute,
                       const std::function<bool(const MetricRow&)>& succeeded) {
  std::vector<MetricRow> rows{execute(out)};
  rows.front()["repeat"] = "1";
  if (repeat <= 1 || !succeeded(rows.front())) return rows.front();
  const fs::path scratch = fs::path(out.dir) / ".fairshape" / ("repeat-" + out.run_id);
  std::string note;
  for (int k = 1; k < repeat; ++k) {
    fs::remove_all(scratch);
    create_run_folders(scratch.string());
    RunTables discarded;
    rows.push_back(execute({scratch.string(), out.run_id, out.single_run, &discarded}));
    if (!succeeded(rows.back())) {
      note = "repeat " + std::to_string(k + 1) + " ended " + rows.back()["termination"] + ": " + rows.back()["message"];
      rows.pop_back();
      break;
    }
  }
  fs::remove_all(scratch);
  MetricRow row = rows.front();
  const std::set<std::string> measured(measured_columns.begin(), measured_columns.end());
  // Every timing and memory column comes from one execution, the median one by time_s (the
  // lower middle of an even count), so the row's parts still add up to at most its time_s;
  // medians taken column by column would not.
  const MetricRow& middle = rows[median_execution(rows)];
  for (const auto& c : measured_columns) {
    if (ends_with(c, "_min_s")) continue;  // the minimum of its X_s column, below
    if (middle.count(c)) row[c] = middle.at(c);
    // solve_s beside solve_min_s: the fastest execution too.
    if (ends_with(c, "_s") && !ends_with(c, "_min_s")) {
      const std::string min_column = c.substr(0, c.size() - 2) + "_min_s";
      const std::vector<double> v = values_of(rows, c);
      if (row.count(min_column) && v.size() == rows.size()) row[min_column] = num(*std::min_element(v.begin(), v.end()));
    }
  }
  std::vector<std::string> differing;
  for (const auto& [c, value] : row) {
    if (measured.count(c) || ends_with(c, "_min_s") || c == "message" || c == "repeat") continue;
    for (const auto& r : rows)
      if (r.count(c) && r.at(c) != value) {
        differing.push_back(c);
        break;
      }
  }
  if (!differing.empty()) {
    std::string cols;
    for (const auto& c : differing) cols.append(cols.empty() ? "" : ", ").append(c);
    note.append(note.empty() ? "" : "; ").append("repeats disagree in " + cols + " (the first execution's values)");
  }
  row["repeat"] = std::to_string(rows.size());
  if (!note.empty()) row["message"] = row["message"].empty() ? note : row["message"] + "; " + note;
  return row;
}

}  // namespace fairshape
