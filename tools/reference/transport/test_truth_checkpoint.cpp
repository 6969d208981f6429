// Tests of the checkpointed truth render (truth_checkpoint.hpp): a render stopped and resumed,
// through its file, gives estimate_radiance's numbers to the bit (so the same unbiased
// estimate, with every chunk on a stream of its own); a plan that misses its noise target is
// extended, its counts only growing; a malformed, damaged, other-version or mismatched
// checkpoint is refused with a message saying why; the scene fingerprint sees a changed
// medium, light or camera.
#include "montecarlo_detail.hpp"
#include "truth_checkpoint.hpp"
#include "volume_tracer.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace mc = cloudmath::reference::mc;
namespace vt = cloudmath::reference::volume;

namespace {

mc::run_options options(unsigned threads) {
    mc::run_options o;
    o.seed = 5;
    o.threads = threads;
    return o;
}

// A sphere of optical diameter 4 under a sun and a blue sky, seen by 6 rays.
struct sphere_scene {
    vt::homogeneous_sphere sphere{2.0};
    mc::phase_model phase = mc::make_phase("hg:0.85");
    vt::lighting light;
    std::vector<vt::camera_ray> rays;
    sphere_scene() {
        light.sun_direction = {0.3, 0.0, 1.0};
        light.sun_irradiance = {1.0, 0.9, 0.8};
        light.escaped = [](const mc::vec3&, const mc::vec3& d, bool ground) {
            return ground ? vt::rgb{0.1, 0.1, 0.1} : vt::rgb{0.2, 0.3, 0.5 + 0.1 * d.z};
        };
        for (int i = 0; i < 6; ++i) {
            vt::camera_ray r;
            r.origin = {-0.9 + 0.35 * i, 0.1, -5.0};
            r.direction = {0.0, 0.0, 1.0};
            rays.push_back(r);
        }
    }
};

std::map<std::string, std::string> identity() { return {{"preset", "sphere"}, {"seed", "5"}}; }

void require_same(const std::vector<vt::rgb_estimate>& a, const std::vector<vt::rgb_estimate>& b) {
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].r.mean == b[i].r.mean);
        CHECK(a[i].g.mean == b[i].g.mean);
        CHECK(a[i].b.mean == b[i].b.mean);
        CHECK(a[i].r.std_error == b[i].r.std_error);
        CHECK(a[i].b.std_error == b[i].b.std_error);
    }
}

// Traces c in batches of batch_jobs, stopping after `batches` batches (0: to the end).
bool trace(vt::truth_checkpoint& c, const sphere_scene& s, unsigned threads, std::size_t batch_jobs, int batches) {
    const vt::path_tracer tracer(s.sphere, s.phase, 0.99, s.light);
    int done = 0;
    return vt::continue_trace(c, tracer, s.rays, options(threads), batch_jobs, 0.0, 1e9,
                              [&]() { return batches > 0 && done++ >= batches; }, nullptr);
}

// The message of the exception parse_checkpoint throws, or "" when it accepts the bytes.
std::string refusal(const std::string& bytes) {
    try {
        (void)vt::parse_checkpoint(bytes, "ck.bin");
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("a render stopped, written, read back and resumed is the uninterrupted one to the bit") {
    const sphere_scene s;
    const vt::path_tracer tracer(s.sphere, s.phase, 0.99, s.light);
    // 5000 paths a ray: two chunks each (4096 + 904), so a stop can fall inside a ray's chunks.
    const std::vector<std::uint64_t> counts(s.rays.size(), 5000);
    const auto want = vt::estimate_radiance(tracer, s.rays, counts, options(2));

    vt::truth_checkpoint c = vt::uniform_plan(identity(), s.rays.size(), 5000);
    CHECK_FALSE(trace(c, s, 2, 3, 1));  // one batch of 3 chunks, then stopped
    CHECK(c.traced_paths() == 4096 + 904 + 4096);
    CHECK(c.next_chunk[0] == 2);
    CHECK(c.next_chunk[1] == 1);
    CHECK(c.next_chunk[2] == 0);
    // The stream state goes on from where the first run stopped: no chunk is drawn twice.
    const std::vector<vt::chunk_job> next = vt::next_jobs(c, 2);
    REQUIRE(next.size() == 2);
    CHECK((next[0].ray == 1 && next[0].chunk == 1 && next[0].paths == 904));
    CHECK((next[1].ray == 2 && next[1].chunk == 0 && next[1].paths == 4096));

    vt::truth_checkpoint resumed = vt::parse_checkpoint(vt::serialize_checkpoint(c), "ck.bin");
    CHECK(resumed.identity == c.identity);
    CHECK(trace(resumed, s, 1, 5, 0));  // another thread count and batch size
    CHECK(resumed.traced_paths() == 6 * 5000);
    require_same(vt::estimates(resumed), want);
    // Every chunk of every ray merged once, in order.
    for (const std::uint64_t k : resumed.next_chunk) CHECK(k == 2);
    CHECK(vt::next_jobs(resumed, 10).empty());
}

TEST_CASE("batches sized by time give the same numbers as fixed ones") {
    const sphere_scene s;
    const vt::path_tracer tracer(s.sphere, s.phase, 0.99, s.light);
    vt::truth_checkpoint fixed = vt::uniform_plan(identity(), s.rays.size(), 9000);
    vt::truth_checkpoint timed = fixed;
    CHECK(trace(fixed, s, 2, 4, 0));
    int batches = 0;
    CHECK(vt::continue_trace(timed, tracer, s.rays, options(2), 1, 1e-4, 1e9, [&]() { return ++batches > 1000; }, nullptr));
    CHECK(batches > 3);  // 18 chunks in batches of 1 or more
    require_same(vt::estimates(timed), vt::estimates(fixed));
}

TEST_CASE("next_jobs: batches bounded by the pilot's predicted cost, at least one job") {
    // Cheap pixels first (the ground, the clear sky), then costly ones (the clouds): a batch of
    // the cheap ones' rate must not run on into the costly ones.
    const std::vector<double> variance(6, 1.0), cost{1.0, 1.0, 1.0, 1000.0, 1000.0, 1000.0};
    const vt::truth_checkpoint c = vt::adaptive_plan(identity(), variance, cost, 0.3, 0.05, 0.85, 100, 100);
    for (std::size_t i = 0; i < 6; ++i) REQUIRE(c.planned[i] == 100);
    const auto total = [&](const std::vector<vt::chunk_job>& jobs) {
        double sum = 0.0;
        for (const vt::chunk_job& j : jobs) sum += vt::job_cost(c, j);
        return sum;
    };
    const std::vector<vt::chunk_job> cheap = vt::next_jobs(c, 100, 350.0);
    CHECK(cheap.size() == 3);  // 3 x 100 of cost 1; the 4th would cost 100000
    CHECK(total(cheap) == 300.0);
    const std::vector<vt::chunk_job> one = vt::next_jobs(c, 100, 1.0);  // less than any job
    CHECK(one.size() == 1);
    CHECK(vt::next_jobs(c, 2).size() == 2);  // by count alone
    CHECK(vt::next_jobs(c, 100).size() == 6);
}

TEST_CASE("an adaptive plan stopped and resumed is estimate_radiance with its counts, and meets its target") {
    const sphere_scene s;
    const vt::path_tracer tracer(s.sphere, s.phase, 0.99, s.light);
    const std::vector<double> variance{0.5, 2.0, 8.0, 8.0, 2.0, 0.01}, cost{10, 20, 30, 30, 20, 1};
    vt::truth_checkpoint c = vt::adaptive_plan(identity(), variance, cost, 0.3, 0.02, 0.85, 16, 1 << 16);
    const std::vector<std::uint64_t> planned = c.planned;
    CHECK(planned[2] > planned[1]);  // Neyman: sqrt(variance / cost)
    CHECK(planned[1] > planned[0]);
    const auto want = vt::estimate_radiance(tracer, s.rays, planned, options(2));
    CHECK_FALSE(trace(c, s, 2, 2, 2));
    vt::truth_checkpoint resumed = vt::parse_checkpoint(vt::serialize_checkpoint(c), "ck.bin");
    vt::truth_checkpoint not_extended = resumed;
    not_extended.extensions = vt::truth_checkpoint::max_extensions;  // the plan as it was
    CHECK(trace(not_extended, s, 2, 4, 0));
    require_same(vt::estimates(not_extended), want);
    // Traced to the end of the plan, then extended while the floor misses the target: the
    // counts only grow, and the target is met within the extensions allowed.
    CHECK(trace(resumed, s, 2, 4, 0));
    for (std::size_t i = 0; i < planned.size(); ++i) CHECK(resumed.planned[i] >= planned[i]);
    CHECK(vt::noise_floor(vt::estimates(resumed)) <= 0.02);
}

TEST_CASE("extend_plan: a pilot that underestimated the variance gets more paths until the target is met") {
    const sphere_scene s;
    // The pilot's variances a hundredth of the truth's: the first plan misses the 3% floor.
    const std::vector<double> variance(6, 0.002), cost(6, 10.0);
    vt::truth_checkpoint c = vt::adaptive_plan(identity(), variance, cost, 0.3, 0.03, 0.85, 4, 1 << 20);
    const std::vector<std::uint64_t> first = c.planned;
    vt::truth_checkpoint once = c;
    CHECK(trace(once, s, 2, 64, 0));
    CHECK(once.extensions >= 1);
    CHECK(vt::noise_floor(vt::estimates(once)) <= 0.03);
    for (std::size_t i = 0; i < first.size(); ++i) CHECK(once.planned[i] > first[i]);
    CHECK_FALSE(vt::extend_plan(once));  // met: nothing to extend

    vt::truth_checkpoint uniform = vt::uniform_plan(identity(), 6, 8);
    CHECK(trace(uniform, s, 1, 64, 0));
    CHECK_FALSE(vt::extend_plan(uniform));  // a uniform plan has no target
}

TEST_CASE("a malformed, damaged or other-version checkpoint is refused, saying why") {
    const sphere_scene s;
    vt::truth_checkpoint c = vt::adaptive_plan(identity(), std::vector<double>(6, 1.0), std::vector<double>(6, 2.0), 0.3,
                                               0.05, 0.85, 8, 1000);
    c.pilot_note = "pilot 8 spp";
    CHECK_FALSE(trace(c, s, 2, 2, 1));
    const std::string good = vt::serialize_checkpoint(c);
    CHECK(refusal(good).empty());

    CHECK(contains(refusal(""), "ck.bin: not a truth checkpoint"));
    CHECK(contains(refusal("x,y,r,g,b\n"), "not a truth checkpoint"));
    std::string other = good;
    other.replace(other.find("version: 1"), 10, "version: 2");
    CHECK(contains(refusal(other), "checkpoint version 2, this tool reads version 1"));
    CHECK(contains(refusal(good.substr(0, good.size() - 40)), "truncated"));
    CHECK(contains(refusal(good.substr(0, 40)), "truncated in its header"));
    CHECK(contains(refusal(good + "x"), "bytes after the end line"));
    std::string flipped = good;
    flipped[good.find("data:\n") + 20] ^= 0x10;
    CHECK(contains(refusal(flipped), "its hash does not match"));
    std::string no_margin = good;
    no_margin.erase(no_margin.find("margin: "), no_margin.find('\n', no_margin.find("margin: ")) - no_margin.find("margin: ") + 1);
    CHECK(contains(refusal(no_margin), "no 'margin' line"));
    std::string bad_number = good;
    bad_number.replace(bad_number.find("runs: "), 7, "runs: x");
    CHECK(contains(refusal(bad_number), "'runs' is not a whole number"));

    // States no render leaves, each with a valid hash: refused by the consistency checks.
    vt::truth_checkpoint too_many = c;
    too_many.tally[3].paths = too_many.planned[3] + 1;
    CHECK(contains(refusal(vt::serialize_checkpoint(too_many)), "pixel 3: more paths traced than planned"));
    vt::truth_checkpoint stream = c;
    stream.next_chunk[0] = 0;  // paths traced with no chunk drawn
    CHECK(contains(refusal(vt::serialize_checkpoint(stream)), "pixel 0: its stream state"));
    vt::truth_checkpoint not_finite = c;
    not_finite.tally[1].g.sum = std::nan("");
    CHECK(contains(refusal(vt::serialize_checkpoint(not_finite)), "pixel 1: a sum that is negative or not finite"));
    vt::truth_checkpoint negative = c;
    negative.tally[2].lookups = -1.0;
    CHECK(contains(refusal(vt::serialize_checkpoint(negative)), "pixel 2: a sum"));
    vt::truth_checkpoint cost = c;
    cost.pilot_cost[4] = 0.0;
    CHECK(contains(refusal(vt::serialize_checkpoint(cost)), "pixel 4: a pilot variance or cost out of range"));
    vt::truth_checkpoint plan = c;
    plan.planned[5] = 2;  // below min_paths
    CHECK(contains(refusal(vt::serialize_checkpoint(plan)), "pixel 5: a planned count outside"));
    vt::truth_checkpoint margin = c;
    margin.margin = 0.0;
    CHECK(contains(refusal(vt::serialize_checkpoint(margin)), "an adaptive plan needs"));

    // Every refusal says how to get out of it.
    CHECK(contains(refusal(flipped), "delete it to start over"));
    CHECK_THROWS_WITH_AS(vt::read_checkpoint("/nonexistent/ck.bin"), "cannot read the checkpoint /nonexistent/ck.bin",
                         std::runtime_error);
    vt::truth_checkpoint multi_line = c;
    multi_line.identity["phase"] = "hg:0.5\nruns: 9";
    CHECK_THROWS_AS((void)vt::serialize_checkpoint(multi_line), std::invalid_argument);
}

TEST_CASE("a checkpoint of another run or scene is refused, naming what differs") {
    vt::truth_checkpoint c = vt::uniform_plan({{"preset", "sunset"}, {"sky", "physical"}, {"scene", "00aa"}}, 4, 8);
    CHECK_NOTHROW(vt::check_same_run(c, {{"preset", "sunset"}, {"sky", "physical"}, {"scene", "00aa"}}, "ck"));
    CHECK_THROWS_WITH_AS(vt::check_same_run(c, {{"preset", "sunset"}, {"sky", "artistic"}, {"scene", "00aa"}}, "ck"),
                         doctest::Contains("ck: the checkpoint's sky is 'physical', this run's 'artistic'"),
                         std::runtime_error);
    CHECK_THROWS_WITH_AS(vt::check_same_run(c, {{"preset", "sunset"}, {"sky", "physical"}, {"scene", "00ab"}}, "ck"),
                         doctest::Contains("changed since it was traced"), std::runtime_error);
    CHECK_THROWS_WITH_AS(vt::check_same_run(c, {{"preset", "sunset"}, {"sky", "physical"}}, "ck"),
                         doctest::Contains("the checkpoint's scene is '00aa', this run's (none)"), std::runtime_error);
    CHECK_THROWS_WITH_AS(
        vt::check_same_run(c, {{"preset", "sunset"}, {"sky", "physical"}, {"scene", "00aa"}, {"seed", "2"}}, "ck"),
        doctest::Contains("the checkpoint's seed is (none), this run's '2'"), std::runtime_error);
    // Another image size: the pixel count does not match the rays.
    const sphere_scene s;
    const vt::path_tracer tracer(s.sphere, s.phase, 0.99, s.light);
    CHECK_THROWS_AS(vt::continue_trace(c, tracer, s.rays, options(1), 4, 0.0, 1e9, nullptr, nullptr), std::invalid_argument);
}

TEST_CASE("the scene fingerprint sees the medium, the light and the camera") {
    const sphere_scene s;
    const std::string base = vt::scene_fingerprint(s.sphere, s.light, s.rays);
    CHECK(base.size() == 16);
    CHECK(vt::scene_fingerprint(s.sphere, s.light, s.rays) == base);
    const vt::homogeneous_sphere denser(2.0 * (1.0 + 1e-15));
    CHECK(vt::scene_fingerprint(denser, s.light, s.rays) != base);
    vt::lighting redder = s.light;
    redder.sun_irradiance.r = 1.01;
    CHECK(vt::scene_fingerprint(s.sphere, redder, s.rays) != base);
    vt::lighting sky = s.light;
    sky.escaped = [](const mc::vec3&, const mc::vec3&, bool) { return vt::rgb{0.2, 0.3, 0.5}; };
    CHECK(vt::scene_fingerprint(s.sphere, sky, s.rays) != base);
    std::vector<vt::camera_ray> moved = s.rays;
    moved[5].origin.y += 1e-9;
    CHECK(vt::scene_fingerprint(s.sphere, s.light, moved) != base);
}

TEST_CASE("trace_chunks and merge_jobs refuse jobs out of range or out of stream order") {
    const sphere_scene s;
    const vt::path_tracer tracer(s.sphere, s.phase, 0.99, s.light);
    CHECK_THROWS_AS((void)vt::trace_chunks(tracer, s.rays, {{6, 0, 1}}, options(1)), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::trace_chunks(tracer, s.rays, {{0, 0, 0}}, options(1)), std::invalid_argument);
    CHECK_THROWS_AS((void)vt::trace_chunks(tracer, s.rays, {{0, 0, mc::detail::paths_per_chunk + 1}}, options(1)),
                    std::invalid_argument);
    vt::truth_checkpoint c = vt::uniform_plan(identity(), 6, 8);
    const std::vector<vt::chunk_job> skipped{{0, 1, 8}};  // chunk 0 never drawn
    CHECK_THROWS_AS(vt::merge_jobs(c, skipped, vt::trace_chunks(tracer, s.rays, skipped, options(1))), std::invalid_argument);
}
