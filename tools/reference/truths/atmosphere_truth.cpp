// tools/reference/truths/atmosphere_truth.cpp: see atmosphere_truth.hpp.
#include "atmosphere_truth.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <cloudmath/atmosphere.hpp>

#include "strict_number.hpp"

namespace cloudmath::reference::atmo {

std::vector<double> set_sun_elevations(const std::string& set_name) {
    if (set_name == "truth") return {truth_sun_elevations.begin(), truth_sun_elevations.end()};
    if (set_name == "holdout") return {holdout_sun_elevations.begin(), holdout_sun_elevations.end()};
    throw std::invalid_argument("no set named '" + set_name + "' (truth or holdout)");
}

namespace {
// A row of a set, its radiance not filled in.
truth_row row(const std::string& set, const std::string& name, double sun_elevation, double view_elevation,
              double view_azimuth) {
    truth_row r;
    r.set = set;
    r.name = name;
    r.sun_elevation = sun_elevation;
    r.view_elevation = view_elevation;
    r.view_azimuth = view_azimuth;
    return r;
}
}  // namespace

std::vector<truth_row> truth_set(const std::vector<double>& sun_elevations) {
    std::vector<truth_row> rows;
    for (double e : sun_elevations) {
        const auto add = [&](const char* name, double el, double az) { rows.push_back(row("table", name, e, el, az)); };
        add("zenith", 90.0, 0.0);
        add("horizon_sun", 1.0, 0.0);
        add("horizon_side", 1.0, 90.0);
        add("horizon_away", 1.0, 180.0);
        add("sun_5", e + 5.0 <= 90.0 ? e + 5.0 : e - 5.0, 0.0);
        add("sun_15", e + 15.0 <= 90.0 ? e + 15.0 : e - 15.0, 0.0);
        add("sun_side", std::clamp(e, 1.0, 80.0), 20.0);
    }
    for (double e : sun_elevations)
        for (int j = 0; j < panorama_elevations; ++j)
            for (int i = 0; i < panorama_azimuths; ++i)
                rows.push_back(row("panorama", std::to_string(i) + "_" + std::to_string(j), e,
                                   (j + 0.5) * 90.0 / panorama_elevations, (i + 0.5) * 180.0 / panorama_azimuths));
    return rows;
}

std::vector<truth_row> horizon_set() {
    std::vector<truth_row> rows;
    for (double e : horizon_sun_elevations)
        for (const auto& [name, el, az] : {std::tuple{"up2_sun", 2.0, 0.0}, {"up2_away", 2.0, 180.0},
                                           {"up10_sun", 10.0, 0.0}, {"up10_away", 10.0, 180.0}})
            rows.push_back(row("horizon", name, e, el, az));
    return rows;
}

std::vector<truth_row> read_truth(const std::string& path, const std::vector<double>& sun_elevations) {
    return read_rows(path, truth_set(sun_elevations));
}

std::vector<truth_row> read_rows(const std::string& path, const std::vector<truth_row>& want) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error(path + ": cannot read the truth file");
    std::vector<truth_row> rows;
    std::string line;
    int number = 0;
    bool header = false;
    while (std::getline(in, line)) {
        ++number;
        if (line.empty() || line[0] == '#') continue;
        if (!header) {
            if (line != "set,name,sun_elevation,view_elevation,view_azimuth,r,g,b,se_r,se_g,se_b")
                throw std::runtime_error(path + ":" + std::to_string(number) + ": not the truth file's header");
            header = true;
            continue;
        }
        std::vector<std::string> f;
        std::stringstream s(line);
        for (std::string item; std::getline(s, item, ',');) f.push_back(item);
        if (f.size() != 11 || line.back() == ',')
            throw std::runtime_error(path + ":" + std::to_string(number) + ": malformed row");
        truth_row r;
        r.set = f[0];
        r.name = f[1];
        double v[9];
        for (int k = 0; k < 9; ++k) {
            const auto x = tools::parse_finite(f[static_cast<std::size_t>(k) + 2]);
            if (!x) throw std::runtime_error(path + ":" + std::to_string(number) + ": malformed row");
            v[k] = *x;
        }
        r.sun_elevation = v[0];
        r.view_elevation = v[1];
        r.view_azimuth = v[2];
        for (int c = 0; c < 3; ++c) {
            r.radiance[c] = v[3 + c];
            r.std_error[c] = v[6 + c];
            if (r.radiance[c] < 0.0 || r.std_error[c] < 0.0)
                throw std::runtime_error(path + ":" + std::to_string(number) + ": negative radiance or error");
        }
        rows.push_back(r);
    }
    if (rows.size() != want.size())
        throw std::runtime_error(path + ": " + std::to_string(rows.size()) + " rows, the set has " + std::to_string(want.size()));
    for (std::size_t i = 0; i < rows.size(); ++i)
        if (rows[i].set != want[i].set || rows[i].name != want[i].name || rows[i].sun_elevation != want[i].sun_elevation ||
            std::abs(rows[i].view_elevation - want[i].view_elevation) > 1e-9 ||
            std::abs(rows[i].view_azimuth - want[i].view_azimuth) > 1e-9)
            throw std::runtime_error(path + ": row " + std::to_string(i + 1) + " is not the set's (" + want[i].set + " " +
                                     want[i].name + " for the sun at " + std::to_string(want[i].sun_elevation) + ")");
    return rows;
}

std::vector<std::array<double, 3>> model_radiance(const std::vector<truth_row>& rows) {
    const auto air = earth_atmosphere<float>();
    const atmosphere_sky_luts<float> luts = atmosphere_make_sky_luts(air, 32, 32);
    const atmosphere_multiple_scattering_table<float> ms = luts.table();
    std::vector<std::array<double, 3>> out;
    out.reserve(rows.size());
    for (const truth_row& r : rows) {
        const mc::vec3 v = direction_from_degrees(r.view_elevation, r.view_azimuth);
        const mc::vec3 s = direction_from_degrees(r.sun_elevation, 0.0);
        const glm::vec3 L = atmosphere_sky_radiance(air, ms, 0.0f, glm::vec3(glm::dvec3(v.x, v.y, v.z)),
                                                    glm::vec3(glm::dvec3(s.x, s.y, s.z)), 32, 32);
        out.push_back({double(L.x), double(L.y), double(L.z)});
    }
    return out;
}

std::vector<ground_row> ground_check(const std::vector<double>& sun_elevations, std::uint64_t paths,
                                     const mc::run_options& options) {
    std::vector<ground_row> rows;
    std::vector<sky_query> queries;
    for (double e : sun_elevations)
        for (const auto& [altitude, view] : {std::pair{0.0, -90.0}, {1000.0, -90.0}, {1000.0, -30.0}, {1000.0, -5.0}}) {
            ground_row r;
            r.sun_elevation = e;
            r.altitude = altitude;
            r.view_elevation = view;
            rows.push_back(r);
            sky_query q;
            q.altitude = altitude;
            q.view = direction_from_degrees(view, 180.0);
            q.sun = direction_from_degrees(e, 0.0);
            queries.push_back(q);
        }
    const std::vector<sky_estimate> est = trace_sky(earth_atmosphere<double>(), queries, paths, options);
    const auto air = earth_atmosphere<float>();
    const atmosphere_sky_luts<float> luts = atmosphere_make_sky_luts(air, 32, 32);
    const atmosphere_multiple_scattering_table<float> sun_only = luts.table();
    const std::vector<glm::vec3> sky_on_ground = atmosphere_ground_irradiance_lut(air, sun_only);
    atmosphere_multiple_scattering_table<float> sky_lit = sun_only;
    sky_lit.ground_irradiance = &sky_on_ground;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const glm::vec3 v(glm::dvec3(queries[i].view.x, queries[i].view.y, queries[i].view.z));
        const glm::vec3 s(glm::dvec3(queries[i].sun.x, queries[i].sun.y, queries[i].sun.z));
        const float h = float(rows[i].altitude);
        const glm::vec3 a = atmosphere_sky_radiance(air, sun_only, h, v, s, 32, 32);
        const glm::vec3 b = atmosphere_sky_radiance(air, sky_lit, h, v, s, 32, 32);
        for (int c = 0; c < 3; ++c) {
            rows[i].truth[c] = est[i].channel[c].mean;
            rows[i].std_error[c] = est[i].channel[c].std_error;
            rows[i].sun_only[c] = double(a[c]);
            rows[i].sky_lit[c] = double(b[c]);
        }
    }
    return rows;
}

error_summary summarise(const std::vector<truth_row>& rows, const std::vector<std::array<double, 3>>& model,
                        const std::string& set, double sun_elevation) {
    error_summary s;
    double sum = 0, weights = 0, noise = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const truth_row& r = rows[i];
        if (r.set != set || r.sun_elevation != sun_elevation) continue;
        // Panorama cells are weighted by their solid angle (cos elevation); table rows alike.
        const double w = set == "panorama" ? std::cos(r.view_elevation * 3.14159265358979323846 / 180.0) : 1.0;
        for (int c = 0; c < 3; ++c) {
            if (!(r.radiance[c] > 0.0)) continue;
            const double e = model[i][static_cast<std::size_t>(c)] / r.radiance[c] - 1.0;
            sum += w * e * e;
            noise += w * (r.std_error[c] / r.radiance[c]) * (r.std_error[c] / r.radiance[c]);
            weights += w;
            if (std::abs(e) > std::abs(s.worst)) s.worst = e;
            ++s.count;
        }
    }
    if (weights > 0) {
        s.rms = std::sqrt(sum / weights);
        s.noise = std::sqrt(noise / weights);
    }
    return s;
}

}  // namespace cloudmath::reference::atmo
