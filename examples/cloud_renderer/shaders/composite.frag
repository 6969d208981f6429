// composite.frag: the composite pass, the last of every frame (docs/integration.md, "Compose
// the clouds with your scene"). It lays the cloud layer over what lies behind it and turns the
// sum into the display colour:
//   shown = tonemap(behind * (1 - opacity) + layer) + dither.
// The layer is premultiplied linear radiance and opacity (1 - transmittance; cloud extinction is
// grey): clouds.frag's pass 0 at full resolution, or the temporal scheme's history that
// temporal_resolve.frag writes. `behind` is clouds.frag's pass 3: the sky, the ground and the
// terrain, which an engine replaces with its own scene colour. The tonemap and the dither live
// here only: the cloud pass writes linear light for a composite to use.
// cpu_renderer.cpp's composite_display is its C++ twin.
//
// The host (gl_renderer.cpp, web/demo/main.js) prepends `#version`, the permutation block (as
// for clouds.frag: `const int u_dither = 1;` and an empty CR_PARAM) and resolves the include
// below; clouds.wgsl's cr_composite is its WGSL twin.

// The permutation: the scene's switches that scene.hpp's CLOUD_RENDERER_SCENE_SWITCHES gives
// this shader (ctest cloud_renderer.variant_table checks them).
CR_PARAM(int, u_dither)  // 0 off, 1 triangular dither before the 8-bit store

uniform float u_exposure;
uniform uint u_frame;
uniform sampler2D u_layer;       // rgb the layer's premultiplied linear radiance, a its opacity
uniform sampler2D u_background;  // rgb what lies behind the layer (linear radiance)

layout(location = 0) out vec4 out_display;  // rgb the display colour in [0, 1], a the clouds' opacity

#include "cloudmath.glsl"

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 layer = texelFetch(u_layer, p, 0);
    vec3 behind = texelFetch(u_background, p, 0).rgb;
    // Exposure, the 1 - e^-x tone curve, display gamma 2.2.
    vec3 shown = pow(vec3(1.0) - exp(-(behind * (1.0 - layer.a) + layer.rgb) * u_exposure), vec3(1.0 / 2.2));
    if (u_dither != 0) {
        // Triangular dither of one 8-bit step (no banding in the sky's slow gradients); its hash
        // is another hash of the pixel than the march jitter's, new each frame.
        uint index = uint(p.x) + uint(p.y) * 8192u;
        shown += cm_triangular_dither(cm_noise_hash(cm_noise_hash(index) + u_frame * 0x9e3779b9u)) * (1.0 / 255.0);
    }
    out_display = vec4(shown, layer.a);
}
