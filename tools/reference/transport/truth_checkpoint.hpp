// tools/reference/transport/truth_checkpoint.hpp: a whole-cloud truth traced across as many runs as it
// needs (cloudmath_volume_truth render --resume --budget-minutes N; scripts/truth.sh). A trace
// of hours outlasts the session that starts it, and a command still running when a session
// ends is killed: the render keeps its state in a checkpoint file, written atomically every
// few minutes and when its time budget runs out, and a later run continues it.
//
// What a checkpoint holds:
//   - the run's identity (preset, field, sky, size, seed, phase, sampling flags and a
//     fingerprint of the scene the tracer sees): a resume with other flags, or over a scene
//     that changed since (the renderer's field, sky or camera), is refused with a message
//     naming what differs, never merged;
//   - the plan: paths per pixel, and for adaptive sampling the pilot's (smoothed) variance and
//     cost per path per pixel, from which the plan is made and extended;
//   - per pixel the sums and sums of squares of r, g, b, the paths traced, the extinction
//     lookups (the cost) and the stream state: the next chunk's index.
//
// Unbiased and reproducible: chunk k of pixel i draws from the random stream (seed, i, k)
// (volume_tracer.hpp, trace_chunks), a resume starts at the first chunk no run has drawn, and
// chunks are merged in their order, so an interrupted and resumed render gives the numbers of
// an uninterrupted one to the bit. The plan comes from the pilot alone, whose paths are not
// averaged in (volume_tracer.hpp, "Adaptive sampling"), so each pixel's mean is unbiased.
// When the finished plan misses the noise target (the pilot underestimated the rare bright
// paths), it is extended: the same pilot, a smaller margin (target / reached), so each
// pixel's count only grows and still depends on its own samples through nothing but that one
// image-wide number; at most max_extensions times.
//
// File format (version 1; little-endian, about 84 bytes a pixel: 1.2 MB at 160 x 90):
//   "cloudmath truth checkpoint\n", "version: 1\n", then "key: value\n" lines (the identity
//   as "run.KEY", the plan's and the progress's scalars), "pixels: N\n", "data:\n", N
//   records of {pilot variance f64, pilot cost f64, planned u32, next chunk u32, paths u32,
//   sum r g b f64, sum of squares r g b f64, lookups f64}, then "end HEX16\n", the FNV-1a
//   64-bit hash of every byte before it. A file that is not one, of another version,
//   truncated, damaged or inconsistent is refused with a message naming the path and why.
#ifndef CLOUDMATH_TOOLS_TRUTH_CHECKPOINT_HPP
#define CLOUDMATH_TOOLS_TRUTH_CHECKPOINT_HPP

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "volume_tracer.hpp"

namespace cloudmath::reference::volume {

struct truth_checkpoint {
    static constexpr std::uint32_t format_version = 1;
    static constexpr unsigned max_extensions = 3;

    // What must match for a resume (keys without spaces or colons, values on one line).
    std::map<std::string, std::string> identity;

    // The plan. Adaptive: noise_target > 0, the pilot's per-pixel variance (r + g + b, per
    // path, smoothed) and cost per path, its mean radiance, and the margin the counts aim at
    // (planned for margin x noise_target). Uniform: noise_target 0, no pilot.
    double noise_target = 0.0;
    double margin = 0.0;
    double pilot_mean = 0.0;
    std::uint64_t min_paths = 2, max_paths = 2;
    unsigned extensions = 0;
    std::string pilot_note;  // for the truth file's allocation line
    std::vector<double> pilot_variance, pilot_cost;
    std::vector<std::uint64_t> planned;

    // The progress.
    std::vector<std::uint64_t> next_chunk;  // the stream state: chunk index of the next paths
    std::vector<path_tally> tally;
    double seconds = 0.0;  // tracing time over every run, the pilot's included
    unsigned runs = 0;     // runs that traced into it

    [[nodiscard]] std::size_t pixels() const { return planned.size(); }
    [[nodiscard]] std::uint64_t planned_paths() const;
    [[nodiscard]] std::uint64_t traced_paths() const;
    [[nodiscard]] bool plan_done() const;
};

// A uniform plan: `paths` per pixel (>= 1).
[[nodiscard]] truth_checkpoint uniform_plan(std::map<std::string, std::string> identity, std::size_t pixels,
                                            std::uint64_t paths);
// An adaptive plan for the noise floor `target` (the rms of the per-pixel standard errors over
// the image mean) from the pilot's smoothed variance and cost per pixel: allocate_paths
// aiming at margin x target with the pilot's mean. Throws std::invalid_argument as
// allocate_paths does, or for a pilot mean that is not positive.
[[nodiscard]] truth_checkpoint adaptive_plan(std::map<std::string, std::string> identity, std::vector<double> variance,
                                             std::vector<double> cost, double pilot_mean, double target, double margin,
                                             std::uint64_t min_paths, std::uint64_t max_paths);

// The noise floor the traced paths give (the report's definition), 0 for a black image.
[[nodiscard]] double noise_floor(const std::vector<rgb_estimate>& estimates);
[[nodiscard]] std::vector<rgb_estimate> estimates(const truth_checkpoint& c);

// Extends a finished adaptive plan that missed its target (see the top); false when it met
// it, is uniform, or has been extended max_extensions times.
bool extend_plan(truth_checkpoint& c);

// The next jobs of the plan in pixel order, each pixel's chunks in order: at most max_jobs, and
// no more than max_cost of predicted cost (job_cost's; at least one job whatever its cost).
[[nodiscard]] std::vector<chunk_job> next_jobs(const truth_checkpoint& c, std::size_t max_jobs,
                                               double max_cost = std::numeric_limits<double>::infinity());
// A job's predicted cost: its paths times the pilot's cost per path of its pixel (1 without a
// pilot).
[[nodiscard]] double job_cost(const truth_checkpoint& c, const chunk_job& j);
// Merges the tallies of trace_chunks(jobs) (jobs from next_jobs) into the checkpoint.
void merge_jobs(truth_checkpoint& c, const std::vector<chunk_job>& jobs, const std::vector<path_tally>& tallies);

// Traces the plan batch by batch (chunks merged in order) until it is done, extending it as
// extend_plan says, or until stop() (asked between batches) says so; save(c) is called every
// save_every_seconds of tracing and once at the end. Returns true when the plan is done.
// c.seconds grows by the time spent. The first batch holds batch_jobs chunks; with
// batch_seconds > 0 the next ones hold the predicted cost (job_cost) that the batches so far
// traced in about that long: a pixel's chunks cost from microseconds (the ground, the clear
// sky) to seconds, so a count of chunks is no measure (a batch sized by its count from the
// cheap rows at the bottom of an image once took in the whole cloud, 17 minutes with no
// checkpoint). A budget is so kept to within about one batch. With 0 every batch holds
// batch_jobs. The numbers do not depend on the batches.
bool continue_trace(truth_checkpoint& c, const path_tracer& tracer, const std::vector<camera_ray>& rays,
                    const mc::run_options& options, std::size_t batch_jobs, double batch_seconds,
                    double save_every_seconds, const std::function<bool()>& stop,
                    const std::function<void(const truth_checkpoint&)>& save);

// The file's bytes, and back. parse_checkpoint throws std::runtime_error("PATH: why").
[[nodiscard]] std::string serialize_checkpoint(const truth_checkpoint& c);
[[nodiscard]] truth_checkpoint parse_checkpoint(std::string_view bytes, const std::string& path);
[[nodiscard]] truth_checkpoint read_checkpoint(const std::string& path);
void write_checkpoint(const std::string& path, const truth_checkpoint& c);

// Throws std::runtime_error naming the first key whose value differs (or is missing on either
// side) between the checkpoint at `path` and this run.
void check_same_run(const truth_checkpoint& c, const std::map<std::string, std::string>& identity,
                    const std::string& path);

// A fingerprint (16 hex digits) of what the tracer sees: every camera ray, the extinction at
// points along a sample of them, the sun and what escaping paths meet. A change of the
// renderer's field, sky, sun or camera changes it, bit for bit.
[[nodiscard]] std::string scene_fingerprint(const medium& m, const lighting& light, const std::vector<camera_ray>& rays);

}  // namespace cloudmath::reference::volume

#endif  // CLOUDMATH_TOOLS_TRUTH_CHECKPOINT_HPP
