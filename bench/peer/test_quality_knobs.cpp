// Tests the peer bench's shader edits (quality_knobs.hpp) without the peer's checkout or a GL
// context: a stand-in source that holds each landmark of TerrainEngine-OpenGL's
// volumetric_clouds.comp (d08c253) once, copied from that file. Whether the edited shader
// draws the shipped image at 64 / 6 is checked by the bench itself, on the real file.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include "quality_knobs.hpp"

#include <string>

namespace {

const std::string stand_in = R"(#version 430 core
float raymarchToLight(vec3 o, float stepSize, vec3 lightDir, float originalDensity, float lightDotEye)
{
	float ds = stepSize * 6.0;
	const float CONE_STEP = 1.0/6.0;
	for(int i = 0; i < 6; i++)
	{
		pos = startPos + coneRadius*noiseKernel[i]*float(i);
		float cloudDensity = sampleCloudDensity(pos, density > 0.3, i/16);
	}
}
vec4 raymarchToCloud(vec3 startPos, vec3 endPos, vec3 bg, out vec4 cloudPos){
	const int nSteps = 64;//int(mix(48.0, 96.0, clamp( len/SPHERE_DELTA - 1.0,0.0,1.0) ));
	startPos += dir * bayerFilter[a * 4 + b];
	for(int i = 0; i < nSteps; ++i)
	{
		float density_sample = sampleCloudDensity(pos, true, i/16);
		float light_density = raymarchToLight(pos, ds*0.1, SUN_DIR, density_sample, lightDotEye);
	}
}
)";

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

}  // namespace

TEST_CASE("the knobs replace every landmark and define the counts after #version") {
    std::string why;
    const std::string out = peer_bench::with_quality_knobs(stand_in, 128, 12, why);
    REQUIRE(why.empty());
    CHECK(out.rfind("#version 430 core\n", 0) == 0);
    CHECK(contains(out, "#define CM_VIEW_STEPS 128\n"));
    CHECK(contains(out, "#define CM_LIGHT_STEPS 12\n"));
    CHECK(contains(out, "uniform float cm_jitter = 0.0;"));
    CHECK(contains(out, "const int nSteps = CM_VIEW_STEPS;"));
    CHECK(contains(out, "for(int i = 0; i < CM_LIGHT_STEPS; i++)"));
    CHECK(contains(out, "fract(bayerFilter[a * 4 + b] + cm_jitter)"));
    CHECK(contains(out, "raymarchToLight(pos, (len / 64.0)*0.1, SUN_DIR"));
    // None of the shipped landmarks is left.
    for (const char* shipped : {"const int nSteps = 64;", "for(int i = 0; i < 6; i++)", "float ds = stepSize * 6.0;",
                                "const float CONE_STEP = 1.0/6.0;", "noiseKernel[i]*float(i)", "density > 0.3, i/16",
                                "sampleCloudDensity(pos, true, i/16)", "ds*0.1, SUN_DIR", "bayerFilter[a * 4 + b];"})
        CHECK_MESSAGE(!contains(out, shipped), shipped);
}

TEST_CASE("a missing or repeated landmark is an error that names it") {
    std::string why;
    std::string missing = stand_in;
    missing.replace(missing.find("const float CONE_STEP = 1.0/6.0;"), 5, "float");
    CHECK(peer_bench::with_quality_knobs(missing, 64, 6, why).empty());
    CHECK(contains(why, "CONE_STEP"));
    CHECK(contains(why, "found it 0 times"));

    why.clear();
    const std::string repeated = stand_in + "\tconst int nSteps = 64;\n";
    CHECK(peer_bench::with_quality_knobs(repeated, 64, 6, why).empty());
    CHECK(contains(why, "nSteps"));
    CHECK(contains(why, "found it 2 times"));

    why.clear();
    std::string no_version = stand_in;
    no_version.replace(0, 8, "#versio ");
    CHECK(peer_bench::with_quality_knobs(no_version, 64, 6, why).empty());
    CHECK(contains(why, "#version"));
}

TEST_CASE("counts out of range are refused") {
    for (const auto& [view, light] : {std::pair{0, 6}, std::pair{64, 0}, std::pair{4097, 6}, std::pair{64, 1025}, std::pair{-1, -1}}) {
        std::string why;
        CHECK(peer_bench::with_quality_knobs(stand_in, view, light, why).empty());
        CHECK(contains(why, "1 to 4096"));
    }
    std::string why;
    CHECK_FALSE(peer_bench::with_quality_knobs(stand_in, 4096, 1024, why).empty());
    CHECK(why.empty());
}
