// Builds the peer shader's copy with explicit quality knobs (quality_knobs.hpp).
#include "quality_knobs.hpp"

#include <cstddef>

namespace peer_bench {

namespace {

// One edit: `from` must occur exactly once in the peer's file (TerrainEngine-OpenGL d08c253).
struct edit {
    const char* from;
    const char* to;
};

// CM_VIEW_STEPS and CM_LIGHT_STEPS are #defined after the #version line. Each replacement is
// written so that at 64 and 6 it folds to the shipped expression exactly: 64 / CM_VIEW_STEPS
// and 6 / CM_LIGHT_STEPS are 1, (36.0 / 6.0) is 6.0, and fract(b + 0.0) is b for the Bayer
// values b in [0, 1).
const edit edits[] = {
    // The view march: its step count, and the texture level by the fraction of the ray.
    {"const int nSteps = 64;", "const int nSteps = CM_VIEW_STEPS;"},
    {"sampleCloudDensity(pos, true, i/16)", "sampleCloudDensity(pos, true, (i * 64 / CM_VIEW_STEPS)/16)"},
    // The start offset, shifted per frame.
    {"startPos += dir * bayerFilter[a * 4 + b];", "startPos += dir * fract(bayerFilter[a * 4 + b] + cm_jitter);"},
    // The light march's step: the shipped one is 6 x (0.1 x the view step), so its reach is
    // 3.6 view steps; here it is 3.6 of the shipped 64 view steps whatever the count.
    {"raymarchToLight(pos, ds*0.1, SUN_DIR", "raymarchToLight(pos, (len / 64.0)*0.1, SUN_DIR"},
    {"float ds = stepSize * 6.0;", "float ds = stepSize * (36.0 / float(CM_LIGHT_STEPS));"},
    {"const float CONE_STEP = 1.0/6.0;", "const float CONE_STEP = 1.0/float(CM_LIGHT_STEPS);"},
    {"for(int i = 0; i < 6; i++)", "for(int i = 0; i < CM_LIGHT_STEPS; i++)"},
    {"pos = startPos + coneRadius*noiseKernel[i]*float(i);",
     "pos = startPos + coneRadius*noiseKernel[i % 6]*(float(i) * (6.0 / float(CM_LIGHT_STEPS)));"},
    {"sampleCloudDensity(pos, density > 0.3, i/16)",
     "sampleCloudDensity(pos, density * (6.0 / float(CM_LIGHT_STEPS)) > 0.3, (i * 6 / CM_LIGHT_STEPS)/16)"},
};

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

}  // namespace

std::string with_quality_knobs(const std::string& peer_source, int view_steps, int light_steps, std::string& why) {
    if (view_steps < 1 || view_steps > 4096 || light_steps < 1 || light_steps > 1024) {
        why = "peer quality knobs: view steps must be 1 to 4096 and light samples 1 to 1024, not " +
              std::to_string(view_steps) + " and " + std::to_string(light_steps);
        return {};
    }
    std::string text = peer_source;
    for (const edit& e : edits) {
        const std::size_t n = count(text, e.from);
        if (n != 1) {
            why = "peer quality knobs: expected \"" + std::string(e.from) + "\" once in volumetric_clouds.comp, found it " +
                  std::to_string(n) + " times (a different version of the peer?)";
            return {};
        }
        const std::size_t at = text.find(e.from);
        text.replace(at, std::char_traits<char>::length(e.from), e.to);
    }
    const std::size_t version = text.find("#version");
    const std::size_t line_end = version == std::string::npos ? version : text.find('\n', version);
    if (line_end == std::string::npos) {
        why = "peer quality knobs: no #version line in volumetric_clouds.comp";
        return {};
    }
    const std::string knobs = "\n// ---- cloudmath peer bench: quality knobs (not part of the peer's shader) ----\n"
                              "#define CM_VIEW_STEPS " + std::to_string(view_steps) + "\n#define CM_LIGHT_STEPS " +
                              std::to_string(light_steps) + "\nuniform float " + jitter_uniform + " = 0.0;\n";
    text.insert(line_end + 1, knobs);
    return text;
}

}  // namespace peer_bench
