// Included by every oitbench shader: the framework's fault-injection hooks, so tests can prove
// that a broken shader is reported (compile-error), that validators fail (wrong-result, used by
// each experiment's own shader) and that the watchdog ends a hang (hang).
#ifndef OITBENCH_COMMON_GLSL
#define OITBENCH_COMMON_GLSL

#ifdef OITBENCH_FAULT_COMPILE_ERROR
this line is the injected compile error (fault=compile-error);
#endif

// Never returns when fault=hang; otherwise costs nothing. `zero` must be a uniform equal to 0.
// The loop's result feeds the output so no compiler may remove it.
float oitbench_fault_hang(int zero) {
  float spin = 0.0;
#ifdef OITBENCH_FAULT_HANG
  while (zero == 0) spin += 1.0;
#endif
  return spin;
}

#endif
