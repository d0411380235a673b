// The full-screen resolve of the per-pixel array techniques, onto the opaque background:
//   MLAB, UMLAB: C_final = C_opaque * prod T_i + sum C_i prod_{j<i} T_j over the nodes near to far
//                (section 3.7; UMLAB's unsorted nodes are first sorted by a register insertion sort)
//   HT:          the core's n nodes near to far, then the tail's weighted average (Bavoil & Myers
//                2008, as Maule et al. 2013): colour sum C_i a_i / sum a_i covering 1 - (1 - a_avg)^n
//                of what lies behind, a_avg = sum a_i / n, over the n tail fragments
//   HT_HTGS:     (HT's ht_variant=htgs) the tail's colour average covers 1 - prod (1 - a_i) (HTGS's tail)
//   FIRST-K:     HT's core alone over the background (the fragments it pushed out were dropped)
//   WINDOW-SORT: what the window emitted (blended front to back during the insertion), then the window's
//                nodes near to far, over the background
//   AT family:   C_final = accumulated sum (pass 2) + C_opaque * vis(infinity)
// Fragments at exactly equal depth do not occlude each other in vis(z) (Eq. 2.3 counts only
// nearer ones), so a stack of them adds up to more opacity than 1 - vis(infinity) and can leave
// [0, 1]. The tie-break: such a pixel's sum is scaled so its opacity sum alpha * vis is exactly
// 1 - vis(infinity) (equal-depth fragments share their layer in proportion to alpha: order-free,
// so deterministic). Without ties the sum telescopes to at most 1 - vis(infinity) and nothing
// changes. APPROX_UNGUARDED drops the scaling.
#include "../common/oitbench.glsl"
#include "../storage/storage.glsl"
#include "bindings.h"
// Included outside the #if: the shader assembler inlines each file once, where first named.
#include "nodes.glsl"
#include "visibility.glsl"
#if defined(TECH_WINDOW_SORT)
#include "window.glsl"
#endif
#if !defined(TECH_MLAB) && !defined(TECH_UMLAB) && !defined(TECH_FIRST_K) && !defined(TECH_WINDOW_SORT)
layout(binding = APPROX_ACCUM_UNIT) uniform sampler2D accumulation;
#endif
#if defined(TECH_HT)
layout(binding = APPROX_REVEAL_UNIT) uniform sampler2D tailCount;
#endif

#include "../scene/backdrop.glsl"
uniform int zero;
layout(location = 0) out vec4 fragColour;

#if defined(TECH_MLAB) || defined(TECH_UMLAB)
vec4 rC[N];
float rZ[N];
#endif

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
#if defined(TECH_MLAB) || defined(TECH_UMLAB)
  for (int i = 0; i < N; ++i) {
    uvec2 node = STORAGE_LOAD(p, i);
    rC[i] = mlab_value(node);
    rZ[i] = node_depth(node);
  }
#if defined(TECH_UMLAB)
  for (int i = 1; i < N; ++i)
    for (int j = i; j > 0; --j)
      if (rZ[j - 1] > rZ[j]) {
        vec4 tc = rC[j - 1]; rC[j - 1] = rC[j]; rC[j] = tc;
        float tz = rZ[j - 1]; rZ[j - 1] = rZ[j]; rZ[j] = tz;
      }
#endif
  vec3 c = vec3(0.0);
  float t = 1.0;
  for (int i = 0; i < N; ++i) {
    c += t * rC[i].rgb;
    t *= rC[i].a;
  }
  c += t * backdrop_colour(p);
#elif defined(TECH_HT) || defined(TECH_FIRST_K) || defined(TECH_WINDOW_SORT)
  vec3 c = vec3(0.0);
  float t = 1.0;
#if defined(TECH_WINDOW_SORT)
  window_load_blended(p, c, t);
  const int core = WINDOW_N;
#else
  const int core = N;
#endif
  for (int i = 0; i < core; ++i) {  // empty nodes unpack to alpha 0: no effect
    vec4 k = unpackUnorm4x8(STORAGE_LOAD(p, i).x);
    c += t * k.a * k.rgb;
    t *= 1.0 - k.a;
  }
#if defined(TECH_HT)
  vec4 acc = texelFetch(accumulation, p, 0);
  float n = texelFetch(tailCount, p, 0).r;
  vec3 tail = vec3(0.0);
  float tailT = 1.0;
#if defined(HT_HTGS)
  tailT = n;  // the product of the tail's transmittances
  if (acc.a > 0.0) tail = acc.rgb / acc.a * (1.0 - tailT);
#else
  if (n > 0.0) {
    // Clamped: opaque tails sum their alphas to n, and a rounding above it gave pow() a negative base (NaN).
    tailT = pow(clamp(1.0 - acc.a / n, 0.0, 1.0), n);
    if (acc.a > 0.0) tail = acc.rgb / acc.a * (1.0 - tailT);
  }
#endif
  c += t * (tail + tailT * backdrop_colour(p));
#else
  c += t * backdrop_colour(p);
#endif
#else
  vec4 acc = texelFetch(accumulation, p, 0);
  float total = visibility(p, DEPTH_EMPTY);
#if !defined(APPROX_UNGUARDED)
  float opacity = 1.0 - total;
  if (acc.a > opacity * (1.0 + 1e-5) + 1e-6) acc.rgb *= opacity / acc.a;
#endif
  vec3 c = acc.rgb + total * backdrop_colour(p);
#endif
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p.x == p.y) c.r += 1.0 / 16.0;  // the diagonal off by 16/255: the validator must notice
#endif
  fragColour = vec4(c + oitbench_fault_hang(zero), 1.0);
}
