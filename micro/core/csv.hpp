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

class CsvWriter {
 public:
  // Creates `path` with the header, or appends when it exists with the identical header;
  // throws CsvError naming the first differing column otherwise. "-" writes to stdout.
  CsvWriter(const std::string& path, std::vector<std::string> columns);
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
