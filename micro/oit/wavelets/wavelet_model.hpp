#pragma once
// WOIT's CPU model (wavelets.hpp), which a GPU image must match to be valid: what
// shaders/wavelets/wavelet_math.glsl computes, in double precision, from the fragments the case
// captured. The coefficients are summed in the order the fragments reached the pixel and rounded to
// the storage (float, or half after every addition) as the blender does; the reconstruction and
// the weighting are exact.
#include <vector>

#include "oit/reference/reference.hpp"
#include "oit/wavelets/wavelets.hpp"

namespace oitbench::oit {

// Window depth -> view depth (near_far: the projection) -> its logarithm scaled from depth_range to
// [0, 1), clamped.
double wavelet_warp(float window_depth, glm::vec2 near_far, glm::vec2 depth_range);
// The Haar functions at warped depth x, times `absorbance`: what one fragment adds to each of the n
// coefficients.
void haar_contribution(double x, double absorbance, int n, double* out);
// The absorbance in front of warped depth x: the integral over [0, x] of the density the n
// coefficients reconstruct (never below 0).
double haar_absorbance(const double* coeffs, int n, double x);
// The cosine basis's counterparts: sqrt(2) cos(pi k x) per coefficient, and the absorbance in front of
// x (its integral, clamped to [0, coefficient 0]: the truncated series rings).
void cosine_contribution(double x, double absorbance, int n, double* out);
double cosine_absorbance(const double* coeffs, int n, double x);
// RGB per pixel (3 doubles), background where no fragment landed.
std::vector<double> woit_model(const HostLists& lists, const Backdrop& background, const WoitSettings& s);

}  // namespace oitbench::oit
