// cloudmath/version.hpp: the library's version, for #if tests and for logs.
//
// Use:      #include <cloudmath/version.hpp>   (cloudmath.hpp includes it)
//           #if CLOUDMATH_VERSION >= 200        // 0.2.0 or later
// The numbers equal project(VERSION) in CMakeLists.txt (hence the CMake package's and the
// pkg-config file's version) and the npm package's version in web/package.json; the test
// version.consistent checks that they agree. docs/releasing.md says how a release bumps them.
// Versions follow semantic versioning; before 1.0 a minor release may change the API.
#ifndef CLOUDMATH_VERSION_HPP
#define CLOUDMATH_VERSION_HPP

#define CLOUDMATH_VERSION_MAJOR 0
#define CLOUDMATH_VERSION_MINOR 1
#define CLOUDMATH_VERSION_PATCH 0
#define CLOUDMATH_VERSION_STRING "0.1.0"

// One number for comparisons: MAJOR * 10000 + MINOR * 100 + PATCH (MINOR, PATCH < 100).
#define CLOUDMATH_VERSION \
    (CLOUDMATH_VERSION_MAJOR * 10000 + CLOUDMATH_VERSION_MINOR * 100 + CLOUDMATH_VERSION_PATCH)

#endif  // CLOUDMATH_VERSION_HPP
