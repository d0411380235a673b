// Local array size vs time: Knowles et al. 2013 (BMA), figure 3. Every fragment declares
// `vec4 myArray[SIZE]` and uses all of it, so no compiler can drop it.
//   VARIANT_DYNAMIC:  filled and read through indices that depend on a uniform: the array must live
//                     in local (scratch) memory.
//   VARIANT_UNROLLED: filled and summed by constant-trip loops: once unrolled every index is a
//                     constant and the compiler may keep the array in registers.
// Every value is a small integer, so the result is exact and the CPU reference compares bit for bit.
#include "../common/oitbench.glsl"

uniform int zero;  // always 0; unknown to the compiler
layout(location = 0) out vec4 fragColour;

vec4 element(ivec2 p, int i) {
  return vec4(float((p.x * (i + 1) + p.y) & 1023), float((p.y * (i + 3) + zero) & 511), float(i),
              float((p.x ^ i) & 63));
}

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 myArray[SIZE];
#if defined(VARIANT_DYNAMIC)
  for (int i = 0; i < SIZE; ++i) myArray[(i + zero) % SIZE] = element(p, i);
  vec4 r = myArray[(p.x + zero) % SIZE] + myArray[(p.y + zero) % SIZE];
#elif defined(VARIANT_UNROLLED)
  for (int i = 0; i < SIZE; ++i) myArray[i] = element(p, i);
  vec4 r = vec4(0.0);
  for (int i = 0; i < SIZE; ++i) r += myArray[i] * float(i % 3 + 1);
#else
#error "define VARIANT_DYNAMIC or VARIANT_UNROLLED"
#endif
#ifdef OITBENCH_FAULT_WRONG_RESULT
  if (p == ivec2(1, 1)) r.x += 1.0;  // one pixel off by one: the validator must notice
#endif
  fragColour = r + oitbench_fault_hang(zero);
}
