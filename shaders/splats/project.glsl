// One splat projected as 3D Gaussian splatting does (Kerbl et al. 2023, forward.cu: computeCov3D,
// computeCov2D, the radius), written against the view-projection the techniques already bind
// (`viewProj`) and the viewport in pixels, in GL window coordinates (gl_FragCoord's: pixel centres at
// i + 0.5, y up). The analytic CPU reference (micro/oit/splats/splat_reference.cpp) projects the same way:
//   Sigma   = R S S^T R^T, R the rotation of the normalised quaternion (w, x, y, z), S = diag(scale)
//   J       = d window / d world at the mean: (viewport / 2) (row_xy - ndc_xy' row_w) / w over the
//             view-projection's rows, ndc_xy' = ndc_xy clamped to +-1.3 (3DGS's 1.3x frustum clamp of
//             t.x / t.z; for a perspective projection this is exactly 3DGS's J W)
//   Sigma'  = J Sigma J^T + 0.3 I (the low-pass), conic = Sigma'^-1
//   radius  = ceil(3 sqrt(lambda_max)), lambda_max = (a + c) / 2 + sqrt(((a - c) / 2)^2 + b^2), Sigma'
//             = [a b; b c]: the quad [centre - radius, centre + radius]^2 in pixels bounds 3 sigma (3DGS
//             floors the root's argument at 0.1; the reference's specification does not, nor does this)
//   culled  where the mean's clip z lies outside [-w, w] (the depth range the quad is drawn at) or
//             det(Sigma') <= 0
#ifndef OIT_SPLATS_PROJECT_GLSL
#define OIT_SPLATS_PROJECT_GLSL

struct SplatProjection {
  bool visible;
  vec2 centre;      // window coordinates of the mean
  vec3 conic;       // (a, b, c) of Sigma'^-1: power = -1/2 (a dx^2 + c dy^2) - b dx dy
  float radius;     // pixels
  float ndc_depth;  // the mean's clip z / w (the quad's depth: window depth (z + 1) / 2, the centre key)
  float view_depth; // the mean's clip w (the view-space distance along the view axis)
};

// The rotation of a quaternion (w, x, y, z), normalised first (3DGS's rotation activation).
mat3 splat_rotation(vec4 q) {
  q = normalize(q);
  float r = q.x, x = q.y, y = q.z, z = q.w;
  // columns (GLSL's constructor order): the rotated local axes
  return mat3(1.0 - 2.0 * (y * y + z * z), 2.0 * (x * y + r * z), 2.0 * (x * z - r * y),  //
              2.0 * (x * y - r * z), 1.0 - 2.0 * (x * x + z * z), 2.0 * (y * z + r * x),  //
              2.0 * (x * z + r * y), 2.0 * (y * z - r * x), 1.0 - 2.0 * (x * x + y * y));
}

mat3 splat_covariance(vec3 scale, vec4 q) {
  mat3 m = splat_rotation(q) * mat3(scale.x, 0.0, 0.0, 0.0, scale.y, 0.0, 0.0, 0.0, scale.z);
  return m * transpose(m);
}

// Row i of the view-projection's upper 3x3 (what a world position's clip coordinate i grows by).
vec3 splat_clip_row(mat4 vp, int i) { return vec3(vp[0][i], vp[1][i], vp[2][i]); }

SplatProjection project_splat(vec3 mean, mat3 sigma, mat4 vp, vec2 viewport) {
  SplatProjection p;
  vec4 clip = vp * vec4(mean, 1.0);
  p.visible = clip.w > 0.0 && abs(clip.z) <= clip.w;
  vec2 half_viewport = 0.5 * viewport;
  vec2 ndc = clip.xy / clip.w;
  p.centre = (ndc + 1.0) * half_viewport;
  p.ndc_depth = clip.z / clip.w;
  p.view_depth = clip.w;
  vec2 lim = clamp(ndc, vec2(-1.3), vec2(1.3));
  vec3 rw = splat_clip_row(vp, 3);
  vec3 jx = half_viewport.x * (splat_clip_row(vp, 0) - lim.x * rw) / clip.w;
  vec3 jy = half_viewport.y * (splat_clip_row(vp, 1) - lim.y * rw) / clip.w;
  vec3 sx = sigma * jx, sy = sigma * jy;
  float a = dot(jx, sx) + 0.3, b = dot(jx, sy), c = dot(jy, sy) + 0.3;
  float det = a * c - b * b;
  p.visible = p.visible && det > 0.0;
  float inv = det > 0.0 ? 1.0 / det : 0.0;
  p.conic = vec3(c * inv, -b * inv, a * inv);
  float mid = 0.5 * (a + c), half_gap = 0.5 * (a - c);
  float lambda = mid + sqrt(half_gap * half_gap + b * b);
  p.radius = ceil(3.0 * sqrt(lambda));
  return p;
}

#endif
