#include "core/files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace oitbench {

namespace {

std::string size_text(std::uint64_t bytes) {
  if (bytes >= (1ull << 30) && bytes % (1ull << 30) == 0) return std::to_string(bytes >> 30) + " GiB";
  if (bytes >= (1ull << 20) && bytes % (1ull << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

// Closes a descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string file_kind(unsigned mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISREG(mode)) return "a regular file";
  return "not a regular file";
}

std::uint64_t check_input_file(const std::string& path, const std::string& what, std::uint64_t max_bytes) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw FileError(path + ": cannot read the " + what + ": " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw FileError(path + ": the " + what + " is " + file_kind(st.st_mode) + ", not a regular file");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes)
    throw FileError(path + ": the " + what + " is " + std::to_string(size) + " bytes, more than the " +
                    size_text(max_bytes) + " oitbench reads");
  return size;
}

std::string read_text_file(const std::string& path, const std::string& what, std::uint64_t max_bytes) {
  check_input_file(path, what, max_bytes);
  // O_NONBLOCK: a FIFO put in the file's place since the check must not block the open.
  Fd in{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (in.fd < 0) throw FileError(path + ": cannot open the " + what + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(in.fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw FileError(path + ": the " + what + " is " + file_kind(st.st_mode) + ", not a regular file");
  std::string text;
  char buf[1 << 16];
  for (;;) {
    ssize_t n = ::read(in.fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw FileError(path + ": cannot read the " + what + ": " + std::strerror(errno));
    if (n == 0) break;
    if (text.size() + static_cast<size_t>(n) > max_bytes)
      throw FileError(path + ": the " + what + " grew past the " + size_text(max_bytes) + " oitbench reads");
    text.append(buf, static_cast<size_t>(n));
  }
  if (auto nul = text.find('\0'); nul != std::string::npos)
    throw FileError(path + ": the " + what + " is not a text file (a NUL byte at offset " + std::to_string(nul) + ")");
  return text;
}

void check_output_file(const std::string& path, const std::string& option) {
  if (path == "-") return;
  if (path.empty()) throw FileError(option + ": expected a file name (or '-' for stdout), got an empty one");
  if (path.back() == '/') throw FileError(option + " " + path + ": names a folder; give a file name in it");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode))
      throw FileError(option + " " + path + ": is " + file_kind(st.st_mode) +
                      ", not a regular file; give a file name (or '-' for stdout)");
    return;
  }
  if (errno != ENOENT) throw FileError(option + " " + path + ": " + std::strerror(errno));
  std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) parent = ".";
  if (::stat(parent.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw FileError(option + " " + path + ": the folder " + parent.string() + " does not exist");
}

}  // namespace oitbench
