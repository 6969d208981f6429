// ctest cloud_renderer.variant_table: the switches are listed once, in scene.hpp's tables
// (CLOUD_RENDERER_VARIANT_TABLE, CLOUD_RENDERER_SCENE_SWITCHES), and every other place that
// names the permutation's constants must name the same ones: clouds.frag's and composite.frag's
// CR_PARAM lines (each shader the switches the table gives it), clouds.wgsl's overrides (both
// shaders' in one module) and the web demo's permutation values (web/demo/main.js). A switch
// added to or removed from one of them alone fails here; so does a terrain box changed on one
// side only (scene.hpp's terrain_boxes, web/demo/scene.js's terrainBoxes). Needs no OpenGL.
#include "scene.hpp"

#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

using namespace cloud_renderer;

namespace {

std::string read(const std::string& path) {
    std::ifstream in(path);
    REQUIRE_MESSAGE(in.good(), "cannot read " << path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The first group of every match of `pattern` in `text`.
std::set<std::string> matches(const std::string& text, const std::string& pattern) {
    std::set<std::string> out;
    const std::regex re(pattern, std::regex::multiline);
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it) out.insert((*it)[1].str());
    return out;
}

// The table's constants for clouds.frag: the pass, the scene's and the variant's.
std::set<std::string> clouds_constants() {
    std::set<std::string> out = {"u_pass"};
    for (const shader_constant& c : scene_constants(scene{}, switch_shader::clouds)) out.insert(c.name);
    for (const shader_constant& c : variant_constants(variant{})) out.insert(c.name);
    return out;
}

// ... for composite.frag: the scene's switches that the table gives it.
std::set<std::string> composite_constants() {
    std::set<std::string> out;
    for (const shader_constant& c : scene_constants(scene{}, switch_shader::composite)) out.insert(c.name);
    return out;
}

// Both shaders' (one WGSL module holds both).
std::set<std::string> table_constants() {
    std::set<std::string> out = clouds_constants();
    for (const std::string& n : composite_constants()) out.insert(n);
    return out;
}

std::string join(const std::set<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : " ") + n;
    return out;
}

}  // namespace

TEST_CASE("clouds.frag's and composite.frag's CR_PARAM lines are the table's constants") {
    const std::string pattern = R"(^CR_PARAM\(int, (\w+)\))";
    const std::set<std::string> frag = matches(read(CLOUD_RENDERER_SOURCE_DIR "/shaders/clouds.frag"), pattern);
    CHECK_MESSAGE(frag == clouds_constants(), "clouds.frag: " << join(frag) << "; the table: " << join(clouds_constants()));
    const std::set<std::string> composite = matches(read(CLOUD_RENDERER_SOURCE_DIR "/shaders/composite.frag"), pattern);
    CHECK_MESSAGE(composite == composite_constants(),
                  "composite.frag: " << join(composite) << "; the table: " << join(composite_constants()));
    CHECK(composite_constants() == std::set<std::string>{"u_dither"});  // the display transform's only switch
}

TEST_CASE("clouds.wgsl's overrides are the table's constants and its sky's") {
    std::set<std::string> wgsl = matches(read(CLOUD_RENDERER_SOURCE_DIR "/shaders/clouds.wgsl"), R"(^override (\w+): i32;)");
    CHECK(wgsl.erase("u_physical_sky") == 1);  // clouds.frag's #define CR_PHYSICAL_SKY
    CHECK_MESSAGE(wgsl == table_constants(), "clouds.wgsl: " << join(wgsl) << "; the table: " << join(table_constants()));
}

TEST_CASE("the web demo sets every constant of the table") {
    const std::string main_js = read(CLOUD_RENDERER_SOURCE_DIR "/../../web/demo/main.js");
    for (const std::string& name : table_constants()) CHECK_MESSAGE(main_js.find(name + ":") != std::string::npos, "web/demo/main.js sets no " << name);
}

TEST_CASE("the web demo's terrain boxes are scene.hpp's") {
    const std::string scene_js = read(CLOUD_RENDERER_SOURCE_DIR "/../../web/demo/scene.js");
    const std::smatch found = [&] {
        std::smatch m;
        std::regex_search(scene_js, m, std::regex(R"(terrainBoxes = \[(\[[^;]*\])\];)"));
        return m;
    }();
    REQUIRE_MESSAGE(!found.empty(), "web/demo/scene.js has no terrainBoxes = [...];");
    std::string want;
    for (const terrain_box& b : terrain_boxes) {
        std::ostringstream box;
        box << "[" << b.x << ", " << b.z << ", " << b.half_width << ", " << b.top << "]";
        want += (want.empty() ? "" : ", ") + box.str();
    }
    CHECK_MESSAGE(found[1].str() == want, "web/demo/scene.js: " << found[1].str() << "; scene.hpp: " << want);
}

TEST_CASE("the table's rows: each key once, each constant once, the spec round-trips") {
    const std::vector<shader_constant> v = variant_constants(variant{});
    std::set<std::string> names;
    for (const shader_constant& c : v) CHECK_MESSAGE(names.insert(c.name).second, c.name << " twice");
    variant changed;
    changed.phase = phase_model::mie;
    changed.powder = true;
    changed.occluded_ambient = false;
    changed.view_steps = 200;
    variant back;
    CHECK(apply_variant_spec(variant_spec(changed), back).empty());
    CHECK(variant_spec(back) == variant_spec(changed));
    CHECK(variant_spec(back) != variant_spec(variant{}));
}
