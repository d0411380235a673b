#pragma once
// Depth peeling: DP, front-to-back depth peeling (Everitt 2001), and DDP, dual depth peeling
// (Bavoil & Myers 2008), as oit techniques (peel_case.cpp, shaders/peel/). Each iteration peels
// the next layer of every pixel (DDP: the next from the front and the next from the back) until an
// occlusion query finds no fragment left or max_layers is reached. Run to completion the image is
// exact; stopped early it is an approximation, validated against a CPU model of the layers it
// peeled (peel_model), its error against the exact composite reported as data.
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "oit/capture/fragment_storage.hpp"
#include "oit/oit_case.hpp"
#include "oit/reference/reference.hpp"

namespace oitbench::oit {

// Which peeling a technique entry (techniques.hpp) runs: its variant.
enum class PeelKind { Depth = 0, Dual = 1 };

// The parameters the peeling techniques add to the oit experiment (max_layers, tie_rule).
std::vector<ParamSpec> peel_params();

struct PeelSettings {
  bool dual = false;        // DDP
  bool depth_only = false;  // tie_rule=depth: layers by depth alone (coplanar fragments lost)
  unsigned iterations = 0;  // the iterations the GPU ran that found layers (0: none were found)
};
// The layers of one pixel in peel order: (depth, colour key) pairs with how many fragments each.
struct PeelLayer {
  float depth;
  unsigned colour;  // packUnorm4x8 bits, the tie-break
  unsigned count;
};
std::vector<PeelLayer> peel_layers(const HostLists& lists, size_t pixel, bool depth_only);
// RGB per pixel (3 doubles): the layers `s.iterations` iterations peel, composited in depth order
// over the background (every layer when that is enough to peel them all).
std::vector<double> peel_model(const HostLists& lists, const Backdrop& backdrop, const PeelSettings& s);

std::unique_ptr<OitCase> make_peel_case(const ParamSet& p, CaseContext& ctx);

}  // namespace oitbench::oit
