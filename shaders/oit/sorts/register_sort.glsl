// The register half of the register-based block sort (Knowles 2014, listings 3-5), shared by
// RBS-L (sorts/register_block.glsl) and RBS-G (sorts/register_block_global.glsl): RS, an insertion
// network unrolled by the preprocessor so every index is a constant, and load_block(), which reads
// up to RBS_M fragments of a list into registers.
// Expects: RBS_M.
#ifndef OIT_REGISTER_SORT
#define OIT_REGISTER_SORT
#pragma optionNV(unroll all)
uvec2 registers[RBS_M];

// RS (listing 5): insertion sort fully unrolled by the preprocessor into nested conditionals, so
// every index into `registers` is a constant (registers, not local memory) on every compiler. The
// outer conditionals shrink the network to the pixel's count; the inner ones stop inserting an
// element once it is in place. RS_INSj inserts element j: swap it down while out of order.
bool rs_swap(int a, int b) {
  if (FRAG_FARTHER(registers[b], registers[a])) {
    uvec2 t = registers[a];
    registers[a] = registers[b];
    registers[b] = t;
    return true;
  }
  return false;
}
#define RS_INS1 rs_swap(0, 1);
#define RS_INS2 if (rs_swap(1, 2)) { RS_INS1 }
#define RS_INS3 if (rs_swap(2, 3)) { RS_INS2 }
#define RS_INS4 if (rs_swap(3, 4)) { RS_INS3 }
#define RS_INS5 if (rs_swap(4, 5)) { RS_INS4 }
#define RS_INS6 if (rs_swap(5, 6)) { RS_INS5 }
#define RS_INS7 if (rs_swap(6, 7)) { RS_INS6 }
#define RS_INS8 if (rs_swap(7, 8)) { RS_INS7 }
#define RS_INS9 if (rs_swap(8, 9)) { RS_INS8 }
#define RS_INS10 if (rs_swap(9, 10)) { RS_INS9 }
#define RS_INS11 if (rs_swap(10, 11)) { RS_INS10 }
#define RS_INS12 if (rs_swap(11, 12)) { RS_INS11 }
#define RS_INS13 if (rs_swap(12, 13)) { RS_INS12 }
#define RS_INS14 if (rs_swap(13, 14)) { RS_INS13 }
#define RS_INS15 if (rs_swap(14, 15)) { RS_INS14 }
#define RS_INS16 if (rs_swap(15, 16)) { RS_INS15 }
#define RS_INS17 if (rs_swap(16, 17)) { RS_INS16 }
#define RS_INS18 if (rs_swap(17, 18)) { RS_INS17 }
#define RS_INS19 if (rs_swap(18, 19)) { RS_INS18 }
#define RS_INS20 if (rs_swap(19, 20)) { RS_INS19 }
#define RS_INS21 if (rs_swap(20, 21)) { RS_INS20 }
#define RS_INS22 if (rs_swap(21, 22)) { RS_INS21 }
#define RS_INS23 if (rs_swap(22, 23)) { RS_INS22 }
#define RS_INS24 if (rs_swap(23, 24)) { RS_INS23 }
#define RS_INS25 if (rs_swap(24, 25)) { RS_INS24 }
#define RS_INS26 if (rs_swap(25, 26)) { RS_INS25 }
#define RS_INS27 if (rs_swap(26, 27)) { RS_INS26 }
#define RS_INS28 if (rs_swap(27, 28)) { RS_INS27 }
#define RS_INS29 if (rs_swap(28, 29)) { RS_INS28 }
#define RS_INS30 if (rs_swap(29, 30)) { RS_INS29 }
#define RS_INS31 if (rs_swap(30, 31)) { RS_INS30 }

void register_sort(int m) {
#if RBS_M > 1
  if (m > 1) { RS_INS1 }
#endif
#if RBS_M > 2
  if (m > 2) { RS_INS2 }
#endif
#if RBS_M > 3
  if (m > 3) { RS_INS3 }
#endif
#if RBS_M > 4
  if (m > 4) { RS_INS4 }
#endif
#if RBS_M > 5
  if (m > 5) { RS_INS5 }
#endif
#if RBS_M > 6
  if (m > 6) { RS_INS6 }
#endif
#if RBS_M > 7
  if (m > 7) { RS_INS7 }
#endif
#if RBS_M > 8
  if (m > 8) { RS_INS8 }
#endif
#if RBS_M > 9
  if (m > 9) { RS_INS9 }
#endif
#if RBS_M > 10
  if (m > 10) { RS_INS10 }
#endif
#if RBS_M > 11
  if (m > 11) { RS_INS11 }
#endif
#if RBS_M > 12
  if (m > 12) { RS_INS12 }
#endif
#if RBS_M > 13
  if (m > 13) { RS_INS13 }
#endif
#if RBS_M > 14
  if (m > 14) { RS_INS14 }
#endif
#if RBS_M > 15
  if (m > 15) { RS_INS15 }
#endif
#if RBS_M > 16
  if (m > 16) { RS_INS16 }
#endif
#if RBS_M > 17
  if (m > 17) { RS_INS17 }
#endif
#if RBS_M > 18
  if (m > 18) { RS_INS18 }
#endif
#if RBS_M > 19
  if (m > 19) { RS_INS19 }
#endif
#if RBS_M > 20
  if (m > 20) { RS_INS20 }
#endif
#if RBS_M > 21
  if (m > 21) { RS_INS21 }
#endif
#if RBS_M > 22
  if (m > 22) { RS_INS22 }
#endif
#if RBS_M > 23
  if (m > 23) { RS_INS23 }
#endif
#if RBS_M > 24
  if (m > 24) { RS_INS24 }
#endif
#if RBS_M > 25
  if (m > 25) { RS_INS25 }
#endif
#if RBS_M > 26
  if (m > 26) { RS_INS26 }
#endif
#if RBS_M > 27
  if (m > 27) { RS_INS27 }
#endif
#if RBS_M > 28
  if (m > 28) { RS_INS28 }
#endif
#if RBS_M > 29
  if (m > 29) { RS_INS29 }
#endif
#if RBS_M > 30
  if (m > 30) { RS_INS30 }
#endif
#if RBS_M > 31
  if (m > 31) { RS_INS31 }
#endif
}

// Reads up to RBS_M fragments of the list from `node` into registers; returns how many.
#define RS_REP4(M, b) M(b) M(b + 1) M(b + 2) M(b + 3)
#define RS_REP8(M, b) RS_REP4(M, b) RS_REP4(M, b + 4)
#define RS_REP16(M, b) RS_REP8(M, b) RS_REP8(M, b + 8)
#define RS_REP32(M, b) RS_REP16(M, b) RS_REP16(M, b + 16)
#if RBS_M == 4
#define RS_FOR_EACH(M) RS_REP4(M, 0)
#elif RBS_M == 8
#define RS_FOR_EACH(M) RS_REP8(M, 0)
#elif RBS_M == 16
#define RS_FOR_EACH(M) RS_REP16(M, 0)
#elif RBS_M == 32
#define RS_FOR_EACH(M) RS_REP32(M, 0)
#else
#error "RBS_M must be 4, 8, 16 or 32"
#endif
#define RS_LOAD(i) if (FRAG_VALID(node)) { registers[i] = FRAG_LOAD(node); node = FRAG_NEXT(node); m = (i) + 1; }
int load_block(inout uint node) {
  int m = 0;
  RS_FOR_EACH(RS_LOAD)
  return m;
}

#endif
