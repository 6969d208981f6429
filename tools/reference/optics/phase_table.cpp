// tools/reference/optics/phase_table.cpp: see phase_table.hpp.
#include "phase_table.hpp"

#include "atomic_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace cloudmath::reference {

namespace {

constexpr double pi = 3.14159265358979323846;

double cos_deg(double theta) {
    // cos(90 deg) in double is 6e-17, not 0; exact 0 keeps mu symmetric around the middle row.
    if (theta == 90.0) return 0.0;
    if (theta == 180.0) return -1.0;
    return std::cos(theta * (pi / 180.0));
}

std::string trim(const std::string& s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    const auto e = s.find_last_not_of(" \t\r");
    return s.substr(b, e - b + 1);
}

}  // namespace

std::string phase_table::meta(const std::string& key) const {
    for (const auto& kv : metadata)
        if (kv.first == key) return kv.second;
    return "";
}

void phase_table::set_meta(const std::string& key, const std::string& value) {
    for (auto& kv : metadata)
        if (kv.first == key) {
            kv.second = value;
            return;
        }
    metadata.emplace_back(key, value);
}

void phase_table::finalize() {
    const std::size_t n = theta_deg.size();
    if (n < 2 || phase.size() != n)
        throw std::invalid_argument("phase table needs at least 2 rows and one value per angle");
    if (theta_deg.front() != 0.0 || theta_deg.back() != 180.0)
        throw std::invalid_argument("phase table angles must run from 0 to 180 degrees");
    for (std::size_t i = 0; i < n; ++i) {
        if (i > 0 && !(theta_deg[i] > theta_deg[i - 1]))
            throw std::invalid_argument("phase table angles must be strictly ascending");
        if (!std::isfinite(phase[i]) || phase[i] < 0.0)
            throw std::invalid_argument("phase table values must be finite and >= 0");
    }
    mu_ascending.resize(n);
    phase_ascending.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        mu_ascending[i] = cos_deg(theta_deg[n - 1 - i]);
        phase_ascending[i] = phase[n - 1 - i];
    }
    // Trapezoids in mu integrate the piecewise-linear function exactly.
    cdf.assign(n, 0.0);
    for (std::size_t i = 1; i < n; ++i)
        cdf[i] = cdf[i - 1] + 0.5 * (phase_ascending[i] + phase_ascending[i - 1]) *
                                  (mu_ascending[i] - mu_ascending[i - 1]);
    total = 2.0 * pi * cdf.back();
    if (!(total > 0.0)) throw std::invalid_argument("phase table integrates to 0");
    const double inv = 1.0 / cdf.back();
    for (double& c : cdf) c *= inv;
    cdf.back() = 1.0;
}

double phase_table::evaluate(double mu) const {
    mu = std::clamp(mu, -1.0, 1.0);
    const auto it = std::upper_bound(mu_ascending.begin(), mu_ascending.end(), mu);
    if (it == mu_ascending.end()) return phase_ascending.back();
    const auto i = static_cast<std::size_t>(it - mu_ascending.begin());
    if (i == 0) return phase_ascending.front();
    const double m0 = mu_ascending[i - 1], m1 = mu_ascending[i];
    const double t = (mu - m0) / (m1 - m0);
    return phase_ascending[i - 1] + t * (phase_ascending[i] - phase_ascending[i - 1]);
}

double phase_table::integral() const { return total; }

double phase_table::mean_cosine() const {
    // Exact integral of mu p(mu) for p linear on [m0, m1]:
    // (m1 - m0)/6 * (p0 (2 m0 + m1) + p1 (m0 + 2 m1)).
    double s = 0.0;
    for (std::size_t i = 1; i < mu_ascending.size(); ++i) {
        const double m0 = mu_ascending[i - 1], m1 = mu_ascending[i];
        const double p0 = phase_ascending[i - 1], p1 = phase_ascending[i];
        s += (m1 - m0) / 6.0 * (p0 * (2.0 * m0 + m1) + p1 * (m0 + 2.0 * m1));
    }
    return 2.0 * pi * s;
}

double phase_table::normalize() {
    const double old = total;
    for (double& p : phase) p /= old;
    finalize();
    return old;
}

double phase_table::sample_mu(double u) const {
    u = std::clamp(u, 0.0, 1.0);
    auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    std::size_t i = it == cdf.end() ? cdf.size() - 1 : static_cast<std::size_t>(it - cdf.begin());
    if (i == 0) i = 1;
    const double m0 = mu_ascending[i - 1], h = mu_ascending[i] - m0;
    const double p0 = phase_ascending[i - 1], p1 = phase_ascending[i];
    // Area still needed inside bin i, in the table's own units (cdf is normalised).
    const double need = (u - cdf[i - 1]) * (total / (2.0 * pi));
    // Solve p0 s + (p1 - p0) s^2 / (2 h) = need for s in [0, h]; the form
    // s = 2 need / (p0 + sqrt(p0^2 + 2 slope need)) has no cancellation (slope may be < 0).
    const double slope = (p1 - p0) / h;
    const double disc = std::max(0.0, p0 * p0 + 2.0 * slope * need);
    const double denom = p0 + std::sqrt(disc);
    double s = denom > 0.0 ? 2.0 * need / denom : 0.0;
    s = std::clamp(s, 0.0, h);
    return std::min(1.0, m0 + s);
}

std::vector<double> default_angles_deg() {
    // (end of the range, step) pairs; integer step counts keep the grid exact.
    const double ranges[][2] = {{1.0, 0.01},    {5.0, 0.05},  {15.0, 0.1},
                                {165.0, 0.25},  {175.0, 0.1}, {180.0, 0.02}};
    std::vector<double> out{0.0};
    double start = 0.0;
    for (const auto& r : ranges) {
        const auto steps = static_cast<int>(std::lround((r[0] - start) / r[1]));
        for (int k = 1; k <= steps; ++k)
            out.push_back(k == steps ? r[0] : start + (r[0] - start) * k / steps);
        start = r[0];
    }
    return out;
}

void write_text_file_atomically(const std::string& path, const std::string& text) {
    const std::string error = cloudmath::tools::write_file_atomically(path, text);
    if (!error.empty()) throw std::runtime_error(error);
}

void write_phase_table(const std::string& path, const phase_table& table) {
    std::ostringstream f;
    for (const auto& kv : table.metadata) f << "# " << kv.first << ": " << kv.second << '\n';
    f << "theta_deg,mu,phase\n" << std::setprecision(17);
    for (std::size_t i = 0; i < table.theta_deg.size(); ++i)
        f << table.theta_deg[i] << ',' << cos_deg(table.theta_deg[i]) << ',' << table.phase[i]
          << '\n';
    write_text_file_atomically(path, f.str());
}

std::pair<std::string, std::string> parse_metadata_line(const std::string& line) {
    const std::string body = trim(line.substr(line.empty() ? 0 : 1));
    const auto colon = body.find(':');
    if (colon == std::string::npos) return {body, ""};
    return {trim(body.substr(0, colon)), trim(body.substr(colon + 1))};
}

phase_table read_phase_table(const std::string& path) {
    std::ifstream f(path);
    if (!f) throw std::runtime_error("cannot open phase table " + path);
    phase_table t;
    std::string line;
    int line_no = 0;
    bool header_seen = false;
    auto fail = [&](const std::string& why) {
        throw std::runtime_error(path + ":" + std::to_string(line_no) + ": " + why);
    };
    while (std::getline(f, line)) {
        ++line_no;
        line = trim(line);
        if (line.empty()) continue;
        if (line[0] == '#') {
            t.metadata.push_back(parse_metadata_line(line));
            continue;
        }
        if (!header_seen) {
            if (line != "theta_deg,mu,phase") fail("expected the header theta_deg,mu,phase");
            header_seen = true;
            continue;
        }
        std::istringstream row(line);
        double v[3];
        char comma = 0;
        if (!(row >> v[0] >> comma) || comma != ',' || !(row >> v[1] >> comma) || comma != ',' ||
            !(row >> v[2]))
            fail("expected three comma-separated numbers");
        std::string rest;
        if (row >> rest) fail("trailing text after the third number");
        t.theta_deg.push_back(v[0]);
        t.phase.push_back(v[2]);
    }
    if (!header_seen) fail("no header line theta_deg,mu,phase");
    try {
        t.finalize();
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(path + ": " + e.what());
    }
    return t;
}

}  // namespace cloudmath::reference
