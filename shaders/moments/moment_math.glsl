// Moment-based OIT (Münstermann, Krumpen, Klein, Peters 2018): the depth warp, the moments one
// fragment adds, and the transmittance reconstructed from a pixel's moments at a depth. Written
// once for both kinds of moments; micro/oit/moments/moment_model.cpp is the same computation in double.
//   MOMENT_COUNT  real numbers stored beside b0 (4, 6, 8): power moments b1..bn, or n/2 complex
//                 trigonometric moments; both give a system of order M = MOMENT_COUNT / 2
//   MOMENT_TRIGONOMETRIC  trigonometric moments (default: power)
// Reconstruction (the paper's section 4, after Peters & Klein's moment shadow mapping): bias the
// normalised moments, solve the Hankel (power) or Toeplitz (trigonometric) system B c = e(z), take
// the roots of the polynomial c (the other support points of the canonical representation),
// interpolate the step function "in front of z" at z (weight: the overestimation beta) and the
// roots, and sum the weights with the moments. Departures from the paper's HLSL: the roots come
// from a fixed number of Durand-Kerner iterations instead of its closed-form quadratic/cubic/
// quartic solvers, and the linear system is eliminated generically instead of its unrolled Cholesky.
#ifndef MOMENTS_MOMENT_MATH_GLSL
#define MOMENTS_MOMENT_MATH_GLSL

#if MOMENT_COUNT != 4 && MOMENT_COUNT != 6 && MOMENT_COUNT != 8
#error "MOMENT_COUNT must be 4, 6 or 8"
#endif
#define ORDER (MOMENT_COUNT / 2)
#define ROOT_ITERATIONS 32
#define REBIAS_STEPS 3
const float ABSORBANCE_MAX = 10.0;  // the paper's clamp for opaque fragments: exp(-10) behind them
const float PI = 3.14159265358979;

// Window depth in [0, 1] -> view depth (near_far: the projection's planes) -> its logarithm scaled to
// [-1, 1] between the geometry's nearest and farthest view depth (range).
float moment_warp(float window_depth, vec2 near_far, vec2 range) {
  float n = near_far.x, f = near_far.y;
  float view = n * f / (f - window_depth * (f - n));
  return (log(view) - log(range.x)) / (log(range.y) - log(range.x)) * 2.0 - 1.0;
}

vec2 cmul(vec2 a, vec2 b) { return vec2(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
vec2 cconj(vec2 a) { return vec2(a.x, -a.y); }
vec2 cdiv(vec2 a, vec2 b) { return cmul(a, cconj(b)) / dot(b, b); }

// Trigonometric moments: warped depth [-1, 1] -> angle [0, 2 pi - wrapping zone] (a zone of pi/10).
const float WRAPPING_ZONE = 0.1 * PI;
float moment_phase(float z) { return (z + 1.0) * (PI - 0.5 * WRAPPING_ZONE); }
// Grows monotonically with the angle of a point on the unit circle (not arclength): -1 .. 7.
float circle_parameter(vec2 p) {
  float r = abs(p.y) - abs(p.x);
  r = p.x < 0.0 ? 2.0 - r : r;
  return p.y < 0.0 ? 6.0 - r : r;
}
// The weight ramps linearly to 1 inside the wrapping zone (roots there are as much behind as in front).
float wrapping_weight(float reference, float root) {
  float zone_begin = circle_parameter(vec2(cos(2.0 * PI - WRAPPING_ZONE), sin(2.0 * PI - WRAPPING_ZONE)));
  float scale = 1.0 / (7.0 - zone_begin);
  return (root < reference ? 1.0 : 0.0) + clamp(root * scale + 1.0 - 7.0 * scale, 0.0, 1.0);
}

// The moments one fragment of absorbance a at warped depth z adds (b0 is a itself).
void moment_contribution(float z, float a, out float b[MOMENT_COUNT]) {
#if defined(MOMENT_TRIGONOMETRIC)
  float phase = moment_phase(z);
  vec2 p = vec2(cos(phase), sin(phase)), pk = p;
  for (int k = 0; k < ORDER; ++k) {
    b[2 * k] = pk.x * a;
    b[2 * k + 1] = pk.y * a;
    pk = cmul(pk, p);
  }
#else
  float zk = z;
  for (int k = 0; k < MOMENT_COUNT; ++k) {
    b[k] = zk * a;
    zk *= z;
  }
#endif
}

// Transmittance at warped depth z from the zeroth moment b0 and the raw (unnormalised) moments.
float moment_transmittance(float b0, float raw[MOMENT_COUNT], float z, float bias, float beta) {
  // m[k]: the normalised, biased moments (complex; power moments are real).
  vec2 m[2 * ORDER + 1];
  vec2 a[ORDER + 1][ORDER + 2];
#if defined(MOMENT_TRIGONOMETRIC)
  float phase = moment_phase(z);
  vec2 point = vec2(cos(phase), sin(phase));
#else
#if MOMENT_COUNT == 4
  const float bias_vector[4] = float[](0.0, 0.375, 0.0, 0.375);
#elif MOMENT_COUNT == 6
  const float bias_vector[6] = float[](0.0, 0.48, 0.0, 0.451, 0.0, 0.45);
#else
  const float bias_vector[8] = float[](0.0, 0.75, 0.0, 0.67666666666666664, 0.0, 0.63, 0.0, 0.60030303030303034);
#endif
  vec2 point = vec2(z, 0.0);
#endif
  // Rounded storage can make the moments inconsistent (a pivot <= 0: the matrix is not positive
  // definite even after biasing, e.g. half-float sums over 128 layers); then the bias grows tenfold,
  // at most REBIAS_STEPS times. The paper has one fixed bias.
  float b = bias;
  for (int attempt = 0; attempt <= REBIAS_STEPS; ++attempt, b = min(b * 10.0, 1.0)) {
    m[0] = vec2(1.0, 0.0);
#if defined(MOMENT_TRIGONOMETRIC)
    for (int k = 1; k <= ORDER; ++k) m[k] = vec2(raw[2 * k - 2], raw[2 * k - 1]) / b0 * (1.0 - b);
#else
    for (int k = 1; k <= MOMENT_COUNT; ++k) m[k] = vec2(mix(raw[k - 1] / b0, bias_vector[k - 1], b), 0.0);
#endif
    // The system B c = e(point): B[i][j] = m[i + j] (Hankel) or m[i - j] (Toeplitz, Hermitian).
    vec2 e = vec2(1.0, 0.0);
    for (int i = 0; i <= ORDER; ++i) {
      for (int j = 0; j <= ORDER; ++j) {
#if defined(MOMENT_TRIGONOMETRIC)
        a[i][j] = i >= j ? m[i - j] : cconj(m[j - i]);
#else
        a[i][j] = m[i + j];
#endif
      }
      a[i][ORDER + 1] = e;
      e = cmul(e, point);
    }
    // Gaussian elimination without pivoting: the pivots of a positive definite matrix are > 0.
    bool definite = true;
    for (int k = 0; k <= ORDER; ++k) {
      definite = definite && a[k][k].x > 0.0;
      for (int i = k + 1; i <= ORDER; ++i) {
        vec2 f = cdiv(a[i][k], a[k][k]);
        for (int j = k; j <= ORDER + 1; ++j) a[i][j] -= cmul(f, a[k][j]);
      }
    }
    if (definite) break;
  }
  vec2 c[ORDER + 1];
  for (int i = ORDER; i >= 0; --i) {
    vec2 s = a[i][ORDER + 1];
    for (int j = i + 1; j <= ORDER; ++j) s -= cmul(a[i][j], c[j]);
    c[i] = cdiv(s, a[i][i]);
  }
  // The polynomial whose roots are the other support points: sum c_k x^k (trigonometric: conj(c_k)).
  vec2 q[ORDER + 1];
  for (int k = 0; k <= ORDER; ++k) {
#if defined(MOMENT_TRIGONOMETRIC)
    q[k] = cdiv(cconj(c[k]), cconj(c[ORDER]));
#else
    q[k] = cdiv(c[k], c[ORDER]);
#endif
  }
  // Durand-Kerner: all ORDER roots of the monic polynomial at once.
  vec2 x[ORDER + 1];
  x[0] = point;
  vec2 seed = vec2(0.4, 0.9);
  for (int k = 1; k <= ORDER; ++k) {
    x[k] = seed;
    seed = cmul(seed, vec2(0.4, 0.9));
  }
  for (int it = 0; it < ROOT_ITERATIONS; ++it)
    for (int k = 1; k <= ORDER; ++k) {
      vec2 value = q[ORDER], denominator = vec2(1.0, 0.0);
      for (int j = ORDER - 1; j >= 0; --j) value = cmul(value, x[k]) + q[j];
      for (int j = 1; j <= ORDER; ++j)
        if (j != k) denominator = cmul(denominator, x[k] - x[j]);
      if (dot(denominator, denominator) > 0.0) x[k] -= cdiv(value, denominator);
    }
  // Weights: beta at the point itself, 1 for support points in front of it, 0 behind.
  vec2 f[ORDER + 1];
  f[0] = vec2(beta, 0.0);
#if defined(MOMENT_TRIGONOMETRIC)
  float reference = circle_parameter(point);
  for (int k = 1; k <= ORDER; ++k) {
    x[k] = normalize(x[k]);  // on the unit circle up to rounding; the parameter needs it there
    f[k] = vec2(wrapping_weight(reference, circle_parameter(x[k])), 0.0);
  }
#else
  for (int k = 1; k <= ORDER; ++k) {
    x[k] = vec2(x[k].x, 0.0);  // real up to rounding
    f[k] = vec2(x[k].x < z ? 1.0 : 0.0, 0.0);
  }
#endif
  // Newton's divided differences, then the interpolating polynomial's coefficients.
  for (int j = 1; j <= ORDER; ++j)
    for (int i = ORDER; i >= j; --i) f[i] = cdiv(f[i] - f[i - 1], x[i] - x[i - j]);
  vec2 p[ORDER + 1];
  for (int k = 0; k <= ORDER; ++k) p[k] = vec2(0.0);
  p[0] = f[ORDER];
  for (int k = ORDER - 1; k >= 0; --k) {
    // p <- p * (x - x_k) + f_k
    for (int j = ORDER; j >= 1; --j) p[j] = p[j - 1] - cmul(p[j], x[k]);
    p[0] = f[k] - cmul(p[0], x[k]);
  }
  float absorbance = 0.0;
  for (int k = 0; k <= ORDER; ++k) absorbance += cmul(p[k], m[k]).x;
  return clamp(exp(-b0 * absorbance), 0.0, 1.0);
}

#endif
