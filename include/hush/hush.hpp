// hush — procedural noise for rendering. MIT License, see LICENSE.
//
// Umbrella header: everything hush offers. Include the one-concept headers
// (hush/perlin.hpp, hush/core/rng.hpp, ...) instead to compile less.
#ifndef HUSH_HUSH_HPP
#define HUSH_HUSH_HPP

#include "hush/anisotropic.hpp"
#include "hush/anisotropic/steerable.hpp"
#include "hush/anisotropic/subband_fit.hpp"
#include "hush/config.hpp"
#include "hush/core/bspline.hpp"
#include "hush/core/error.hpp"
#include "hush/core/footprint.hpp"
#include "hush/core/frame.hpp"
#include "hush/core/hash.hpp"
#include "hush/core/lattice.hpp"
#include "hush/core/point_noise.hpp"
#include "hush/core/poisson_table.hpp"
#include "hush/core/rng.hpp"
#include "hush/core/samples.hpp"
#include "hush/core/surface_map.hpp"
#include "hush/core/tile_cache.hpp"
#include "hush/core/triangles.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/exec.hpp"
#include "hush/fractal.hpp"
#include "hush/gabor.hpp"
#include "hush/gabor/kernel.hpp"
#include "hush/perlin.hpp"
#include "hush/wavelet.hpp"
#include "hush/wavelet/tile.hpp"

// Scene-driven noises (hush::frame: per-frame G-buffer views).
#include "hush/coherent.hpp"
#include "hush/npr_gabor.hpp"
#include "hush/npr_gabor/style.hpp"

#endif  // HUSH_HUSH_HPP
