// RFC 4180 CSV: fields quoted when they hold a comma, quote, CR or LF; records end in CRLF.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace fairshape {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  int column(const std::string& name) const;  // -1 if absent
};

std::string csv_escape(std::string_view field);
std::string csv_record(const std::vector<std::string>& fields);  // with the CRLF
//! Parses RFC 4180 (CRLF or LF). An unterminated final record (a writer killed mid-row)
//! is dropped when drop_partial_tail is set, and is an error otherwise.
CsvTable parse_csv(std::string_view text, const std::string& name, bool drop_partial_tail = false);
CsvTable read_csv(const std::string& path, bool drop_partial_tail = false);
void write_csv(const CsvTable& table, const std::string& path);  // atomic

// Appends whole records to a CSV that grows while a sweep runs. Each record goes out in one
// write() under an exclusive lock, so concurrent workers never interleave, then fdatasync:
// a crash loses at most the record being written.
class CsvAppender {
 public:
  explicit CsvAppender(const std::string& path);
  ~CsvAppender();
  CsvAppender(const CsvAppender&) = delete;
  CsvAppender& operator=(const CsvAppender&) = delete;
  void append(const std::vector<std::string>& fields);
  //! Appends `rows` in one write under the lock, preceded by `header` when the file is empty
  //! (so the first of several concurrent writers creates the table, the others only add rows).
  void append_table_rows(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows);

 private:
  void write_locked(const std::string& records, bool header_if_empty, const std::string& header);
  std::string path_;
  int fd_ = -1;
};

// Cuts an unterminated final record off a file (left by a killed writer).
void truncate_partial_tail(const std::string& path);

}  // namespace fairshape
