// cloudmath/glsl.hpp: the GLSL twins as strings, with their #include lines resolved, for
// raw OpenGL (which has no #include) and for engines that assemble shaders at run time.
//
// Use:      #include <cloudmath/glsl.hpp>
//           std::string src = "#version 330 core\n" + cloudmath::glsl_source("phase") + my_code;
// Sources:  glsl_source() reads the copies in cloudmath/glsl_embedded.hpp (a committed header
//           written from include/cloudmath/glsl/*.glsl by cmake/UpdateGlslEmbedded.cmake, so
//           include/ copied alone is complete): no file I/O, no paths. glsl_source_from_directory() does the same from
//           .glsl files on disk, for engines that ship or hot-reload shader files.
// Modules:  "core", "phase", "transmittance", "integration", "multiple_scattering",
//           "diffusion_lighting" (with its generated "diffusion_lighting_models"),
//           "cone_sampling", "geometry", "density", "noise", "sun", "reprojection", "shadow_map",
//           "texture_lod", and "cloudmath" (all of them).
// Includes: a line `#include "name.glsl"` is replaced by that file's resolved text the first
//           time it is met and dropped afterwards (what the include guards would do).
//           The result has no #version line: the caller chooses the target.
// Errors:   no exceptions (apart from std::bad_alloc): an unknown module or a missing file
//           gives an empty string and, if `error` is given, a message.
// Not part of cloudmath.hpp: it needs <string> and <fstream>, which the math does not.
#ifndef CLOUDMATH_GLSL_HPP
#define CLOUDMATH_GLSL_HPP

#include <cloudmath/glsl_embedded.hpp>

#include <cstddef>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cloudmath {

namespace detail {

// Returns the quoted file name of an `#include "..."` line, or an empty view.
inline std::string_view glsl_include_target(std::string_view line) {
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string_view::npos || line[i] != '#') return {};
    i = line.find_first_not_of(" \t", i + 1);
    if (i == std::string_view::npos || line.compare(i, 7, "include") != 0) return {};
    const std::size_t open = line.find('"', i + 7);
    if (open == std::string_view::npos) return {};
    const std::size_t close = line.find('"', open + 1);
    if (close == std::string_view::npos) return {};
    return line.substr(open + 1, close - open - 1);
}

template <class Loader>
bool glsl_resolve(const std::string& name, Loader& load, std::vector<std::string>& seen,
                  std::string& out, std::string& error);

// Appends `text` to `out` with each `#include "name"` line replaced by that file resolved.
template <class Loader>
bool glsl_expand(std::string_view text, Loader& load, std::vector<std::string>& seen, std::string& out,
                 std::string& error) {
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view line = text.substr(pos, end - pos);
        const std::string_view target = glsl_include_target(line);
        if (!target.empty()) {
            if (!glsl_resolve(std::string(target), load, seen, out, error)) return false;
        } else {
            out.append(line.data(), line.size());
            out.push_back('\n');
        }
        pos = end + 1;
    }
    return true;
}

// Appends file `name` resolved to `out`. `load(name, key, text)` fetches a file's text and
// its canonical name `key` (what include-once compares). Files already in `seen` are
// skipped; a missing file sets `error` and stops.
template <class Loader>
bool glsl_resolve(const std::string& name, Loader& load, std::vector<std::string>& seen,
                  std::string& out, std::string& error) {
    std::string key, text;
    if (!load(name, key, text)) {
        error = "cloudmath: no GLSL file named '" + name + "'";
        return false;
    }
    for (const std::string& s : seen)
        if (s == key) return true;
    seen.push_back(key);
    return glsl_expand(text, load, seen, out, error);
}

// The file name without its directories: includes name files relative to the including
// file, and all of cloudmath's twins share one folder.
inline std::string glsl_base_name(const std::string& name) {
    const std::size_t slash = name.find_last_of('/');
    return slash == std::string::npos ? name : name.substr(slash + 1);
}

// Loads an embedded file by its base name.
inline bool glsl_load_embedded(const std::string& name, std::string& key, std::string& text) {
    key = glsl_base_name(name);
    for (const glsl_embedded::file& f : glsl_embedded::files)
        if (key == f.name) {
            text = f.text;
            return true;
        }
    return false;
}

template <class Loader>
std::string glsl_resolve_module(std::string_view module, Loader load, std::string* error) {
    std::vector<std::string> seen;
    std::string out, message;
    if (!glsl_resolve(std::string(module) + ".glsl", load, seen, out, message)) {
        if (error) *error = message;
        return {};
    }
    if (error) error->clear();
    return out;
}

}  // namespace detail

// Names of the embedded files, e.g. "phase.glsl".
[[nodiscard]] inline std::vector<std::string_view> glsl_file_names() {
    std::vector<std::string_view> names;
    for (const glsl_embedded::file& f : glsl_embedded::files) names.emplace_back(f.name);
    return names;
}

// A file's embedded text as shipped (with its #include lines), or empty if unknown.
[[nodiscard]] inline std::string_view glsl_embedded_file(std::string_view file_name) {
    for (const glsl_embedded::file& f : glsl_embedded::files)
        if (file_name == f.name) return f.text;
    return {};
}

// A module's source with its includes resolved, from the embedded copies.
[[nodiscard]] inline std::string glsl_source(std::string_view module, std::string* error = nullptr) {
    return detail::glsl_resolve_module(module, detail::glsl_load_embedded, error);
}

// The same from the .glsl files in `directory` (for example the installed
// <prefix>/include/cloudmath/glsl).
[[nodiscard]] inline std::string glsl_source_from_directory(const std::string& directory,
                                                            std::string_view module,
                                                            std::string* error = nullptr) {
    return detail::glsl_resolve_module(
        module,
        [&directory](const std::string& name, std::string& key, std::string& text) {
            key = detail::glsl_base_name(name);
            std::ifstream in(directory + "/" + key, std::ios::binary);
            if (!in) return false;
            std::ostringstream buffer;
            buffer << in.rdbuf();
            text = buffer.str();
            return true;
        },
        error);
}

// Your own shader source with its `#include "name"` lines resolved (what an engine without a
// GLSL #include needs): each line is replaced by that file's text, itself resolved, the first
// time the file is met, and dropped afterwards (what include guards would do). Names are looked
// up among `files` (name -> text; as written, then by base name on both sides, so
// "lighting.glsl" finds "shaders/lighting.glsl"), then among cloudmath's
// embedded twins by base name, so `#include "cloudmath/glsl/phase.glsl"` and
// `#include "phase.glsl"` both work. Other lines are kept as they are: a `#define` placed
// before an include (configuration, callbacks such as CM_CONE_EXTINCTION) still applies. A
// missing file gives an empty string and, if `error` is given, a message that names it.
[[nodiscard]] inline std::string glsl_resolve_includes(
    std::string_view source, const std::vector<std::pair<std::string, std::string>>& files = {},
    std::string* error = nullptr) {
    const auto load = [&files](const std::string& name, std::string& key, std::string& text) {
        const std::string base = detail::glsl_base_name(name);
        for (int pass = 0; pass < 2; ++pass)  // as written first, then by base name
            for (const auto& [file_name, file_text] : files)
                if (pass == 0 ? file_name == name : detail::glsl_base_name(file_name) == base) {
                    key = "user:" + file_name;
                    text = file_text;
                    return true;
                }
        return detail::glsl_load_embedded(name, key, text);
    };
    std::vector<std::string> seen;
    std::string out, message;
    if (!detail::glsl_expand(source, load, seen, out, message)) {
        if (error) *error = message;
        return {};
    }
    if (error) error->clear();
    return out;
}

}  // namespace cloudmath

#endif  // CLOUDMATH_GLSL_HPP
