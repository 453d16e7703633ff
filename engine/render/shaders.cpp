// SPDX-License-Identifier: MIT
#include "cleave/render/shaders.h"

#include "cleave/render/renderer.h"

// The joint array size of the skinning shaders, spelled out for the GLSL source.
#define CLEAVE_MAX_SKIN_JOINTS_STRING "128"
static_assert(cleave::render::kMaxSkinJoints == 128, "update CLEAVE_MAX_SKIN_JOINTS_STRING");

namespace cleave::render::shaders {

// The sky is a function, not a texture: the sky pass draws it and metal materials reflect it.
#define CLEAVE_SKY_FUNCTION                                                              \
  "vec3 skyColor(vec3 dir, vec3 sunDir) {\n"                                             \
  "  float h = clamp(dir.y, -1.0, 1.0);\n"                                               \
  "  vec3 zenith = vec3(0.07, 0.20, 0.55);\n"                                            \
  "  vec3 horizon = vec3(0.50, 0.62, 0.80);\n"                                           \
  "  vec3 ground = vec3(0.30, 0.28, 0.26);\n"                                            \
  "  vec3 c = h >= 0.0 ? mix(horizon, zenith, pow(h, 0.55)) : mix(horizon, ground, pow(-h, 0.4));\n" \
  "  float s = max(dot(dir, -sunDir), 0.0);\n"                                           \
  "  c += vec3(1.0, 0.9, 0.7) * (pow(s, 600.0) * 6.0 + pow(s, 12.0) * 0.25);\n"          \
  "  return c;\n"                                                                        \
  "}\n"                                                                                  \
  "vec3 toDisplay(vec3 c) {\n" /* ACES fit (Narkowicz 2015), then gamma 2.2 */            \
  "  c *= 0.8;\n"                                                                           \
  "  c = clamp((c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14), 0.0, 1.0);\n"  \
  "  return pow(c, vec3(1.0 / 2.2));\n"                                                 \
  "}\n"

// Linear blend skinning, shared by the lit and the shadow pass. Static meshes draw with uSkinned
// false (their joint attributes are disabled and never read). The blend is divided by the weight
// sum, as MeshContainer::setSkinningPose does, so GPU and CPU poses match.
#define CLEAVE_SKINNING                                                                  \
  "layout(location = 4) in uvec4 aJoints;\n"                                             \
  "layout(location = 5) in vec4 aWeights;\n"                                             \
  "uniform bool uSkinned;\n"                                                             \
  "uniform mat4 uJoints[" CLEAVE_MAX_SKIN_JOINTS_STRING "];\n"                            \
  "mat4 skinMatrix() {\n"                                                                \
  "  if (!uSkinned) return mat4(1.0);\n"                                                 \
  "  float total = aWeights.x + aWeights.y + aWeights.z + aWeights.w;\n"                 \
  "  if (total <= 0.0) return mat4(1.0);\n"                                              \
  "  mat4 m = aWeights.x * uJoints[aJoints.x] + aWeights.y * uJoints[aJoints.y] +\n"      \
  "           aWeights.z * uJoints[aJoints.z] + aWeights.w * uJoints[aJoints.w];\n"      \
  "  return m / total;\n"                                                                \
  "}\n"

const char* const kMeshVertex = "#version 330 core\n"
    "layout(location = 0) in vec3 aPosition;\n"
    "layout(location = 1) in vec3 aNormal;\n"
    "layout(location = 2) in vec2 aUv;\n"
    "layout(location = 3) in vec4 aTangent;\n" CLEAVE_SKINNING R"(
uniform mat4 uModel;
uniform mat3 uNormalMatrix;
uniform mat4 uViewProj;
uniform mat4 uLightViewProj;
out vec3 vWorldPos;
out vec3 vNormal;
out vec2 vUv;
out vec4 vLightPos;
void main() {
  mat4 skin = skinMatrix();
  vec4 world = uModel * (skin * vec4(aPosition, 1.0));
  vWorldPos = world.xyz;
  vNormal = normalize(uNormalMatrix * (mat3(skin) * aNormal));
  vUv = aUv;
  vLightPos = uLightViewProj * world;
  gl_Position = uViewProj * world;
}
)";

const char* const kMeshFragment =
    "#version 330 core\n"
    "in vec3 vWorldPos;\n"
    "in vec3 vNormal;\n"
    "in vec2 vUv;\n"
    "in vec4 vLightPos;\n"
    "uniform int uShading;\n"
    "uniform vec4 uBaseColor;\n"
    "uniform bool uHasAlbedo;\n"
    "uniform sampler2D uAlbedo;\n"
    "uniform sampler2DShadow uShadowMap;\n"
    "uniform bool uShadows;\n"
    "uniform bool uShadowSoft;\n"
    "uniform float uSpecular;\n"
    "uniform float uShininess;\n"
    "uniform float uReflectivity;\n"
    "uniform float uCheckerScale;\n"
    "uniform vec4 uCheckerColor;\n"
    "uniform vec3 uSunDir;\n"
    "uniform vec3 uSunColor;\n"
    "uniform vec3 uAmbient;\n"
    "uniform vec3 uCameraPos;\n"
    "out vec4 fragColor;\n" CLEAVE_SKY_FUNCTION
    R"(
float shadowFactor(vec3 n) {
  if (!uShadows) return 1.0;
  vec3 p = vLightPos.xyz / vLightPos.w * 0.5 + 0.5;
  if (p.z > 1.0 || p.x < 0.0 || p.x > 1.0 || p.y < 0.0 || p.y > 1.0) return 1.0;
  float bias = max(0.0015 * (1.0 - dot(n, -uSunDir)), 0.0004);
  // One linear-filtered tap (four depth tests) at reduced render scales.
  if (!uShadowSoft) return texture(uShadowMap, vec3(p.xy, p.z - bias));
  vec2 texel = 1.0 / vec2(textureSize(uShadowMap, 0));
  // Four taps half a texel off centre: with linear comparison filtering each tap already blends
  // four depth tests, so the result is as soft as a 3x3 kernel at less than half the cost.
  float sum = 0.0;
  sum += texture(uShadowMap, vec3(p.xy + vec2(-0.5, -0.5) * texel, p.z - bias));
  sum += texture(uShadowMap, vec3(p.xy + vec2(0.5, -0.5) * texel, p.z - bias));
  sum += texture(uShadowMap, vec3(p.xy + vec2(-0.5, 0.5) * texel, p.z - bias));
  sum += texture(uShadowMap, vec3(p.xy + vec2(0.5, 0.5) * texel, p.z - bias));
  return sum * 0.25;
}
void main() {
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;
  if (uShading == 2) {  // debug normals
    fragColor = vec4(n * 0.5 + 0.5, 1.0);
    return;
  }
  vec4 base = uBaseColor;
  if (uHasAlbedo) base *= texture(uAlbedo, vUv);
  if (uShading == 1 || uShading == 4) {  // checker: 2D on the floor, 3D solid texture otherwise
    vec3 q = floor(vWorldPos * uCheckerScale);
    float parity = uShading == 1 ? mod(q.x + q.z, 2.0) : mod(q.x + q.y + q.z, 2.0);
    base = mix(base, uCheckerColor, parity);
  }
  if (uShading == 3) {  // unlit
    fragColor = vec4(base.rgb, base.a);
    return;
  }
  vec3 v = normalize(uCameraPos - vWorldPos);
  vec3 l = -uSunDir;
  float ndl = max(dot(n, l), 0.0);
  float shadow = ndl > 0.0 ? shadowFactor(n) : 0.0;
  vec3 h = normalize(l + v);
  float spec = pow(max(dot(n, h), 0.0), uShininess) * uSpecular * (ndl > 0.0 ? 1.0 : 0.0);
  float hemi = 0.6 + 0.4 * n.y;
  vec3 color = base.rgb * (uAmbient * hemi + uSunColor * ndl * shadow) + uSunColor * spec * shadow;
  if (uReflectivity > 0.0) {
    vec3 r = reflect(-v, n);
    float fresnel = uReflectivity + (1.0 - uReflectivity) * pow(1.0 - max(dot(n, v), 0.0), 5.0);
    color = mix(color, skyColor(r, uSunDir) * base.rgb * (0.35 + 0.65 * shadow), fresnel);
  }
  // Distance fog towards the horizon colour keeps the far floor calm.
  float dist = length(uCameraPos - vWorldPos);
  if (dist > 25.0) {  // the sky colour is only needed where there is fog
    float fog = 1.0 - exp(-(dist - 25.0) * 0.02);
    color = mix(color, skyColor(normalize(vWorldPos - uCameraPos) * vec3(1.0, 0.0, 1.0) + vec3(0.0, 0.02, 0.0), uSunDir), fog);
  }
  fragColor = vec4(toDisplay(color), base.a);
}
)";

const char* const kShadowVertex = "#version 330 core\n"
    "layout(location = 0) in vec3 aPosition;\n" CLEAVE_SKINNING R"(
uniform mat4 uLightMvp;
void main() { gl_Position = uLightMvp * (skinMatrix() * vec4(aPosition, 1.0)); }
)";

const char* const kShadowFragment = R"(#version 330 core
void main() {}
)";

const char* const kSkyVertex = R"(#version 330 core
out vec2 vNdc;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  vNdc = p;
  gl_Position = vec4(p, 1.0, 1.0);
}
)";

const char* const kSkyFragment =
    "#version 330 core\n"
    "in vec2 vNdc;\n"
    "uniform mat4 uInvViewProj;\n"
    "uniform vec3 uSunDir;\n"
    "out vec4 fragColor;\n" CLEAVE_SKY_FUNCTION
    R"(
void main() {
  vec4 a = uInvViewProj * vec4(vNdc, -1.0, 1.0);
  vec4 b = uInvViewProj * vec4(vNdc, 1.0, 1.0);
  vec3 dir = normalize(b.xyz / b.w - a.xyz / a.w);
  vec3 color = skyColor(dir, uSunDir);
  fragColor = vec4(toDisplay(color), 1.0);
}
)";

const char* const kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec4 aColor;
uniform mat4 uMatrix;
out vec4 vColor;
void main() {
  vColor = aColor;
  gl_Position = uMatrix * vec4(aPosition, 1.0);
}
)";

const char* const kLineFragment = R"(#version 330 core
in vec4 vColor;
out vec4 fragColor;
void main() { fragColor = vColor; }
)";

}  // namespace cleave::render::shaders
