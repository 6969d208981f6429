// cloudmath/cloudmath.hpp: the whole library. Each module can also be included alone.
#ifndef CLOUDMATH_CLOUDMATH_HPP
#define CLOUDMATH_CLOUDMATH_HPP

#include "version.hpp"
#include "core.hpp"
#include "phase.hpp"
#include "transmittance.hpp"
#include "integration.hpp"
#include "multiple_scattering.hpp"
#include "diffusion_lighting.hpp"
#include "lighting_choice.hpp"
#include "cone_sampling.hpp"
#include "geometry.hpp"
#include "density.hpp"
#include "noise.hpp"
#include "sun.hpp"
#include "reprojection.hpp"
#include "shadow_map.hpp"
#include "texture_lod.hpp"
#include "atmosphere.hpp"

#endif  // CLOUDMATH_CLOUDMATH_HPP
