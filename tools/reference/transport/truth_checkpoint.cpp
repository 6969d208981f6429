// tools/reference/transport/truth_checkpoint.cpp: see truth_checkpoint.hpp.
#include "truth_checkpoint.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>

#include "atomic_file.hpp"
#include "strict_number.hpp"

namespace cloudmath::reference::volume {

using mc::detail::paths_per_chunk;

std::uint64_t truth_checkpoint::planned_paths() const {
    std::uint64_t n = 0;
    for (const std::uint64_t p : planned) n += p;
    return n;
}
std::uint64_t truth_checkpoint::traced_paths() const {
    std::uint64_t n = 0;
    for (const path_tally& t : tally) n += t.paths;
    return n;
}
bool truth_checkpoint::plan_done() const {
    for (std::size_t i = 0; i < planned.size(); ++i)
        if (tally[i].paths < planned[i]) return false;
    return true;
}

namespace {

void start_progress(truth_checkpoint& c) {
    c.next_chunk.assign(c.planned.size(), 0);
    c.tally.assign(c.planned.size(), path_tally{});
}

// allocate_paths for margin x target with the pilot's mean (sum over pixels and channels of
// the variance of the mean, the report's noise floor squared times (3 n mean^2)).
std::vector<std::uint64_t> plan_counts(const truth_checkpoint& c, double margin) {
    const double n = static_cast<double>(c.pilot_variance.size());
    const double target_sum = margin * c.noise_target * c.pilot_mean * margin * c.noise_target * c.pilot_mean * 3.0 * n;
    return allocate_paths(c.pilot_variance, c.pilot_cost, target_sum, c.min_paths, c.max_paths).paths;
}

}  // namespace

truth_checkpoint uniform_plan(std::map<std::string, std::string> identity, std::size_t pixels, std::uint64_t paths) {
    if (paths < 1) throw std::invalid_argument("uniform_plan: at least 1 path per pixel");
    truth_checkpoint c;
    c.identity = std::move(identity);
    c.min_paths = c.max_paths = paths;
    c.planned.assign(pixels, paths);
    start_progress(c);
    return c;
}

truth_checkpoint adaptive_plan(std::map<std::string, std::string> identity, std::vector<double> variance,
                               std::vector<double> cost, double pilot_mean, double target, double margin,
                               std::uint64_t min_paths, std::uint64_t max_paths) {
    if (!(pilot_mean > 0.0) || !std::isfinite(pilot_mean))
        throw std::invalid_argument("adaptive_plan: the pilot's mean must be positive (a black image has no noise floor)");
    if (!(target > 0.0 && target < 1.0) || !(margin > 0.0 && margin <= 1.0))
        throw std::invalid_argument("adaptive_plan: target and margin in (0, 1)");
    truth_checkpoint c;
    c.identity = std::move(identity);
    c.noise_target = target;
    c.margin = margin;
    c.pilot_mean = pilot_mean;
    c.min_paths = min_paths;
    c.max_paths = max_paths;
    c.pilot_variance = std::move(variance);
    c.pilot_cost = std::move(cost);
    c.planned = plan_counts(c, margin);
    start_progress(c);
    return c;
}

std::vector<rgb_estimate> estimates(const truth_checkpoint& c) {
    std::vector<rgb_estimate> out;
    out.reserve(c.tally.size());
    for (const path_tally& t : c.tally) out.push_back(make_rgb_estimate(t));
    return out;
}

double noise_floor(const std::vector<rgb_estimate>& e) {
    double sum = 0.0, se_sq = 0.0;
    for (const rgb_estimate& x : e) {
        sum += x.r.mean + x.g.mean + x.b.mean;
        se_sq += x.r.std_error * x.r.std_error + x.g.std_error * x.g.std_error + x.b.std_error * x.b.std_error;
    }
    const double count = 3.0 * static_cast<double>(e.size());
    return sum > 0.0 ? std::sqrt(se_sq / count) / (sum / count) : 0.0;
}

bool extend_plan(truth_checkpoint& c) {
    if (c.noise_target <= 0.0 || c.extensions >= truth_checkpoint::max_extensions) return false;
    const double reached = noise_floor(estimates(c));
    if (!(reached > c.noise_target)) return false;
    // The floor falls as the square root of the paths, so aiming at target / reached of the
    // old margin (with 5% to spare) asks for about what was missing.
    c.margin *= 0.95 * c.noise_target / reached;
    const std::vector<std::uint64_t> more = plan_counts(c, c.margin);
    for (std::size_t i = 0; i < c.planned.size(); ++i) c.planned[i] = std::max(c.planned[i], more[i]);
    ++c.extensions;
    return true;
}

double job_cost(const truth_checkpoint& c, const chunk_job& j) {
    const double per_path = j.ray < c.pilot_cost.size() ? c.pilot_cost[j.ray] : 1.0;
    return static_cast<double>(j.paths) * per_path;
}

std::vector<chunk_job> next_jobs(const truth_checkpoint& c, std::size_t max_jobs, double max_cost) {
    std::vector<chunk_job> jobs;
    double cost = 0.0;
    const auto full = [&] { return jobs.size() >= max_jobs || (!jobs.empty() && cost >= max_cost); };
    for (std::size_t i = 0; i < c.planned.size() && !full(); ++i) {
        std::uint64_t left = c.planned[i] - std::min(c.planned[i], c.tally[i].paths);
        for (std::uint64_t k = c.next_chunk[i]; left > 0 && !full(); ++k) {
            const chunk_job j{i, k, std::min(left, paths_per_chunk)};
            if (!jobs.empty() && cost + job_cost(c, j) > max_cost) return jobs;
            jobs.push_back(j);
            cost += job_cost(c, j);
            left -= j.paths;
        }
    }
    return jobs;
}

void merge_jobs(truth_checkpoint& c, const std::vector<chunk_job>& jobs, const std::vector<path_tally>& tallies) {
    if (jobs.size() != tallies.size()) throw std::invalid_argument("merge_jobs: one tally per job");
    for (std::size_t k = 0; k < jobs.size(); ++k) {
        const chunk_job& j = jobs[k];
        if (j.ray >= c.tally.size() || j.chunk != c.next_chunk[j.ray])
            throw std::invalid_argument("merge_jobs: jobs out of their stream order");
        c.tally[j.ray].merge(tallies[k]);
        c.next_chunk[j.ray] = j.chunk + 1;
    }
}

bool continue_trace(truth_checkpoint& c, const path_tracer& tracer, const std::vector<camera_ray>& rays,
                    const mc::run_options& options, std::size_t batch_jobs, double batch_seconds,
                    double save_every_seconds, const std::function<bool()>& stop,
                    const std::function<void(const truth_checkpoint&)>& save) {
    if (rays.size() != c.pixels()) throw std::invalid_argument("continue_trace: one camera ray per pixel of the plan");
    using clock = std::chrono::steady_clock;
    auto last_save = clock::now();
    const std::size_t first = std::max<std::size_t>(batch_jobs, 1);
    double traced_cost = 0.0, traced_seconds = 0.0;  // of the batches so far: the rate
    for (;;) {
        if (c.plan_done() && !extend_plan(c)) break;
        if (stop && stop()) break;
        const bool by_cost = batch_seconds > 0.0 && traced_seconds > 0.0 && traced_cost > 0.0;
        const std::vector<chunk_job> jobs =
            by_cost ? next_jobs(c, std::numeric_limits<std::size_t>::max(), traced_cost / traced_seconds * batch_seconds)
                    : next_jobs(c, first);
        const auto start = clock::now();
        merge_jobs(c, jobs, trace_chunks(tracer, rays, jobs, options));
        const auto end = clock::now();
        const double seconds = std::chrono::duration<double>(end - start).count();
        c.seconds += seconds;
        traced_seconds += seconds;
        for (const chunk_job& j : jobs) traced_cost += job_cost(c, j);
        if (save && std::chrono::duration<double>(end - last_save).count() >= save_every_seconds) {
            save(c);
            last_save = end;
        }
    }
    if (save) save(c);
    return c.plan_done();
}

// ---------------------------------------------------------------------------------------
// The file.
namespace {

constexpr std::string_view magic = "cloudmath truth checkpoint\n";
constexpr std::size_t record_bytes = 2 * 8 + 3 * 4 + 7 * 8;

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = 0xcbf29ce484222325ULL) {
    for (const char ch : bytes) {
        h ^= static_cast<unsigned char>(ch);
        h *= 0x100000001b3ULL;
    }
    return h;
}

std::string hex16(std::uint64_t v) {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
    return b;
}

void put_u32(std::string& out, std::uint64_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}
void put_f64(std::string& out, double d) {
    std::uint64_t v;
    std::memcpy(&v, &d, sizeof v);
    for (int k = 0; k < 8; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}
std::uint64_t get_uint(std::string_view bytes, std::size_t& at, int size) {
    std::uint64_t v = 0;
    for (int k = 0; k < size; ++k) v |= std::uint64_t(static_cast<unsigned char>(bytes[at + std::size_t(k)])) << (8 * k);
    at += std::size_t(size);
    return v;
}
double get_f64(std::string_view bytes, std::size_t& at) {
    const std::uint64_t v = get_uint(bytes, at, 8);
    double d;
    std::memcpy(&d, &v, sizeof d);
    return d;
}

// Doubles as text that reads back to the same bits.
std::string exact(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return b;
}

}  // namespace

std::string serialize_checkpoint(const truth_checkpoint& c) {
    const auto one_line = [](const std::string& t) { return t.find('\n') == std::string::npos; };
    for (const auto& [k, v] : c.identity)
        if (!one_line(k) || !one_line(v) || k.find(": ") != std::string::npos)
            throw std::invalid_argument("serialize_checkpoint: identity keys and values on one line");
    if (!one_line(c.pilot_note)) throw std::invalid_argument("serialize_checkpoint: the pilot note on one line");
    std::ostringstream head;
    head << magic << "version: " << truth_checkpoint::format_version << '\n';
    for (const auto& [k, v] : c.identity) head << "run." << k << ": " << v << '\n';
    head << "noise_target: " << exact(c.noise_target) << '\n'
         << "margin: " << exact(c.margin) << '\n'
         << "pilot_mean: " << exact(c.pilot_mean) << '\n'
         << "min_paths: " << c.min_paths << '\n'
         << "max_paths: " << c.max_paths << '\n'
         << "extensions: " << c.extensions << '\n'
         << "pilot_note: " << c.pilot_note << '\n'
         << "seconds: " << exact(c.seconds) << '\n'
         << "runs: " << c.runs << '\n'
         << "pixels: " << c.pixels() << '\n'
         << "data:\n";
    std::string out = head.str();
    for (std::size_t i = 0; i < c.pixels(); ++i)
        if (c.planned[i] > 0xFFFFFFFFULL || c.next_chunk[i] > 0xFFFFFFFFULL)
            throw std::invalid_argument("serialize_checkpoint: a count beyond 32 bits");
    const bool adaptive = c.noise_target > 0.0;
    for (std::size_t i = 0; i < c.pixels(); ++i) {
        const path_tally& t = c.tally[i];
        put_f64(out, adaptive ? c.pilot_variance[i] : 0.0);
        put_f64(out, adaptive ? c.pilot_cost[i] : 0.0);
        put_u32(out, c.planned[i]);
        put_u32(out, c.next_chunk[i]);
        put_u32(out, t.paths);
        for (const double v : {t.r.sum, t.g.sum, t.b.sum, t.r.sum_sq, t.g.sum_sq, t.b.sum_sq, t.lookups}) put_f64(out, v);
    }
    out += "end " + hex16(fnv1a(out)) + "\n";
    return out;
}

namespace {
[[noreturn]] void refuse(const std::string& path, const std::string& why) {
    throw std::runtime_error(path + ": " + why + " (a checkpoint of cloudmath_volume_truth render; delete it to start over)");
}
}  // namespace

truth_checkpoint parse_checkpoint(std::string_view bytes, const std::string& path) {
    const auto fail = [&path](const std::string& why) { refuse(path, why); };
    if (bytes.substr(0, magic.size()) != magic) fail("not a truth checkpoint");
    // The header: "key: value" lines up to "data:".
    std::map<std::string, std::string> head;
    std::size_t at = magic.size();
    for (;;) {
        const std::size_t eol = bytes.find('\n', at);
        if (eol == std::string_view::npos) fail("truncated in its header");
        const std::string line(bytes.substr(at, eol - at));
        at = eol + 1;
        if (line == "data:") break;
        const std::size_t colon = line.find(": ");
        if (colon == std::string::npos && !line.empty() && line.back() == ':') {
            head[line.substr(0, line.size() - 1)] = "";
            continue;
        }
        if (colon == std::string::npos) fail("malformed header line '" + line + "'");
        head[line.substr(0, colon)] = line.substr(colon + 2);
    }
    const auto text = [&](const std::string& key) -> std::string {
        const auto it = head.find(key);
        if (it == head.end()) refuse(path, "no '" + key + "' line");
        return it->second;
    };
    const auto whole = [&](const std::string& key, std::uint64_t hi) -> std::uint64_t {
        const std::optional<std::uint64_t> v = cloudmath::tools::parse_integer<std::uint64_t>(text(key));
        if (!v || *v > hi) refuse(path, "'" + key + "' is not a whole number up to " + std::to_string(hi));
        return *v;
    };
    const auto number = [&](const std::string& key) -> double {
        const std::optional<double> v = cloudmath::tools::parse_finite(text(key));
        if (!v || *v < 0.0) refuse(path, "'" + key + "' is not a finite number >= 0");
        return *v;
    };
    const std::uint64_t version = whole("version", std::numeric_limits<std::uint32_t>::max());
    if (version != truth_checkpoint::format_version)
        fail("checkpoint version " + std::to_string(version) + ", this tool reads version " +
             std::to_string(truth_checkpoint::format_version));
    truth_checkpoint c;
    for (const auto& [k, v] : head)
        if (k.rfind("run.", 0) == 0) c.identity[k.substr(4)] = v;
    c.noise_target = number("noise_target");
    c.margin = number("margin");
    c.pilot_mean = number("pilot_mean");
    constexpr std::uint64_t count_limit = 0xFFFFFFFFULL;
    c.min_paths = whole("min_paths", count_limit);
    c.max_paths = whole("max_paths", count_limit);
    c.extensions = static_cast<unsigned>(whole("extensions", truth_checkpoint::max_extensions));
    c.pilot_note = text("pilot_note");
    c.seconds = number("seconds");
    c.runs = static_cast<unsigned>(whole("runs", 1u << 20));
    const std::uint64_t pixels = whole("pixels", 4096ULL * 4096ULL);
    const bool adaptive = c.noise_target > 0.0;
    if (adaptive && !(c.noise_target < 1.0 && c.margin > 0.0 && c.margin <= 1.0 && c.pilot_mean > 0.0))
        fail("an adaptive plan needs a noise target and a margin in (0, 1) and a positive pilot mean");
    if (c.min_paths < 1 || c.min_paths > c.max_paths) fail("min_paths must be from 1 to max_paths");

    // The records and the hash that closes them.
    const std::size_t data_end = at + static_cast<std::size_t>(pixels) * record_bytes;
    const std::string tail = "end " + std::string(16, '0') + "\n";
    if (bytes.size() < data_end + tail.size())
        fail("truncated: " + std::to_string(bytes.size() > at ? bytes.size() - at : 0) + " bytes after the header, want " +
             std::to_string(data_end + tail.size() - at));
    if (bytes.size() > data_end + tail.size()) fail("bytes after the end line");
    if (bytes.substr(data_end, 4) != "end " || bytes.back() != '\n') fail("no end line after " + std::to_string(pixels) + " pixels");
    if (std::string(bytes.substr(data_end + 4, 16)) != hex16(fnv1a(bytes.substr(0, data_end))))
        fail("its hash does not match its contents (a damaged or edited file)");

    const auto n = static_cast<std::size_t>(pixels);
    c.planned.resize(n);
    c.next_chunk.resize(n);
    c.tally.resize(n);
    if (adaptive) {
        c.pilot_variance.resize(n);
        c.pilot_cost.resize(n);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const double variance = get_f64(bytes, at), cost = get_f64(bytes, at);
        c.planned[i] = get_uint(bytes, at, 4);
        c.next_chunk[i] = get_uint(bytes, at, 4);
        path_tally& t = c.tally[i];
        t.paths = get_uint(bytes, at, 4);
        double* fields[] = {&t.r.sum, &t.g.sum, &t.b.sum, &t.r.sum_sq, &t.g.sum_sq, &t.b.sum_sq, &t.lookups};
        for (double* v : fields) *v = get_f64(bytes, at);
        const std::string pixel = "pixel " + std::to_string(i) + ": ";
        for (const double* v : fields)
            if (!std::isfinite(*v) || *v < 0.0) fail(pixel + "a sum that is negative or not finite");
        if (adaptive) {
            if (!(variance >= 0.0) || !std::isfinite(variance) || !(cost > 0.0) || !std::isfinite(cost))
                fail(pixel + "a pilot variance or cost out of range");
            c.pilot_variance[i] = variance;
            c.pilot_cost[i] = cost;
        }
        if (c.planned[i] < c.min_paths || c.planned[i] > c.max_paths) fail(pixel + "a planned count outside [min_paths, max_paths]");
        if (t.paths > c.planned[i]) fail(pixel + "more paths traced than planned");
        // Every chunk drawn holds 1 to paths_per_chunk paths.
        if (t.paths > c.next_chunk[i] * paths_per_chunk || c.next_chunk[i] > t.paths)
            fail(pixel + "its stream state (next chunk " + std::to_string(c.next_chunk[i]) + ") does not fit its " +
                 std::to_string(t.paths) + " paths");
    }
    return c;
}

truth_checkpoint read_checkpoint(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read the checkpoint " + path);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parse_checkpoint(bytes, path);
}

void write_checkpoint(const std::string& path, const truth_checkpoint& c) {
    const std::string error = cloudmath::tools::write_file_atomically(path, serialize_checkpoint(c));
    if (!error.empty()) throw std::runtime_error(error);
}

void check_same_run(const truth_checkpoint& c, const std::map<std::string, std::string>& identity, const std::string& path) {
    // The flags first (in key order), then the scene they make: a resume under another sky
    // names the sky, not only the fingerprint that follows from it.
    std::set<std::string> keys;
    for (const auto* m : {&c.identity, &identity})
        for (const auto& kv : *m)
            if (kv.first != "scene") keys.insert(kv.first);
    std::vector<std::string> order(keys.begin(), keys.end());
    order.push_back("scene");
    for (const std::string& key : order) {
        const auto a = c.identity.find(key), b = identity.find(key);
        const std::string was = a == c.identity.end() ? "(none)" : "'" + a->second + "'";
        const std::string now = b == identity.end() ? "(none)" : "'" + b->second + "'";
        if (was != now)
            throw std::runtime_error(path + ": the checkpoint's " + key + " is " + was + ", this run's " + now +
                                     (key == "scene" ? " (the renderer's field, sky, sun or camera changed since it was traced)"
                                                     : "") +
                                     ": resume with the flags it was started with, or delete it to start over");
    }
}

std::string scene_fingerprint(const medium& m, const lighting& light, const std::vector<camera_ray>& rays) {
    std::uint64_t h = 0xcbf29ce484222325ULL;
    const auto add = [&h](double v) {
        char b[sizeof v];
        std::memcpy(b, &v, sizeof v);
        h = fnv1a(std::string_view(b, sizeof b), h);
    };
    const auto add3 = [&](const vec3& v) {
        add(v.x);
        add(v.y);
        add(v.z);
    };
    const auto add_rgb = [&](const rgb& c) {
        add(c.r);
        add(c.g);
        add(c.b);
    };
    for (const camera_ray& r : rays) {
        add3(r.origin);
        add3(r.direction);
        add(r.t_begin);
        add(r.t_end);
        add_rgb(r.background);
    }
    add3(light.sun_direction);
    add_rgb(light.sun_irradiance);
    // The field along every 37th ray, 16 points over its stretch in the medium; the sun and
    // the escaped light from those rays' points.
    for (std::size_t i = 0; i < rays.size(); i += 37) {
        const camera_ray& r = rays[i];
        const vec3 d = mc::normalized(r.direction);
        const double end = std::min(r.t_end, m.exit(r.origin, d).distance);
        for (int k = 0; k < 16; ++k) {
            const double t = r.t_begin + (k + 0.5) / 16.0 * std::max(0.0, end - r.t_begin);
            const vec3 p = r.origin + t * d;
            add(m.extinction(p));
            if (k % 4 == 0 && light.sun_at) add_rgb(light.sun_at(p));
        }
        if (light.escaped) {
            add_rgb(light.escaped(r.origin, d, false));
            add_rgb(light.escaped(r.origin, d, true));
        }
    }
    return hex16(h);
}

}  // namespace cloudmath::reference::volume
