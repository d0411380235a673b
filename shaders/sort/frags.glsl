// The per-pixel fragment array every sort and insertion is written against, and the only place
// that knows where it lives. A fragment is 64 bits as in Knowles 2014 and Brüll 2018: x = the
// 32-bit depth key (float bits), y = RGBA8 colour packed into 32 bits.
//
// Injected defines:
//   SORT_N            elements per pixel (the array's declared size)
//   SORT_N_LOG2       ceil(log2(SORT_N)), for the power-of-two networks
//   MEMORY_REGISTERS  loop bounds are the constant SORT_N: loops unroll, every index becomes a
//                     constant and the compiler may keep `frags` in registers (Knowles 2014 Listing 2, right)
//   MEMORY_LOCAL      loop bounds are the uniform `count` (== SORT_N, unknown to the compiler): loops
//                     stay loops, indices stay dynamic and `frags` must live in indexable local memory
//                     (Listing 2, left) - the way a resolve with a per-pixel fragment count is written
//
// The API the algorithms use (never `frags` or `count` directly):
//   SORT_T                  the element type
//   SORT_AT(i)              element i, an lvalue
//   SORT_KEY(v)             the sort key of an element value (float depth)
//   SORT_GT(a, b)           key(a) > key(b), for element values
//   SORT_GREATER(i, j)      key at i > key at j
//   SORT_SWAP(i, j)         exchange elements i and j
//   SORT_SIZE, SORT_SIZE_LOG2   loop bounds (constant or uniform, see above)
#ifndef SORT_FRAGS_GLSL
#define SORT_FRAGS_GLSL

#if !defined(SORT_N) || !defined(SORT_N_LOG2)
#error "define SORT_N and SORT_N_LOG2"
#endif

layout(std430, binding = 0) readonly buffer InFrags { uvec2 in_frags[]; };
layout(std430, binding = 1) writeonly buffer OutFrags { uvec2 out_frags[]; };

uniform int count;       // == SORT_N
uniform int count_log2;  // == SORT_N_LOG2
uniform int zero;        // == 0
uniform ivec2 image_size;

#define SORT_T uvec2
// A global, never a function argument: GLSL copies array arguments in and out (Knowles 2014, 2.7).
SORT_T frags[SORT_N];

#define SORT_AT(i) frags[i]
#define SORT_KEY(v) uintBitsToFloat((v).x)
#define SORT_GT(a, b) (SORT_KEY(a) > SORT_KEY(b))
#define SORT_GREATER(i, j) SORT_GT(frags[i], frags[j])
#define SORT_SWAP(i, j)      \
  {                          \
    SORT_T sort_tmp_ = frags[i]; \
    frags[i] = frags[j];     \
    frags[j] = sort_tmp_;    \
  }

#if defined(MEMORY_REGISTERS)
#define SORT_SIZE SORT_N
#define SORT_SIZE_LOG2 SORT_N_LOG2
#elif defined(MEMORY_LOCAL)
#define SORT_SIZE count
#define SORT_SIZE_LOG2 count_log2
#else
#error "define MEMORY_REGISTERS or MEMORY_LOCAL"
#endif

int sort_pixel_index(ivec2 p) { return p.y * image_size.x + p.x; }

void sort_load(ivec2 p) {
  int base = sort_pixel_index(p) * SORT_N;
  for (int i = 0; i < SORT_SIZE; ++i) SORT_AT(i) = in_frags[base + i];
}

void sort_store(ivec2 p) {
  int base = sort_pixel_index(p) * SORT_N;
  for (int i = 0; i < SORT_SIZE; ++i) out_frags[base + i] = SORT_AT(i);
}

#endif
