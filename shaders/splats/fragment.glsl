// The splat path of shaders/scene/fragment.glsl (SPLATS): the Gaussian evaluated at the pixel centre
// as 3DGS does (alpha = min(0.99, opacity exp(power)), discarded below 1/255 and where power > 0; with
// SPLAT_NO_DISCARD such a fragment is returned with alpha 0 instead),
// and the fragment's depth key (the splat_depth parameter):
//   centre   the mean's depth (Kerbl et al. 2023): the quad's own depth, gl_FragCoord.z
//   ray-max  SPLAT_DEPTH_RAY_MAX: the depth of the Gaussian's maximum along the pixel's ray (Radl et al.
//            2024, StopThePop): t = d^T P (mu - o) / d^T P d, P = Sigma^-1, the ray o + t d through the
//            pixel centre between the near and far planes
uniform mat4 viewProj;
uniform vec2 splatViewport;
flat in vec4 vSplatColour;
flat in vec3 vSplatConic;
flat in vec2 vSplatCentre;
flat in float vSplatViewDepth;
flat in uint vSplatPrimitive;
flat in vec3 vSplatMean;
#if defined(SPLAT_DEPTH_RAY_MAX)
flat in mat3 vSplatPrecision;
flat in mat4 vSplatInverseViewProj;
#endif

// The window depth and the view depth (clip w) of the Gaussian's maximum along the pixel's ray.
vec2 splat_depth_key() {
#if defined(SPLAT_DEPTH_RAY_MAX)
  vec2 ndc = gl_FragCoord.xy / splatViewport * 2.0 - 1.0;
  vec4 a = vSplatInverseViewProj * vec4(ndc, -1.0, 1.0), b = vSplatInverseViewProj * vec4(ndc, 1.0, 1.0);
  vec3 o = a.xyz / a.w, d = b.xyz / b.w - o;
  vec3 pd = vSplatPrecision * d;
  float t = dot(pd, vSplatMean - o) / dot(pd, d);
  vec4 clip = viewProj * vec4(o + t * d, 1.0);
  return vec2(clip.z / clip.w * 0.5 + 0.5, clip.w);
#else
  return vec2(gl_FragCoord.z, vSplatViewDepth);
#endif
}

SceneFragment splat_fragment() {
  vec2 d = gl_FragCoord.xy - vSplatCentre;
  float power = -0.5 * (vSplatConic.x * d.x * d.x + vSplatConic.z * d.y * d.y) - vSplatConic.y * d.x * d.y;
  float alpha = min(0.99, vSplatColour.a * exp(power));
#if defined(SPLAT_NO_DISCARD)
  // The caller skips alpha 0 itself: SLAB's insertion, whose spinlock lost masks on llvmpipe when the
  // invocations that take it had discarded (its image left [0, 1]; fine without the discard).
  if (power > 0.0 || alpha < 1.0 / 255.0) alpha = 0.0;
#else
  if (power > 0.0) discard;
  if (alpha < 1.0 / 255.0) discard;
#endif
  vec2 depth = splat_depth_key();
  // the shading's world position (self-shadowing) is the mean's: a splat is lit as one point
  return SceneFragment(shade_fragment(vec4(vSplatColour.rgb, alpha), vSplatMean), depth.x, depth.y,
                       vSplatPrimitive + (uint(gl_PrimitiveID) & 1u));
}
