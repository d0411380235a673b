#pragma once
// Files the user names: inputs must be regular files of bounded size (a folder, /dev/zero, a FIFO or a
// socket is refused by name before anything reads it), outputs must be regular files or new ones in a
// folder that exists (never a folder, /dev/null, /dev/full).
#include <cstdint>
#include <stdexcept>
#include <string>

namespace oitbench {

class FileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The largest text inputs read whole: scene and preset files.
inline constexpr std::uint64_t kMaxTextInputBytes = 64ull << 20;
// The largest model file handed to assimp.
inline constexpr std::uint64_t kMaxModelFileBytes = 2ull << 30;

// "a folder", "a character device", "a FIFO", ...: what a non-regular file is, for messages.
std::string file_kind(unsigned mode);

// Throws FileError ("PATH: WHAT is a folder, not a file") unless `path` is a regular file of at most
// `max_bytes`; `what` says what the file was meant to be ("scene file", "preset"). Returns its size.
std::uint64_t check_input_file(const std::string& path, const std::string& what, std::uint64_t max_bytes);
// check_input_file, then the whole text; a NUL byte (a binary file) is refused with its offset.
std::string read_text_file(const std::string& path, const std::string& what,
                           std::uint64_t max_bytes = kMaxTextInputBytes);

// Throws FileError naming `option` ("--out") unless `path` is "-", an existing regular file, or a new
// file name in an existing folder.
void check_output_file(const std::string& path, const std::string& option);

}  // namespace oitbench
