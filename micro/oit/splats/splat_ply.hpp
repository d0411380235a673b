#pragma once
// The standard 3D Gaussian splatting PLY file (what graphdeco-inria's trainer writes): one element
// "vertex" of N splats with float properties x y z, f_dc_0..2 (degree-0 spherical harmonic per channel),
// f_rest_0..K-1 (the higher degrees, channel-major: K/3 coefficients of red, then green, then blue;
// K = 0, 9, 24 or 45 for degree 0, 1, 2 or 3), opacity (a logit), scale_0..2 (logs of the standard
// deviations) and rot_0..3 (a quaternion w x y z, not necessarily normalised); nx ny nz and any other
// property are skipped by their declared type. binary_little_endian 1.0 and ascii 1.0 are read;
// big-endian is refused. Every error names the file and what is wrong (the header line for header
// errors, the vertex index and property for bad values); nothing is allocated beyond what the file's
// real size can hold.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "oit/splats/splat.hpp"

namespace oitbench::oit {

class SplatFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The largest splat file read (a degree-3 file of 10^7 splats is 2.5 GB).
inline constexpr std::uint64_t kMaxSplatFileBytes = 16ull << 30;

struct SplatPlyHeader {
  bool ascii = false;
  std::uint64_t count = 0;        // splats (the vertex element's count)
  std::uint64_t stride = 0;       // bytes per vertex (binary)
  std::uint64_t data_offset = 0;  // the first byte after end_header
  int sh_degree = 0;              // 0..3, from the number of f_rest_* properties
};

// The header, checked: required properties, their types, the SH degree, and (binary) that the file
// holds count x stride bytes after it. Throws SplatFileError.
SplatPlyHeader read_splat_ply_header(const std::string& path);

// The first `max_count` splats (all by default), colours evaluated for the direction from `eye` to
// each splat (degree 0 only: the same for every view), moved by `offset`. Throws SplatFileError.
SplatList read_splat_ply(const std::string& path, glm::vec3 eye, std::uint64_t max_count = UINT64_MAX,
                         glm::vec3 offset = glm::vec3(0.0f));
// Reads and checks every splat of the file, keeping none (what a run checks before its cases).
void check_splat_ply(const std::string& path);

// The colour of a splat's spherical harmonics seen along `dir` (unit, from the eye to the splat):
// 0.5 + the SH sum, clamped at 0 below (3DGS's convention). `dc` holds 3 coefficients, `rest` the
// file's f_rest values (channel-major, 3 * ((degree + 1)^2 - 1) of them).
glm::vec3 sh_colour(int degree, const float* dc, const float* rest, glm::vec3 dir);

// Writes splats as a binary little-endian 3DGS PLY: degree 0 from each splat's colour (f_dc = (colour -
// 0.5) / C0), or with `rest` (3 * ((degree + 1)^2 - 1) floats per splat, channel-major) a higher degree.
// Opacities are clamped into (0, 1) for their logit. Throws SplatFileError when the file cannot be written.
void write_splat_ply(const std::string& path, const SplatList& splats, int sh_degree = 0,
                     const std::vector<float>& rest = {});

}  // namespace oitbench::oit
