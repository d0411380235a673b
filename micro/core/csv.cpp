#include "core/csv.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

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

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  if (path == "-") {
    fd_ = STDOUT_FILENO;
    write_all(fd_, csv_line(columns_), "stdout");
    return;
  }
  std::ifstream existing(path);
  bool append = false;
  if (existing) {
    std::string first;
    std::getline(existing, first);
    if (!first.empty()) {
      auto parsed = csv_parse(first + "\n");
      auto header = parsed.empty() ? std::vector<std::string>{} : parsed[0];
      if (header != columns_) {
        std::string diff;
        for (size_t i = 0; i < std::max(header.size(), columns_.size()); ++i) {
          std::string a = i < header.size() ? header[i] : "(none)";
          std::string b = i < columns_.size() ? columns_[i] : "(none)";
          if (a != b) {
            diff = "column " + std::to_string(i + 1) + " is '" + a + "' in the file but '" + b + "' in this run";
            break;
          }
        }
        throw CsvError("--out " + path + " exists with a different header (" + diff +
                       "); write to a new file or remove the old one");
      }
      append = true;
    }
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) throw CsvError("cannot open " + path + " for writing: " + std::strerror(errno));
  if (!append) {
    if (::ftruncate(fd_, 0) != 0) throw CsvError("cannot truncate " + path);
    write_all(fd_, csv_line(columns_), path);
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
