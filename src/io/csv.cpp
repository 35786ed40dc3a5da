#include "fairshape/io/csv.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/error.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape {

int CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  return -1;
}

std::string csv_escape(std::string_view f) {
  if (f.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(f);
  std::string out = "\"";
  for (char c : f) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

std::string csv_record(const std::vector<std::string>& fields) {
  std::string out;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) out += ',';
    out += csv_escape(fields[i]);
  }
  return out + "\r\n";
}

CsvTable parse_csv(std::string_view text, const std::string& name, bool drop_partial_tail) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> rec;
  std::string field;
  bool quoted = false, field_started = false;
  long line = 1;
  std::size_t i = 0;
  auto end_record = [&] {
    rec.push_back(std::move(field));
    field.clear();
    records.push_back(std::move(rec));
    rec.clear();
    field_started = false;
  };
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') { field += '"'; ++i; }
      else if (c == '"') quoted = false;
      else { if (c == '\n') ++line; field += c; }
    } else if (c == '"') {
      if (!field.empty()) throw ParseError(name, line, "quote inside an unquoted field");
      quoted = field_started = true;
    } else if (c == ',') {
      rec.push_back(std::move(field));
      field.clear();
      field_started = true;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      end_record();
      ++line;
    } else {
      field += c;
      field_started = true;
    }
  }
  if (quoted || field_started || !rec.empty()) {  // no final line break
    if (!drop_partial_tail) {
      if (quoted) throw ParseError(name, line, "unterminated quoted field");
      end_record();
    }
  }
  CsvTable t;
  if (records.empty()) return t;
  t.header = std::move(records.front());
  for (std::size_t r = 1; r < records.size(); ++r) {
    if (records[r].size() == 1 && records[r][0].empty()) continue;  // blank line
    if (records[r].size() != t.header.size())
      throw ParseError(name, 0, "record " + std::to_string(r) + " has " + std::to_string(records[r].size()) +
                                    " fields, the header has " + std::to_string(t.header.size()));
    t.rows.push_back(std::move(records[r]));
  }
  return t;
}

CsvTable read_csv(const std::string& path, bool drop_partial_tail) {
  return parse_csv(io::internal::read_whole_file(path), path, drop_partial_tail);
}

void write_csv(const CsvTable& table, const std::string& path) {
  write_atomically(path, [&](std::ostream& os) {
    os << csv_record(table.header);
    for (const auto& r : table.rows) os << csv_record(r);
  });
}

CsvAppender::CsvAppender(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IOError(path + ": cannot open for appending: " + std::strerror(errno));
}

CsvAppender::~CsvAppender() {
  if (fd_ >= 0) ::close(fd_);
}

void CsvAppender::append(const std::vector<std::string>& fields) { write_locked(csv_record(fields), false, ""); }

void CsvAppender::append_table_rows(const std::vector<std::string>& header,
                                    const std::vector<std::vector<std::string>>& rows) {
  std::string records;
  for (const auto& r : rows) records += csv_record(r);
  write_locked(records, true, csv_record(header));
}

void CsvAppender::write_locked(const std::string& records, bool header_if_empty, const std::string& header) {
  ::flock(fd_, LOCK_EX);
  struct stat st {};
  const bool empty = ::fstat(fd_, &st) == 0 && st.st_size == 0;
  const std::string out = header_if_empty && empty ? header + records : records;
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t n = ::write(fd_, out.data() + done, out.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = errno;
      // Never leave half a record behind: cut the file back to where this write began.
      if (done > 0 && ::ftruncate(fd_, static_cast<off_t>(::lseek(fd_, 0, SEEK_END) - done)) != 0) {}
      ::flock(fd_, LOCK_UN);
      throw IOError(path_ + ": append failed: " + std::strerror(n < 0 ? err : ENOSPC));
    }
    done += static_cast<std::size_t>(n);
  }
  const bool synced = ::fdatasync(fd_) == 0;
  ::flock(fd_, LOCK_UN);
  if (!synced) throw IOError(path_ + ": append not durable: " + std::strerror(errno));
}

void truncate_partial_tail(const std::string& path) {
  const std::string text = io::internal::read_whole_file(path);
  if (text.empty() || text.back() == '\n') return;
  const std::size_t last = text.find_last_of('\n');
  std::filesystem::resize_file(path, last == std::string::npos ? 0 : last + 1);
}

}  // namespace fairshape
