#version 450 core
// Last frame's indirect irradiance (Output Radiance, or the unblurred history) seen from this frame's camera.
// Rejected (disoccluded, off-screen, first frame) pixels get 0: a defined value, never garbage.
#include "common.glsl"
#include "reprojection.glsl"
uniform sampler2D uHistory;
layout(location = 0) out vec3 oReprojected;
void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);
    vec2 prevUV;
    float w = reprojectionWeight(pix, prevUV);
    oReprojected = w > 0.0 ? sanitizeR11G11B10(texture(uHistory, prevUV).rgb, gl_FragCoord.xy) : vec3(0.0);
}
