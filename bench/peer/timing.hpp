// Timed rows of the peer bench, timed in interleaved rounds (one frame of each row per
// round), so that a change in a shared machine's load hits every row alike.
#ifndef CLOUDMATH_PEER_BENCH_TIMING_HPP
#define CLOUDMATH_PEER_BENCH_TIMING_HPP

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

namespace peer_bench {

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// One timed row: how to draw one frame of it (returning its host time), how many frames to
// draw before timing (shader compile and JIT; the temporal history), the measured times.
struct timed_row {
    std::function<bool(double& ms, std::string& why)> frame;
    int warm_up = 1;
    std::vector<double> ms;
    double median_ms = 0, min_ms = 0, max_ms = 0;
};

// Warms every row up, then times them in `frames` rounds.
inline bool time_rows(const std::vector<timed_row*>& rows, int frames, std::string& why) {
    for (timed_row* r : rows)
        for (int f = 0; f < r->warm_up; ++f) {
            double ignored = 0;
            if (!r->frame(ignored, why)) return false;
        }
    for (int f = 0; f < frames; ++f)
        for (timed_row* r : rows) {
            double ms = 0;
            if (!r->frame(ms, why)) return false;
            r->ms.push_back(ms);
        }
    for (timed_row* r : rows) {
        r->median_ms = median(r->ms);
        r->min_ms = r->ms.empty() ? 0.0 : *std::min_element(r->ms.begin(), r->ms.end());
        r->max_ms = r->ms.empty() ? 0.0 : *std::max_element(r->ms.begin(), r->ms.end());
    }
    return true;
}

}  // namespace peer_bench

#endif  // CLOUDMATH_PEER_BENCH_TIMING_HPP
