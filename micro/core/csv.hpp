#pragma once
// Tidy CSV: RFC 4180 quoting, one row per write() so a crash or Ctrl-C never leaves half a row,
// append onto an existing file only when its header is the same.
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace oitbench {

class CsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string csv_quote(const std::string& field);
std::string csv_line(const std::vector<std::string>& fields);
// Parses a whole CSV text (quoted fields, embedded commas, quotes and newlines).
std::vector<std::vector<std::string>> csv_parse(const std::string& text);

// What appending rows of `columns` to an existing file needs, judged from its first bytes `head` (up to
// kCsvHeadBytes; the whole file when `size` is no larger) and its last byte: write the header (an
// empty file), append, or append after adding the final newline the file lacks (only when its last
// row is whole). Throws CsvError naming `option` and `path` for anything else: an empty first line,
// another header, a last row cut short. Nothing is ever truncated.
enum class AppendAction { WriteHeader, Append, AppendAfterNewline };
inline constexpr size_t kCsvHeadBytes = 1 << 20;
AppendAction csv_append_action(const std::string& head, unsigned long long size, char last_byte,
                               const std::vector<std::string>& columns, const std::string& path,
                               const std::string& option = "--out");

class CsvWriter {
 public:
  // Creates `path` with the header, or appends when it exists with the identical header (under an
  // exclusive lock, so runs creating the same file at once write one header); throws CsvError naming
  // `option` and the first differing column otherwise. "-" writes to stdout. A path that is not a
  // regular file (a folder, /dev/null, /dev/full) is refused.
  CsvWriter(const std::string& path, std::vector<std::string> columns, const std::string& option = "--out");
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  ~CsvWriter();

  const std::vector<std::string>& columns() const { return columns_; }
  // Fields not named by a column throw CsvError (a typo in an experiment is a bug, not data).
  void write(const std::map<std::string, std::string>& row);
  const std::string& path() const { return path_; }
  size_t rows_written() const { return rows_; }

 private:
  std::string path_;
  std::vector<std::string> columns_;
  int fd_ = -1;
  size_t rows_ = 0;
};

}  // namespace oitbench
