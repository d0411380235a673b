// HAT, section 6.3: AT with the height metric (Eq. 6.1).
// The metric at_family.glsl (the AT family's insertion, insert/api.glsl) removes the least of.
// The height metric, Eq. 6.1: the step's height relative to the transmittance before it.
float at_error(float tPrev, float t, float zPrev, float z) {
  float h = tPrev - t;
  return h * h / GUARD(tPrev, 1e-30);
}
