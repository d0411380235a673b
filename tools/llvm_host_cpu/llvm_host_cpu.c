// A preload library that tells llvmpipe's (and lavapipe's) JIT which CPU to tune for, the one switch Mesa
// does not have: gallivm passes llvm::sys::getHostCPUName() to LLVM as -mcpu, and LLVM 15 names a Zen 4
// "znver3" but knows no Zen 5 (family 26: "generic"), so two hosts with the same ISA flags can get
// different instruction scheduling. docs/drivers.md ("The host difference") shows it in use:
//
//   LD_PRELOAD=build/liboitbench_llvm_host_cpu.so OITBENCH_LLVM_MCPU=generic
//     MESA_SHADER_CACHE_DIR=cache-generic build/oitbench run ...   (one command line)
//
// (a cache folder of its own: Mesa's shader cache keys on the renderer string, not on the CPU LLVM tuned
// for, so a shared cache would hand back the other CPU's code). Without OITBENCH_LLVM_MCPU it changes
// nothing and only says, once, on stderr, what LLVM calls this CPU.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

// llvm::StringRef: a pointer and a length, returned in two registers like this struct.
struct string_ref {
  const char* data;
  size_t size;
};

struct string_ref llvm_host_cpu_name(void) __asm__("_ZN4llvm3sys14getHostCPUNameEv");

struct string_ref llvm_host_cpu_name(void) {
  struct string_ref (*llvm_own)(void) = (struct string_ref(*)(void))dlsym(RTLD_NEXT, "_ZN4llvm3sys14getHostCPUNameEv");
  struct string_ref name = {"", 0};
  if (llvm_own) name = llvm_own();
  const char* told = getenv("OITBENCH_LLVM_MCPU");
  static int said;
  if (!said) {
    said = 1;
    if (told && *told)
      fprintf(stderr, "llvm_host_cpu: LLVM names this CPU '%.*s'; the JIT is told '%s'\n", (int)name.size, name.data,
              told);
    else
      fprintf(stderr, "llvm_host_cpu: LLVM names this CPU '%.*s'\n", (int)name.size, name.data);
  }
  if (told && *told) {
    name.data = told;
    name.size = strlen(told);
  }
  return name;
}
