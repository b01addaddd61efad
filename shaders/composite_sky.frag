#version 450 core
// The composite's draw for the sky's pixels on software GL (CompositePass: a depth test against layer 1's depth picks
// them, and composite.frag's draw skips them): the environment seen through each, as composite.frag shows it.
#include "common.glsl"
#include "environment.glsl"
#include "display.glsl"
layout(location = 0) out vec4 oRadiance;  // linear, unexposed
layout(location = 1) out vec4 oDisplay;   // sRGB-encoded, exposed
layout(location = 2) out vec4 oDirect;    // Direct Radiance: none on the sky
void main() {
    vec3 L = sanitize(uBackground.rgb + environmentBackdrop(gl_FragCoord.xy));
    oRadiance = vec4(L, 1.0);
    oDisplay = displayColor(L);
    oDirect = vec4(0.0);
}
