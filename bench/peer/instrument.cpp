// Builds the counting copy of the peer's clouds shader (instrument.hpp). Only text edits at
// landmarks that must each be found once; anything else in the peer's file is left as it is,
// so the counted program takes the very same branches as the timed one.
#include "instrument.hpp"

namespace peer_bench {

namespace {

// Goes right after the #version line. The wrappers are declared before the macros so that
// their own texture()/textureLod() calls are the built-ins; everything after the macros, the
// peer's whole shader, calls the wrappers. Overloads for the sampler types the peer uses
// (2D: weather map and sky; 3D: the two noise volumes); an int lod converts as before.
const char* const prelude = R"(
// ---- cloudmath peer bench: texture-read counters (not part of the peer's shader) ----
uint cm_reads = 0u;         // every texture()/textureLod() call of this invocation
uint cm_light_reads = 0u;   // the ones made inside raymarchToLight
bool cm_in_light = false;
bool cm_marched = false;    // raymarchToCloud ran (the fog test did not skip the pixel)
void cm_count() { cm_reads += 1u; if (cm_in_light) cm_light_reads += 1u; }
vec4 cm_texture(sampler2D s, vec2 p) { cm_count(); return texture(s, p); }
vec4 cm_texture(sampler3D s, vec3 p) { cm_count(); return texture(s, p); }
vec4 cm_texture_lod(sampler2D s, vec2 p, float l) { cm_count(); return textureLod(s, p, l); }
vec4 cm_texture_lod(sampler3D s, vec3 p, float l) { cm_count(); return textureLod(s, p, l); }
#define texture(s, p) cm_texture(s, p)
#define textureLod(s, p, l) cm_texture_lod(s, p, l)
#define main cm_peer_main
// ---- end of the counters' prelude; the peer's shader follows ----
)";

// Appended: the real main runs the peer's and stores the counters of pixels inside the image.
const char* const epilogue = R"(
// ---- cloudmath peer bench: counter output ----
#undef main
layout(std430, binding = 0) writeonly buffer cm_counter_block { uint cm_counts[]; };
uniform ivec2 cm_size;
void main() {
    cm_peer_main();
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x < cm_size.x && p.y < cm_size.y) {
        uint i = 3u * uint(p.y * cm_size.x + p.x);
        cm_counts[i] = cm_reads;
        cm_counts[i + 1u] = cm_light_reads;
        cm_counts[i + 2u] = cm_marched ? 1u : 0u;
    }
}
)";

// Position just after the opening brace of the function whose definition starts with
// `signature` (which must occur exactly once), npos if not so.
std::size_t body_start(const std::string& text, const std::string& signature) {
    const std::size_t at = text.find(signature);
    if (at == std::string::npos || text.find(signature, at + 1) != std::string::npos) return std::string::npos;
    const std::size_t brace = text.find('{', at);
    return brace == std::string::npos ? brace : brace + 1;
}

}  // namespace

instrumented_shader instrument_texture_reads(const std::string& peer_source, std::string& why) {
    instrumented_shader out;
    std::string text = peer_source;
    const std::string changed = "the peer's volumetric_clouds.comp differs from the version this harness knows: ";

    // The light function: on at its first statement, off before its (only) return.
    const std::size_t light = body_start(text, "float raymarchToLight(");
    const std::size_t light_return = light == std::string::npos ? light : text.find("return T;", light);
    const std::size_t light_end = light == std::string::npos ? light : text.find("\n}", light);  // closing brace, column 0
    if (light == std::string::npos) {
        out.light_note = "no single definition 'float raymarchToLight(' in the peer's shader";
    } else if (light_return == std::string::npos || light_end == std::string::npos || light_return > light_end) {
        out.light_note = "the peer's raymarchToLight does not end with 'return T;'";
    } else {
        text.insert(light_return, "cm_in_light = false; ");
        text.insert(light, " cm_in_light = true;");
        out.light_attributed = true;
    }

    const std::size_t march = body_start(text, "vec4 raymarchToCloud(");
    if (march == std::string::npos) {
        why = changed + "no single definition 'vec4 raymarchToCloud('";
        return out;
    }
    text.insert(march, " cm_marched = true;");

    // After the #version line (a directive must come first; the macros must precede all use).
    const std::size_t version = text.find("#version");
    const std::size_t line_end = version == std::string::npos ? version : text.find('\n', version);
    if (line_end == std::string::npos) {
        why = changed + "no #version line";
        return out;
    }
    text.insert(line_end + 1, prelude);
    if (text.find("void main(") == std::string::npos) {
        why = changed + "no 'void main('";
        return out;
    }
    out.source = text + epilogue;
    return out;
}

}  // namespace peer_bench
