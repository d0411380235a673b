// Wavelet OIT (Aizenshtein, Smal, McGuire 2022) with the Haar basis: the depth warp, the
// coefficients one fragment adds, and the absorbance in front of a depth reconstructed from a
// pixel's coefficients. micro/oit/wavelets/wavelet_model.cpp is the same computation in double.
//   WAVELET_COEFFS  coefficients per pixel (8, 16, 32): the scaling function (index 0: its
//                   coefficient is the total absorbance) and the wavelets of levels 0..log2(N)-1,
//                   index 2^j + k for psi_{j,k}, orthonormal on [0, 1)
// A fragment is a Dirac pulse of its absorbance at its warped depth x: its coefficients are the basis
// functions at x. The absorbance in front of x integrates the reconstructed density, so each
// coefficient is weighted by its function's integral up to x: x for the scaling function, a tent
// over its cell for a wavelet. Only one wavelet per level is non-zero at any x.
//   WAVELET_COSINE  the cosine basis instead (not a wavelet; a smooth comparison): 1 and
//                   sqrt(2) cos(pi k x), integrals x and sqrt(2) sin(pi k x) / (pi k); the truncated
//                   series rings, so the absorbance is clamped to [0, c0]
#ifndef WAVELETS_WAVELET_MATH_GLSL
#define WAVELETS_WAVELET_MATH_GLSL

#if WAVELET_COEFFS != 8 && WAVELET_COEFFS != 16 && WAVELET_COEFFS != 32
#error "WAVELET_COEFFS must be 8, 16 or 32"
#endif
#define WAVELET_TARGETS (WAVELET_COEFFS / 4)
const float ABSORBANCE_MAX = 10.0;  // MBOIT's clamp for opaque fragments: exp(-10) behind them

// Window depth in [0, 1] -> view depth (near_far: the projection's planes) -> its logarithm scaled to
// [0, 1) between the geometry's nearest and farthest view depth (range).
float wavelet_warp(float window_depth, vec2 near_far, vec2 range) {
  float n = near_far.x, f = near_far.y;
  float view = n * f / (f - window_depth * (f - n));
  return clamp((log(view) - log(range.x)) / (log(range.y) - log(range.x)), 0.0, 0.99999994);
}

#ifdef WAVELET_COSINE
const float WAVELET_PI = 3.14159265358979;
void basis_contribution(float x, float absorbance, out float w[WAVELET_COEFFS]) {
  w[0] = absorbance;
  for (int k = 1; k < WAVELET_COEFFS; ++k) w[k] = absorbance * sqrt(2.0) * cos(WAVELET_PI * float(k) * x);
}

float basis_absorbance(float w[WAVELET_COEFFS], float x) {
  float a = w[0] * x;
  for (int k = 1; k < WAVELET_COEFFS; ++k)
    a += w[k] * sqrt(2.0) * sin(WAVELET_PI * float(k) * x) / (WAVELET_PI * float(k));
  return clamp(a, 0.0, max(w[0], 0.0));
}
#else
void basis_contribution(float x, float absorbance, out float w[WAVELET_COEFFS]) {
  w[0] = absorbance;
  for (int level = 0; (1 << level) < WAVELET_COEFFS; ++level) {
    float cells = float(1 << level), lo = floor(x * cells) / cells, width = 1.0 / cells;
    int first = 1 << level, k = int(lo * cells + 0.5);
    for (int i = first; i < 2 * first; ++i) w[i] = 0.0;
    w[first + k] = absorbance * (x < lo + 0.5 * width ? sqrt(cells) : -sqrt(cells));
  }
}

float basis_absorbance(float w[WAVELET_COEFFS], float x) {
  float a = w[0] * x;
  for (int level = 0; (1 << level) < WAVELET_COEFFS; ++level) {
    float cells = float(1 << level), lo = floor(x * cells) / cells, width = 1.0 / cells;
    int k = int(lo * cells + 0.5);
    float u = x - lo;
    a += w[(1 << level) + k] * sqrt(cells) * (u < 0.5 * width ? u : width - u);
  }
  return max(a, 0.0);
}
#endif

#endif
