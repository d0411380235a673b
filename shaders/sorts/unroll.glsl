// SORT_EACH_INDEX(M) expands to M(0) M(1) ... M(SORT_N - 1): straight-line code with constant
// indices for any SORT_N up to 32, without token pasting (which GLSL does not promise). The
// expansion is fixed when this file is included, so SORT_N must be bound before; for SORT_N > 32
// SORT_EACH_INDEX is left undefined (a sort that needs it says so with an #error).
#ifndef SORTS_UNROLL_GLSL
#define SORTS_UNROLL_GLSL

#ifndef SORT_N
#error "bind SORT_N (sorts/api.glsl) before including sorts/unroll.glsl"
#endif

#if SORT_N <= 32
#if SORT_N > 0
#define SORT_EACH_0(M) M(0)
#else
#define SORT_EACH_0(M)
#endif
#if SORT_N > 1
#define SORT_EACH_1(M) M(1)
#else
#define SORT_EACH_1(M)
#endif
#if SORT_N > 2
#define SORT_EACH_2(M) M(2)
#else
#define SORT_EACH_2(M)
#endif
#if SORT_N > 3
#define SORT_EACH_3(M) M(3)
#else
#define SORT_EACH_3(M)
#endif
#if SORT_N > 4
#define SORT_EACH_4(M) M(4)
#else
#define SORT_EACH_4(M)
#endif
#if SORT_N > 5
#define SORT_EACH_5(M) M(5)
#else
#define SORT_EACH_5(M)
#endif
#if SORT_N > 6
#define SORT_EACH_6(M) M(6)
#else
#define SORT_EACH_6(M)
#endif
#if SORT_N > 7
#define SORT_EACH_7(M) M(7)
#else
#define SORT_EACH_7(M)
#endif
#if SORT_N > 8
#define SORT_EACH_8(M) M(8)
#else
#define SORT_EACH_8(M)
#endif
#if SORT_N > 9
#define SORT_EACH_9(M) M(9)
#else
#define SORT_EACH_9(M)
#endif
#if SORT_N > 10
#define SORT_EACH_10(M) M(10)
#else
#define SORT_EACH_10(M)
#endif
#if SORT_N > 11
#define SORT_EACH_11(M) M(11)
#else
#define SORT_EACH_11(M)
#endif
#if SORT_N > 12
#define SORT_EACH_12(M) M(12)
#else
#define SORT_EACH_12(M)
#endif
#if SORT_N > 13
#define SORT_EACH_13(M) M(13)
#else
#define SORT_EACH_13(M)
#endif
#if SORT_N > 14
#define SORT_EACH_14(M) M(14)
#else
#define SORT_EACH_14(M)
#endif
#if SORT_N > 15
#define SORT_EACH_15(M) M(15)
#else
#define SORT_EACH_15(M)
#endif
#if SORT_N > 16
#define SORT_EACH_16(M) M(16)
#else
#define SORT_EACH_16(M)
#endif
#if SORT_N > 17
#define SORT_EACH_17(M) M(17)
#else
#define SORT_EACH_17(M)
#endif
#if SORT_N > 18
#define SORT_EACH_18(M) M(18)
#else
#define SORT_EACH_18(M)
#endif
#if SORT_N > 19
#define SORT_EACH_19(M) M(19)
#else
#define SORT_EACH_19(M)
#endif
#if SORT_N > 20
#define SORT_EACH_20(M) M(20)
#else
#define SORT_EACH_20(M)
#endif
#if SORT_N > 21
#define SORT_EACH_21(M) M(21)
#else
#define SORT_EACH_21(M)
#endif
#if SORT_N > 22
#define SORT_EACH_22(M) M(22)
#else
#define SORT_EACH_22(M)
#endif
#if SORT_N > 23
#define SORT_EACH_23(M) M(23)
#else
#define SORT_EACH_23(M)
#endif
#if SORT_N > 24
#define SORT_EACH_24(M) M(24)
#else
#define SORT_EACH_24(M)
#endif
#if SORT_N > 25
#define SORT_EACH_25(M) M(25)
#else
#define SORT_EACH_25(M)
#endif
#if SORT_N > 26
#define SORT_EACH_26(M) M(26)
#else
#define SORT_EACH_26(M)
#endif
#if SORT_N > 27
#define SORT_EACH_27(M) M(27)
#else
#define SORT_EACH_27(M)
#endif
#if SORT_N > 28
#define SORT_EACH_28(M) M(28)
#else
#define SORT_EACH_28(M)
#endif
#if SORT_N > 29
#define SORT_EACH_29(M) M(29)
#else
#define SORT_EACH_29(M)
#endif
#if SORT_N > 30
#define SORT_EACH_30(M) M(30)
#else
#define SORT_EACH_30(M)
#endif
#if SORT_N > 31
#define SORT_EACH_31(M) M(31)
#else
#define SORT_EACH_31(M)
#endif

#define SORT_EACH_INDEX(M) \
  SORT_EACH_0(M) SORT_EACH_1(M) SORT_EACH_2(M) SORT_EACH_3(M) SORT_EACH_4(M) SORT_EACH_5(M) SORT_EACH_6(M) SORT_EACH_7(M) \
  SORT_EACH_8(M) SORT_EACH_9(M) SORT_EACH_10(M) SORT_EACH_11(M) SORT_EACH_12(M) SORT_EACH_13(M) SORT_EACH_14(M) SORT_EACH_15(M) \
  SORT_EACH_16(M) SORT_EACH_17(M) SORT_EACH_18(M) SORT_EACH_19(M) SORT_EACH_20(M) SORT_EACH_21(M) SORT_EACH_22(M) SORT_EACH_23(M) \
  SORT_EACH_24(M) SORT_EACH_25(M) SORT_EACH_26(M) SORT_EACH_27(M) SORT_EACH_28(M) SORT_EACH_29(M) SORT_EACH_30(M) SORT_EACH_31(M)
#endif

#endif
