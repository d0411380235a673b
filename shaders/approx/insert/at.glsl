// AT, section 3.6: sorted absolute transmittance, rect metric, underestimation.
// The metric at_family.glsl (the AT family's insertion, insert/api.glsl) removes the least of.
// The rect metric: the area the removed step leaves between the two depths.
float at_error(float tPrev, float t, float zPrev, float z) { return (z - zPrev) * (tPrev - t); }
