#pragma once
// What every row records about where and from what it ran: the machine, the code, the clock and
// the environment that changes a driver's behaviour.
#include <string>

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

}  // namespace oitbench
