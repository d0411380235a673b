#pragma once
// Memory decided before it is used (issue 27): a case estimates what it will hold from its counts
// (fragments, pixels) before it allocates anything that large, and a case over the limit is
// `unsupported` with the estimate and the limit that refuses it, in seconds, instead of an error row
// saying `std::bad_alloc` after minutes.
//
// The limits (docs/measurement.md#memory-decided-before-it-is-used):
//   CPU  the smallest of /proc/meminfo's MemAvailable and what RLIMIT_AS and RLIMIT_DATA leave this
//        process (the limit minus its VmSize, VmData), read when each case is prepared; --memory-limit
//        SIZE replaces it.
//   GPU  GL_NVX_gpu_memory_info's or GL_ATI_meminfo's free video memory where the driver has one;
//        on a software renderer (llvmpipe, zink over lavapipe) the GPU's buffers are this process's
//        memory, so both needs are held together against the CPU limit; elsewhere unknown (only the
//        storage's own limits, GL_MAX_TEXTURE_BUFFER_SIZE and its chunks, refuse).
#include <optional>
#include <string>

namespace oitbench {

struct MemoryLimit {
  unsigned long long bytes = 0;  // 0: unknown (not checked)
  std::string source;            // what set it: "MemAvailable", "RLIMIT_AS", "--memory-limit", ...
  bool known() const { return bytes > 0; }
};

struct MemoryLimits {
  MemoryLimit cpu, gpu;
  bool shared = false;  // a software renderer: GPU buffers are CPU memory, both needs against `cpu`
};

// What a case would hold: GPU storage and CPU memory (read-back, references, validation buffers),
// each with what it is for and how it was counted ("402 M fragments x 24 B").
struct MemoryNeed {
  unsigned long long gpu_bytes = 0, cpu_bytes = 0;
  std::string gpu_what, cpu_what;
};

// Two needs held at once: the bytes added, the texts joined with " + ".
MemoryNeed combined(MemoryNeed a, const MemoryNeed& b);

// Empty when `need` fits `limits`; else the reason the case is refused, naming the estimate and the
// limit: "needs 9.6 GiB of CPU memory for ... (402 M fragments x 24 B); limit 6.2 GiB (MemAvailable)".
std::string memory_refusal(const MemoryNeed& need, const MemoryLimits& limits);
// Throws Unsupported with memory_refusal()'s reason, prefixed with `what`, when it does not fit.
void require_memory(const MemoryNeed& need, const MemoryLimits& limits, const std::string& what);

// The CPU limit as described above, from /proc/meminfo and getrlimit (reads them now).
MemoryLimit cpu_memory_limit();
// The GPU's free memory from GL_NVX_gpu_memory_info or GL_ATI_meminfo (a current context); unknown
// without either. `software`: the renderer is a software one (shared memory, see above).
MemoryLimits current_memory_limits(bool software, bool nvx, bool ati, std::optional<unsigned long long> cpu_override);

// "8G", "512M", "1.5GiB", "64k", "1000000" (bytes); K, M, G, T are powers of 1024, with or without
// "iB" or "B". Throws std::invalid_argument saying what is accepted (zero, negative, NaN, too big).
unsigned long long parse_byte_size(const std::string& text);
// "9.6 GiB", "512 MiB", "900 B".
std::string format_bytes(unsigned long long bytes);
// "402 M", "4.19 M", "1100": a count for a reason.
std::string format_count(unsigned long long n);

}  // namespace oitbench
