// The library of sorts: every sort the suite runs on the GPU is one file in shaders/sorts/, written
// once against the element API below, and every experiment that sorts (sort, oit, stencil) runs
// these files, so the sort micro-benchmark times the code the OIT resolves run. Each row of those
// experiments names the file it ran and a hash of its text in the `sort_source` column.
//
// The caller "binds" the API to its array before it calls a sort (shaders/sort/frags.glsl: the sort
// experiment's ascending depth keys; shaders/oit/resolve_pixel.glsl: far-to-near fragments;
// shaders/stencil/resolve.frag: nodes by .y). A binding defines:
//   SORT_T          the element type
//   SORT_AT(i)      element i of the array being sorted, an lvalue
//   SORT_GT(a, b)   element value a belongs after element value b (strict: false for equal
//                   elements). Every sort orders SORT_AT(0 .. SORT_SIZE - 1) so that no element
//                   belongs after its successor.
//   SORT_N          the array's declared size, a compile-time constant: the network
//                   (register_sort.glsl) and SORT_EACH_INDEX (unroll.glsl) expand to it, merge
//                   sizes its scratch array by it
//   SORT_SIZE       the loop bound: how many elements the loop sorts sort. A constant (SORT_N)
//                   lets the compiler unroll the loops so every index is a constant and the array
//                   may live in registers (the register form); a value known only at run time
//                   keeps the loops and the dynamic indices (the local-memory form). The binding,
//                   not the sort, decides which form is measured.
//   SORT_SIZE_LOG2  ceil(log2(SORT_SIZE)), of the same kind (bitonic and odd-even merge only)
// Defined here from those (a binding must not define them):
//   SORT_GREATER(i, j)  SORT_GT(SORT_AT(i), SORT_AT(j))
//   SORT_SWAP(i, j)     exchanges elements i and j (a statement)
//
// The sorts, each `void sort_<file>()` unless noted; a listing's variants are injected defines
// documented in its file, never edits:
//   insertion.glsl       insertion sort (Brüll 2018 Listings 4.11 with Table A.1's writes, 4.12;
//                        Knowles 2014 Listing 1)
//   bubble.glsl          bubble sort (Brüll 2018 Listing 4.10)
//   shell.glsl           shell sort (Brüll 2018 Listings 4.13, 4.14)
//   merge.glsl           bottom-up merge sort (Knowles 2014 2.1; Knowles 2013's IMS form)
//   bitonic.glsl         bitonic network (Knowles 2014 2.4)
//   odd_even_merge.glsl  Batcher's odd-even merge network (Knowles 2014 2.4)
//   register_sort.glsl   `void sort_register(int n)`: RS, the unrolled insertion network of the
//                        register-based block sort (Knowles 2014 Listing 5)
//   unroll.glsl          SORT_EACH_INDEX(M): M(0) ... M(SORT_N - 1), for SORT_N <= 32 (no sort)
// A function named sort_<name> is a sort: it is defined here in shaders/sorts/ and nowhere else
// (tests/unit/sort_library_test.cpp checks the whole shader tree); helpers elsewhere take other names.
// A new sort: shaders/sorts/<name>.glsl defining sort_<name>() against this API; then select it
// where it runs (shaders/sort/algorithms.glsl and the variant table in micro/experiments/sort.cpp;
// shaders/oit/resolve_pixel.glsl and micro/oit/resolve_sort.cpp).
//
// Including: the shader assembler (micro/core/shader.cpp) emits a file once, at its first
// #include, whatever #if surrounds it. Include this file unconditionally before any #if that
// selects a sort; it only defines macros, so it may come before the binding.
#ifndef SORTS_API_GLSL
#define SORTS_API_GLSL

#define SORT_GREATER(i, j) SORT_GT(SORT_AT(i), SORT_AT(j))
#define SORT_SWAP(i, j)            \
  {                                \
    SORT_T sort_tmp_ = SORT_AT(i); \
    SORT_AT(i) = SORT_AT(j);       \
    SORT_AT(j) = sort_tmp_;        \
  }

#endif
