// The peer's cloud renderer (TerrainEngine-OpenGL's shaders/volumetric_clouds.comp), set up
// the way its engine does it (CloudsModel, VolumetricClouds, Skybox, Main.cpp) with raw GL
// calls on the current context. Its shader files are read at run time from a checkout the
// user names; none of its code is in this repository.
#ifndef CLOUDMATH_PEER_BENCH_PEER_CLOUDS_HPP
#define CLOUDMATH_PEER_BENCH_PEER_CLOUDS_HPP

#include "image.hpp"

#include <glm/vec3.hpp>

#include <memory>
#include <string>
#include <vector>

namespace peer_bench {

// The view we impose on the peer so both renderers look the same way: our scene's compass
// heading (0 = north = -z, as in examples/cloud_renderer/scene.hpp), pitch and vertical FOV,
// and the unit direction toward the sun. Everything else is the engine's default.
struct peer_view {
    float yaw_deg = 0.0f;
    float pitch_deg = 0.0f;
    float fov_y_deg = 60.0f;
    glm::vec3 sun_dir{0.0f, 1.0f, 0.0f};
};

// Texture reads (texture() and textureLod() calls) per pixel of the peer's clouds shader.
// "Marched" pixels are those whose ray the peer marches through its cloud layer: it calls
// raymarchToCloud, i.e. the fog test (fog amount at the layer entry > 0.965) did not skip it.
struct peer_reads {
    int pixels = 0;             // in the image
    int marched = 0;            // of those, marched
    double mean = 0, p95 = 0;   // over marched pixels (all of that pixel's reads, the sky's included)
    double light_share = 0;     // reads inside raymarchToLight / all reads, over marched pixels
    bool light_attributed = false;  // false: light_share unknown, light_note says why
    std::string light_note;
    double mean_all = 0;        // over every pixel
};

class peer_clouds {
public:
    using proc_loader = void* (*)(const char* name);

    // Reads the shader files from `peer_dir`/shaders, compiles the clouds program as it is
    // and its instrumented copy (instrument.hpp), and generates the noise textures and the
    // weather map with the peer's compute shaders. nullptr and the reason on failure.
    static std::unique_ptr<peer_clouds> create(const std::string& peer_dir, proc_loader load, bool quiet, std::string& why);
    ~peer_clouds();
    peer_clouds(const peer_clouds&) = delete;
    peer_clouds& operator=(const peer_clouds&) = delete;

    // Allocates the four output images at width x height, renders the sky texture with the
    // peer's sky.frag, a "no terrain" depth map, and sets the uniforms of both programs.
    bool prepare(int width, int height, const peer_view& view, std::string& why);
    // One frame: the clouds dispatch (and the engine's image barrier) between glFinish calls;
    // wall_ms the host time from before the dispatch to the end of glFinish().
    bool dispatch(double& wall_ms, std::string& why);
    // A copy of the clouds shader with its quality knobs explicit (quality_knobs.hpp: view
    // steps, light samples, a start-offset shift), compiled and set up as the shipped one for
    // the view of the last prepare(); its handle for dispatch_quality, or -1 and the reason.
    int add_quality_program(int view_steps, int light_steps, std::string& why);
    // One frame of such a copy, its start offsets shifted by `jitter` in [0, 1); timed as dispatch().
    bool dispatch_quality(int program, float jitter, double& wall_ms, std::string& why);
    // Which pixels the last dispatch marched through the layer (1) and which the peer's fog
    // test skipped (0: its cloudDistance image holds -1 there).
    bool read_marched(std::vector<char>& mask, std::string& why);
    // One dispatch of the instrumented copy, then the counters read back.
    bool count_reads(peer_reads& out, std::string& why);
    // The fragColor image of the last dispatch (rows bottom-up, as cloud_renderer::image).
    bool read_image(cloud_renderer::image& out, std::string& why);

    struct state;

private:
    explicit peer_clouds(std::unique_ptr<state> s);
    std::unique_ptr<state> s_;
};

}  // namespace peer_bench

#endif  // CLOUDMATH_PEER_BENCH_PEER_CLOUDS_HPP
