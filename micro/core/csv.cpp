#include "core/csv.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "core/files.hpp"

namespace oitbench {

std::string csv_quote(const std::string& f) {
  if (f.find_first_of(",\"\n\r") == std::string::npos) return f;
  std::string q = "\"";
  for (char c : f) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string line;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    line += csv_quote(fields[i]);
  }
  return line + "\n";
}

std::vector<std::vector<std::string>> csv_parse(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, any = false;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
      continue;
    }
    if (c == '"') {
      quoted = true;
      any = true;
    } else if (c == ',') {
      row.push_back(std::move(field));
      field.clear();
      any = true;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      if (any || !field.empty()) {
        row.push_back(std::move(field));
        rows.push_back(std::move(row));
      }
      row.clear();
      field.clear();
      any = false;
    } else {
      field += c;
      any = true;
    }
  }
  if (quoted) throw CsvError("CSV ends inside a quoted field");
  if (any || !field.empty()) {
    row.push_back(std::move(field));
    rows.push_back(std::move(row));
  }
  return rows;
}

namespace {
void write_all(int fd, const std::string& s, const std::string& path) {
  size_t off = 0;
  while (off < s.size()) {
    ssize_t n = ::write(fd, s.data() + off, s.size() - off);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw CsvError("cannot write " + path + ": " + std::strerror(errno));
    off += static_cast<size_t>(n);
  }
}
}  // namespace

AppendAction csv_append_action(const std::string& head, unsigned long long size, char last_byte,
                               const std::vector<std::string>& columns, const std::string& path,
                               const std::string& option) {
  if (size == 0) return AppendAction::WriteHeader;
  const std::string where = option + " " + path + ": ";
  const std::string keep = "; it is left as it is: write to a new file";
  auto eol = head.find('\n');
  std::string first = head.substr(0, eol);
  if (!first.empty() && first.back() == '\r') first.pop_back();
  if (first.empty())
    throw CsvError(where + "the file's first line is empty, so it has no CSV header (" + std::to_string(size) +
                   " bytes)" + keep);
  if (eol == std::string::npos && size > head.size())
    throw CsvError(where + "the file's first line is longer than " + std::to_string(kCsvHeadBytes) +
                   " bytes: not a CSV header" + keep);
  std::vector<std::string> header;
  try {
    auto parsed = csv_parse(first + "\n");
    if (!parsed.empty()) header = parsed[0];
  } catch (const CsvError&) {
    throw CsvError(where + "the file's first line is not a CSV header (it ends inside a quoted field)" + keep);
  }
  if (header != columns) {
    std::string diff;
    for (size_t i = 0; i < std::max(header.size(), columns.size()); ++i) {
      std::string a = i < header.size() ? header[i] : "(none)";
      std::string b = i < columns.size() ? columns[i] : "(none)";
      if (a != b) {
        diff = "column " + std::to_string(i + 1) + " is '" + a + "' in the file but '" + b + "' in this run";
        break;
      }
    }
    throw CsvError(option + " " + path + " exists with a different header (" + diff +
                   "); write to a new file or remove the old one");
  }
  if (last_byte == '\n') return AppendAction::Append;
  // No final newline: repair it only when the last row is whole (its fields match the header).
  if (size > head.size())
    throw CsvError(where + "the file does not end with a newline, and it is too large (" + std::to_string(size) +
                   " bytes) to check its last row" + keep);
  std::vector<std::vector<std::string>> rows;
  try {
    rows = csv_parse(head);
  } catch (const CsvError&) {
    throw CsvError(where + "the file ends inside a quoted field (a row cut short)" + keep);
  }
  if (rows.size() < 2) return AppendAction::AppendAfterNewline;  // the header alone, without its newline
  if (rows.back().size() != columns.size())
    throw CsvError(where + "the file does not end with a newline and its last row has " +
                   std::to_string(rows.back().size()) + " fields where the header has " +
                   std::to_string(columns.size()) + " (a row cut short)" + keep);
  return AppendAction::AppendAfterNewline;
}

namespace {
// Holds an flock for its lifetime.
class FileLock {
 public:
  explicit FileLock(int fd) : fd_(fd) {
    while (::flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
    }
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock() { ::flock(fd_, LOCK_UN); }

 private:
  int fd_;
};
}  // namespace

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns, const std::string& option)
    : path_(path), columns_(std::move(columns)) {
  if (path == "-") {
    fd_ = STDOUT_FILENO;
    write_all(fd_, csv_line(columns_), "stdout");
    return;
  }
  try {
    check_output_file(path, option);
  } catch (const FileError& e) {
    throw CsvError(e.what());
  }
  // Never O_TRUNC: an existing file keeps every byte. O_NONBLOCK: a FIFO put there since the check.
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC | O_NONBLOCK, 0644);
  if (fd_ < 0) throw CsvError(option + " " + path + ": cannot open for writing: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    fd_ = -1;
    throw CsvError(option + " " + path + ": is " + file_kind(st.st_mode) + ", not a regular file");
  }
  ::fcntl(fd_, F_SETFL, O_APPEND);
  try {
    // Runs that open the same new file at once: the first to hold the lock writes the header, the
    // others find it there and append.
    FileLock lock(fd_);
    if (::fstat(fd_, &st) != 0) throw CsvError(option + " " + path + ": " + std::strerror(errno));
    const auto size = static_cast<unsigned long long>(st.st_size);
    std::string head(std::min<unsigned long long>(size, kCsvHeadBytes), '\0');
    char last = '\n';
    if (size > 0) {
      ssize_t n = ::pread(fd_, head.data(), head.size(), 0);
      if (n < 0 || ::pread(fd_, &last, 1, static_cast<off_t>(size - 1)) != 1)
        throw CsvError(option + " " + path + ": cannot read the existing file: " + std::strerror(errno));
      head.resize(static_cast<size_t>(n));
    }
    switch (csv_append_action(head, size, last, columns_, path, option)) {
      case AppendAction::WriteHeader:
        write_all(fd_, csv_line(columns_), path);
        break;
      case AppendAction::AppendAfterNewline:
        write_all(fd_, "\n", path);
        break;
      case AppendAction::Append:
        break;
    }
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

CsvWriter::~CsvWriter() {
  if (fd_ > STDERR_FILENO) ::close(fd_);
}

void CsvWriter::write(const std::map<std::string, std::string>& row) {
  std::set<std::string> known(columns_.begin(), columns_.end());
  for (const auto& [k, v] : row)
    if (!known.count(k)) throw CsvError("row field '" + k + "' has no column in " + path_);
  std::vector<std::string> fields;
  fields.reserve(columns_.size());
  for (const auto& c : columns_) {
    auto it = row.find(c);
    fields.push_back(it == row.end() ? "" : it->second);
  }
  write_all(fd_, csv_line(fields), path_);  // one write() per row: never half a row on disk
  ++rows_;
}

}  // namespace oitbench
