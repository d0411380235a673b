#pragma once
// What every row records about where and from what it ran: the machine, the code, the clock and
// the environment that changes a driver's behaviour.
#include <map>
#include <string>
#include <vector>

namespace oitbench {

std::string utc_now();         // 2026-12-01T23:09:57Z
std::string host_name();       // gethostname
std::string cpu_model();       // /proc/cpuinfo "model name"
std::string recorded_env();    // NAME=VALUE;... of the variables that change a driver's speed or behaviour
std::string lp_num_threads();  // LP_NUM_THREADS, or "unset(N cores)"
const char* git_sha();         // generated at build time (cmake/version.cmake)
// git describe of the source tree at build time (v0.1.0-123-gSHA[-dirty]; 0.1.0-gSHA[-dirty] without a
// v* tag), generated with git_sha.
const char* version_string();
// The configured options, one "name: value" line each: build type, compiler, osmesa, glfw, sanitizers
// (generated from cmake/build_info.cpp.in).
const char* build_options();

// A run's identity: a random UUID (version 4, from std::random_device), the same in every row and raw
// sample one invocation writes (an isolated case's child gets its parent's).
std::string new_run_id();
bool is_run_id(const std::string& s);  // 8-4-4-4-12 lower-case hex

// --tag KEY=VALUE labels (a driver's commit, a machine pool, a CI job's address). A key is 1-64 of
// [A-Za-z0-9_.-] starting with a letter; a value anything without control characters. Throws
// UsageError naming `option` for a malformed tag or a key given twice.
using Tags = std::map<std::string, std::string>;
Tags parse_tags(const std::vector<std::string>& specs, const std::string& option = "--tag");
// The `tags` column: KEY=VALUE;... sorted by key, with '%', ';' and '=' in values as %25, %3B, %3D.
std::string encode_tags(const Tags& tags);
Tags decode_tags(const std::string& column);

// What identifies the machine well enough to tell two apart that share a name and a "model name".
struct MachineIdentity {
  std::string cpu_vendor;      // vendor_id: GenuineIntel, AuthenticAMD, ...
  std::string cpu_family;      // "cpu family"
  std::string cpu_model_id;    // "model" (a number)
  std::string cpu_stepping;    // "stepping"
  std::string cpu_isa;         // the ISA extensions a JIT (llvmpipe's LLVM) may use, space-separated, fixed order
  int cpu_count = 0;           // logical CPUs online
  long long memory_bytes = 0;  // MemTotal
  std::string kernel;          // uname: release and version
  std::string fingerprint;     // 16 hex digits, a hash of all of the above
};
// Parses /proc/cpuinfo and /proc/meminfo text (tests feed their own); kernel as given.
MachineIdentity machine_identity(const std::string& cpuinfo, const std::string& meminfo, const std::string& kernel);
MachineIdentity this_machine();  // this machine's /proc files and uname

// What llvmpipe targets, from GL_RENDERER "llvmpipe (LLVM 15.0.6, 256 bits)" (also inside zink's
// renderer string); empty where the renderer names no LLVM.
struct LlvmTarget {
  std::string llvm_version;  // 15.0.6
  std::string vector_bits;   // 256
};
LlvmTarget llvm_target(const std::string& gl_renderer);
// "Mesa 22.3.6" from GL_VERSION "4.5 (Core Profile) Mesa 22.3.6"; empty for other drivers.
std::string mesa_version(const std::string& gl_version);

}  // namespace oitbench
