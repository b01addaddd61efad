#version 450 core
// Last frame's indirect irradiance (Output Radiance, or the unblurred history) seen from this frame's camera.
// Rejected (disoccluded, off-screen, first frame) pixels get 0: a defined value, never garbage. The weight goes to
// History Weight, computed once for the gather's selection and the temporal blend.
#include "common.glsl"
#include "reprojection.glsl"
uniform sampler2D uHistory;
layout(location = 0) out vec3 oReprojected;
layout(location = 1) out float oWeight;
void main() {
    ivec2 pix = ivec2(gl_FragCoord.xy);  // radiosity grid
    vec2 prevUV;
    float w = reprojectionWeight(screenPixelOfRadiosity(pix), prevUV);
    // Bilinear between the history texels around the point, each texel at the screen pixel it stands for (a grid
    // texel's centre is not its screen pixel's centre at half resolution: sampling prevUV directly would shift
    // and blur the history by a quarter texel every frame).
    float d = uRadiosityGrid.x;
    vec2 g = (prevUV * uViewport.xy - 0.5 - floor(d * 0.5)) / d + 0.5;
    vec2 uv = g / uRadiosityGrid.yz;
    oWeight = w;
    oReprojected = w > 0.0 ? sanitizeR11G11B10(texture(uHistory, uv).rgb, gl_FragCoord.xy) : vec3(0.0);
}
