#pragma once
// The occupancy experiment's measured occupancy (GL_NV_shader_thread_group): the pieces that do not need the
// extension, so they are tested on any driver.
#include <string>
#include <vector>

#include "backends/backend.hpp"

namespace oitbench {

// Empty where the driver offers GL_NV_shader_thread_group (the OCCUPANCY_MEASURE variant is built); else the
// note a row carries in measured_occupancy_note.
std::string occupancy_measure_unavailable(const GlInfo& gl);

struct OccupancyMeasurement {
  int warps_per_sm = 0;       // gl_WarpsPerSMNV
  int max_slots = 0;          // distinct warp slots seen on the busiest SM
  double mean_slots = 0;      // over the SMs that ran any warp
  int sms_with_warps = 0;     // SMs that ran any warp
  unsigned out_of_range = 0;  // warps that gave an SM or warp id outside the ranges the driver reported
  double occupancy = 0;       // max_slots / warps_per_sm
  std::string note() const;   // measured_occupancy_note
};

// `slots` as the shader leaves occupancy_slots: [0] the out-of-range count, then per SM ceil(warps_per_sm / 32)
// words with one bit per warp slot seen.
OccupancyMeasurement count_warp_slots(const std::vector<unsigned>& slots, int sm_count, int warps_per_sm);

}  // namespace oitbench
