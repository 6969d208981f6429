#include "options.hpp"

#include "strict_number.hpp"

#include <cstdio>
#include <optional>
#include <sstream>
#include <vector>

namespace cloud_renderer {
namespace {

// The whole text a finite decimal number in [lo, hi] (tools/common/strict_number.hpp: no
// spaces, hexadecimal, nan or suffix).
bool to_number(const std::string& text, double lo, double hi, double& out) {
    const std::optional<double> v = cloudmath::tools::parse_finite(text);
    if (!v || *v < lo || *v > hi) return false;
    out = *v;
    return true;
}

std::string range_text(double lo, double hi) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "a number from %g to %g", lo, hi);
    return buf;
}

}  // namespace

const char* usage_text() {
    return "usage: cloudmath_cloud_renderer [mode] [options]\n"
           "modes (default: a window):\n"
           "  --headless          render once on the GPU without a window (EGL), write a PNG\n"
           "  --cpu               render with the C++ reference on all cores, write a PNG\n"
           "  --compare           render on both, print PSNR and max difference, write both PNGs\n"
           "  --bench             render every lighting variant, print ms per frame and PSNR\n"
           "                      against the reference variant as a markdown table\n"
           "  --convergence       every preset (--preset: that one) on the CPU: the variant (and one change per row)\n"
           "                      against 1024 view steps and 128-step light marches of the same\n"
           "                      lighting model, PSNR of the image and of the horizon band\n"
           "  --list-presets      print the scene presets\n"
           "  --print-sky         print the frame's sky and sun (JSON: the sun by height, the sky's\n"
           "                      zenith and horizon, the ground, the sky light, EV100) for the scene\n"
           "  --dump-shader       print the fragment shader as compiled for the variant and\n"
           "                      --pass (frame, temporal, shadow, background: clouds.frag's passes,\n"
           "                      one program each, as the renderer compiles them; composite: composite.frag)\n"
           "options:\n"
           "  --preset NAME       scene preset (default: ground; see --list-presets)\n"
           "  --variant SPEC      lighting variant over the defaults (the diffusion model, 6-step\n"
           "                      light marches toward the sun and away from it, opaque view steps\n"
           "                      refined, the far field toward a low sun in 12 steps), e.g.\n"
           "                      phase=mie,lighting=octaves,octaves=4,powder=on,light=cone,\n"
           "                      behind=cone,light-steps=32,integration=naive,steps=128,refine=1,\n"
           "                      schedule=growing,ambient=flat,reach=band\n"
           "  --without LIST      leave out of the picture any of sun-disc, haze (aerial perspective),\n"
           "                      shadows (the clouds' on the ground), dither, terrain (the mountains\n"
           "                      preset's boxes; the scene's switches), e.g. --without haze,dither\n"
           "  --width N, --height N   image size (default 1280 x 720; 16 to 8192)\n"
           "  --out FILE          PNG to write (default clouds.png; --cpu: clouds_cpu.png;\n"
           "                      --compare: FILE and FILE with _cpu before .png)\n"
           "  --bench-out FILE    also write the --bench table to FILE\n"
           "  --accumulate N      --headless, --cpu, --compare: the average of frames 0..N-1, each\n"
           "                      with its own march jitter (deterministic; default 1)\n"
           "  --temporal N        --headless, --cpu, --compare: frames 0..N-1 of the temporal scheme\n"
           "                      (1 of 16 pixels shaded per frame, the rest reprojected from the\n"
           "                      history; 128 frames converge a still camera), the last written;\n"
           "                      --cpu also prints its PSNR against a full render of that frame\n"
           "  --pan DEG, --drift M    --temporal: camera yaw and wind (+x) added per frame\n"
           "  --save-every N      --temporal: also write every Nth frame as FILE_fNNN.png\n"
           "  --frames N          --bench: timed frames per variant, after one warm-up (default 3);\n"
           "                      window: close after N frames (default: when closed)\n"
           "  --min-psnr DB       --compare: exit with status 1 if the PSNR is below DB\n"
           "  --cache DIR         texture cache directory (default ~/.cache/cloudmath; none: off)\n"
           "  --altitude M, --yaw DEG, --pitch DEG, --fov DEG          camera\n"
           "  --sun-elevation DEG, --sun-azimuth DEG                   sun\n"
           "  --coverage X, --cloud-type X (0 stratus .. 1 cumulus), --exposure X\n"
           "  --sky S             the sun and sky: physical (default: cloudmath's atmosphere, lux and\n"
           "                      cd/m^2, exposure from EV100) or artistic (hand-made colours,\n"
           "                      --exposure)\n"
           "  --ev100 X           --sky physical: the exposure value (-10..25; default: the one that\n"
           "                      exposes the sky's mean luminance to middle grey)\n"
           "  --shape S           the density field: detailed (default: per-cloud type and top from the\n"
           "                      weather map, rounded tops, curl-distorted detail, crisp edges, a\n"
           "                      240 km weather period) or classic (one profile, 60 km period)\n"
           "  --quiet             no progress lines\n"
           "  --help              this text\n";
}

std::string parse_options(int argc, const char* const* argv, options& o) {
    std::vector<std::string> args(argv + 1, argv + argc);
    bool mode_given = false, pass_given = false, exposure_given = false, ev100_given = false;
    const auto set_mode = [&](run_mode m, const std::string& flag) -> std::string {
        if (mode_given && o.mode != m) return "choose one mode; " + flag + " conflicts with an earlier mode flag";
        o.mode = m;
        mode_given = true;
        return {};
    };
    // The preset first, wherever it is, so that scene flags always override it.
    for (std::size_t i = 0; i + 1 < args.size(); ++i)
        if (args[i] == "--preset") {
            const scene* p = find_preset(args[i + 1]);
            if (p == nullptr) {
                std::string names;
                for (const scene& s : presets()) names += (names.empty() ? "" : ", ") + s.name;
                return "unknown preset '" + args[i + 1] + "' (known: " + names + ")";
            }
            o.sc = *p;
            o.preset_given = true;
        }
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const auto value = [&](std::string& v) -> bool {
            if (i + 1 >= args.size()) return false;
            v = args[++i];
            return true;
        };
        // A numeric option in [lo, hi]; writes the value through `store`.
        const auto number = [&](double lo, double hi, auto store) -> std::string {
            std::string v;
            if (!value(v)) return a + " needs a value (" + range_text(lo, hi) + ")";
            double x = 0;
            if (!to_number(v, lo, hi, x)) return a + " must be " + range_text(lo, hi) + ", not '" + v + "'";
            store(x);
            return {};
        };
        std::string err;
        if (a == "--headless") err = set_mode(run_mode::headless, a);
        else if (a == "--cpu") err = set_mode(run_mode::cpu, a);
        else if (a == "--compare") err = set_mode(run_mode::compare, a);
        else if (a == "--bench") err = set_mode(run_mode::bench, a);
        else if (a == "--convergence") err = set_mode(run_mode::convergence, a);
        else if (a == "--list-presets") err = set_mode(run_mode::list_presets, a);
        else if (a == "--dump-shader") err = set_mode(run_mode::dump_shader, a);
        else if (a == "--print-sky") err = set_mode(run_mode::print_sky, a);
        else if (a == "--help" || a == "-h") err = set_mode(run_mode::help, a);
        else if (a == "--run-time" || a == "--compile-time")
            return a + " was removed: the renderer compiles one program per permutation, as engines ship them "
                       "(the run-time uber-shader's numbers: docs/lighting_research.md, \"Switches removed\")";
        else if (a == "--quiet") o.quiet = true;
        else if (a == "--preset") {
            std::string v;
            if (!value(v)) return "--preset needs a name (see --list-presets)";  // applied above
        } else if (a == "--variant") {
            std::string v;
            if (!value(v)) return "--variant needs a spec such as phase=mie,octaves=4";
            err = apply_variant_spec(v, o.var);
            if (!err.empty()) return "--variant: " + err;
        } else if (a == "--width") err = number(16, 8192, [&](double x) { o.width = static_cast<int>(x); });
        else if (a == "--height") err = number(16, 8192, [&](double x) { o.height = static_cast<int>(x); });
        else if (a == "--frames") err = number(1, 100000, [&](double x) { o.frames = static_cast<int>(x); o.frames_given = true; });
        else if (a == "--temporal") err = number(1, 100000, [&](double x) { o.temporal = static_cast<int>(x); });
        else if (a == "--save-every") err = number(1, 100000, [&](double x) { o.save_every = static_cast<int>(x); });
        else if (a == "--pan") err = number(-45, 45, [&](double x) { o.pan = float(x); });
        else if (a == "--drift") err = number(-10000, 10000, [&](double x) { o.drift = float(x); });
        else if (a == "--accumulate") err = number(1, 4096, [&](double x) { o.accumulate = static_cast<int>(x); });
        else if (a == "--min-psnr") err = number(0, 200, [&](double x) { o.min_psnr = x; });
        else if (a == "--altitude") err = number(0, 100000, [&](double x) { o.sc.camera_altitude = float(x); });
        else if (a == "--yaw") err = number(-360, 360, [&](double x) { o.sc.yaw = float(x); });
        else if (a == "--pitch") err = number(-89, 89, [&](double x) { o.sc.pitch = float(x); });
        else if (a == "--fov") err = number(10, 120, [&](double x) { o.sc.fov_y = float(x); });
        else if (a == "--sun-elevation") err = number(-10, 90, [&](double x) { o.sc.sun_elevation = float(x); });
        else if (a == "--sun-azimuth") err = number(-360, 360, [&](double x) { o.sc.sun_azimuth = float(x); });
        else if (a == "--coverage") err = number(0, 1, [&](double x) { o.sc.coverage = float(x); });
        else if (a == "--cloud-type") err = number(0, 1, [&](double x) { o.sc.cloud_type = float(x); });
        else if (a == "--exposure") err = number(0.01, 100, [&](double x) { o.sc.exposure = float(x); exposure_given = true; });
        else if (a == "--ev100") err = number(-10, 25, [&](double x) { o.sc.ev100 = float(x); ev100_given = true; });
        else if (a == "--sky") {
            std::string v;
            if (!value(v)) return "--sky needs artistic or physical";
            const std::optional<sky_model> m = sky_model_named(v);
            if (!m) return "--sky must be artistic or physical, not '" + v + "'";
            o.sc.sky = *m;
        } else if (a == "--without") {
            std::string v;
            if (!value(v)) return "--without needs a list of " + scene_switch_names();
            std::stringstream items(v);
            std::string item;
            while (std::getline(items, item, ','))
                if (!turn_off_scene_switch(o.sc, item)) return "--without takes " + scene_switch_names() + ", not '" + item + "'";
        } else if (a == "--shape") {
            std::string v;
            if (!value(v)) return "--shape needs classic or detailed";
            if (v == "classic") o.sc.shape = cloud_shape::classic;
            else if (v == "detailed") o.sc.shape = cloud_shape::detailed;
            else return "--shape must be classic or detailed, not '" + v + "'";
        } else if (a == "--pass") {
            std::string v;
            if (!value(v)) return "--pass needs frame, temporal, shadow, background or composite";
            const char* names[4] = {"frame", "temporal", "shadow", "background"};
            o.pass = v == "composite" ? composite_pass_option : -1;
            for (int p = 0; p < 4; ++p)
                if (v == names[p]) o.pass = p;
            if (o.pass < 0) return "--pass must be frame, temporal, shadow, background or composite, not '" + v + "'";
            pass_given = true;
        } else if (a == "--out" || a == "--bench-out" || a == "--cache") {
            std::string v;
            if (!value(v) || v.empty()) return a + " needs a path";
            (a == "--out" ? o.out : a == "--bench-out" ? o.bench_out : o.cache_dir) = v;
        } else {
            return "unknown option '" + a + "' (see --help)";
        }
        if (!err.empty()) return err;
        // Whole-number options given a fraction: say so rather than truncate silently.
        if ((a == "--width" || a == "--height" || a == "--frames" || a == "--accumulate" || a == "--temporal" ||
             a == "--save-every") && args[i].find_first_not_of("0123456789") != std::string::npos)
            return a + " must be a whole number, not '" + args[i] + "'";
    }
    if (pass_given && o.mode != run_mode::dump_shader) return "--pass is an option of --dump-shader";
    // Each sky has its own exposure: the other's would be ignored, so say so.
    if (exposure_given && o.sc.sky == sky_model::physical)
        return "--exposure is the artistic sky's (--sky artistic); the physical sky's exposure is --ev100";
    if (ev100_given && o.sc.sky == sky_model::artistic)
        return "--ev100 is the physical sky's; the artistic sky's exposure is --exposure";
    if (o.temporal > 0 && o.accumulate > 1) return "--temporal and --accumulate exclude each other (the scheme accumulates itself)";
    if ((o.pan != 0.0f || o.drift != 0.0f || o.save_every > 0) && o.temporal == 0)
        return "--pan, --drift and --save-every need --temporal N";
    return {};
}

}  // namespace cloud_renderer
