#pragma once
// Approximate OIT (Brüll 2018, sections 2.3, 3.5-3.7, chapters 5 and 6): per-pixel arrays of n
// nodes filled under a per-pixel spinlock (MLAB, UMLAB, AT, HAT, UAT, UHAT), weighted blended OIT
// (McGuire & Bavoil 2013) and plain unsorted blending. Each technique has a CPU model here: the
// same approximation applied to the same fragments in the order they reached the pixel (the
// reversed per-pixel linked list, which on a rasteriser that shades each pixel's fragments in
// submission order is also the order the spinlock serialises them in). A GPU image is valid when
// it matches its own model; its distance to the exact reference is reported as data.
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/registry.hpp"
#include "oit/fragment_storage.hpp"
#include "oit/oit_case.hpp"

namespace oitbench::oit {

enum class ApproxTechnique { Mlab, Umlab, At, Hat, Uat, Uhat, Laat, Wboit, Unsorted };

const std::vector<std::string>& approx_technique_names();  // MLAB UMLAB AT HAT UAT UHAT LAAT WBOIT unsorted
bool is_approx_technique(const std::string& name);
ApproxTechnique parse_approx_technique(const std::string& name);  // throws std::invalid_argument

struct ApproxSettings {
  ApproxTechnique technique = ApproxTechnique::Mlab;
  int nodes = 8;                 // per-pixel array techniques (LAAT stores one more: its head)
  std::string weight = "eq7";    // WBOIT: none | eq7 | eq10
  bool unguarded = false;        // the deliberately unguarded variant (hard-case tests)
  glm::vec2 near_far{0.1f, 10.f};  // the projection's planes (WBOIT eq7 works on view distance)
};

struct ApproxModel {
  std::vector<float> rgb;  // 3 floats per pixel, background where no fragment landed
};
// The technique's own CPU model on the captured fragments (see the header comment).
ApproxModel approx_model(const HostLists& lists, glm::vec3 background, const ApproxSettings& s);

// Image statistics against the exact reference (double RGB per pixel).
struct ApproxError {
  double rmse = 0, psnr = 0, max_abs_error = 0, frac_pixels_off = 0;  // off: by more than 1/255
};
ApproxError approx_error(const std::vector<float>& rgb, const std::vector<double>& reference);

// The parameters the approximate techniques add to the oit experiment (ignored by the exact ones).
std::vector<ParamSpec> approx_params();

// The oit experiment's case for an approximate technique (parameters as in micro/experiments/oit.cpp).
std::unique_ptr<OitCase> make_approx_case(const ParamSet& p, CaseContext& ctx);

// 8-bit sRGB-less PNG of an RGB float image (rows bottom-up as GL reads them), values * scale.
void write_png(const std::string& path, const std::vector<float>& rgb, int width, int height, float scale = 1.0f);

}  // namespace oitbench::oit
