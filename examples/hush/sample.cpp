// hush — the `hush` program: `hush sample NOISE [options] --out FILE.npy|FILE.png`.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "image.hpp"
#include "noises.hpp"
#include "npy/npy.hpp"
#include "output_file.hpp"
#include "progress.hpp"

namespace hush_cli {
namespace {

// 32 samples per lattice cell: Perlin noise looks smooth and nothing aliases.
constexpr double kDefaultStep = 1.0 / 32;
constexpr const char* kDefaultSize = "256";
// A bound on the work one command may ask for (8 GiB of float32).
constexpr std::uint64_t kMaxSamples = std::uint64_t(1) << 31;

enum class format { npy, png };

// A parsed `hush sample` command line.
struct request {
  const noise_entry* noise = nullptr;
  option_values noise_options;
  noise_setup setup;
  sample_grid grid;
  std::vector<std::size_t> shape;  // of the output, C order: (ny, nx) or (nz, ny, nx)
  std::string out;
  format out_format = format::npy;
  backend where = backend::scalar;
  std::optional<std::pair<double, double>> range;  // --range lo,hi (PNG only)
};

// --size N | NxM | NxMxK: grid.size and the output shape. N alone means N along every
// axis of the noise; NxM is one plane (with --dim 3, the z-plane at the origin's z).
void parse_size(const std::string& token, request& r) {
  const std::string max = std::to_string(kMaxSamples);
  const std::vector<std::string> parts = split(token, 'x');
  const std::size_t axes = parts.size();
  if (axes > 3 || (axes == 3 && r.setup.dim == 2))
    throw_bad_value("--size", token,
                    r.setup.dim == 2 ? "N or NxM (NxMxK needs --dim 3)" : "N, NxM or NxMxK");
  std::vector<std::size_t> n;
  for (const std::string& p : parts) {
    long long e = 0;
    if (!to_integer(p, e) || e < 1 || e > static_cast<long long>(kMaxSamples))
      throw_bad_value("--size", token, "N, NxM or NxMxK, each extent an integer in 1 ... " + max);
    n.push_back(static_cast<std::size_t>(e));
  }
  if (axes == 1) n.assign(static_cast<std::size_t>(r.setup.dim), n[0]);  // square or cube
  std::uint64_t count = 1;
  for (std::size_t e : n) {
    count *= e;  // cannot overflow: both factors are <= 2^31
    if (count > kMaxSamples) throw_bad_value("--size", token, "at most " + max + " samples in all");
  }
  r.grid.size = {n[0], n[1], n.size() == 3 ? n[2] : 1};
  r.shape.assign(n.rbegin(), n.rend());
}

// --region x0,y0[,z0]:nx,ny[,nz]: the block of the --size grid to render (grid::block),
// one first index and one extent per axis of that grid, each extent >= 1 and the block
// inside the grid. Samples keep their whole-grid positions, so blocks rendered anywhere
// equal the same samples of the whole grid bit for bit; the output holds the block only.
void parse_region(const std::string& token, request& r) {
  const std::size_t axes = r.shape.size();
  const std::string form = axes == 2 ? "x0,y0:nx,ny" : "x0,y0,z0:nx,ny,nz";
  const std::vector<std::string> halves = split(token, ':');
  std::vector<std::size_t> v;
  for (std::size_t h = 0; halves.size() == 2 && h < 2; ++h)
    for (const std::string& p : split(halves[h], ',')) {
      long long e = 0;
      if (!to_integer(p, e) || e < (h == 0 ? 0 : 1) || e > static_cast<long long>(kMaxSamples))
        v.push_back(SIZE_MAX);  // refused below with the form
      else
        v.push_back(static_cast<std::size_t>(e));
    }
  if (v.size() != 2 * axes || std::count(v.begin(), v.end(), SIZE_MAX) != 0)
    throw_bad_value("--region", token,
                    form + " (" + std::to_string(axes) +
                        " first indices >= 0 and extents >= 1, one per axis of --size)");
  std::array<std::size_t, 3> first{0, 0, 0}, size{1, 1, 1};
  for (std::size_t a = 0; a < axes; ++a) {
    first[a] = v[a];
    size[a] = v[axes + a];
    if (first[a] + size[a] > r.grid.size[a])
      throw_bad_value("--region", token,
                      form + " inside the --size grid: first + extent <= " +
                          std::to_string(r.grid.size[a]) + " along " + "xyz"[a]);
  }
  r.grid = r.grid.block(first, size);
  r.shape.assign(size.rbegin() + static_cast<std::ptrdiff_t>(3 - axes), size.rend());
}

format parse_out(const std::string& path) {
  std::string ext = path.size() >= 4 ? path.substr(path.size() - 4) : "";
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".npy") return format::npy;
  if (ext == ".png") return format::png;
  throw_bad_value("--out", path, "a file name ending in .npy or .png");
}

request parse_request(const std::vector<std::string>& args) {
  request r;
  arg_reader in(args);
  r.noise = &find_noise(in.positional("NOISE", noise_names()));
  std::vector<option_spec> options = sample_options();
  options.insert(options.end(), r.noise->options.begin(), r.noise->options.end());
  option_values given;
  while (!in.done()) {
    const option_spec& o = in.option(options);
    given[o.name] = in.value();
  }
  // Read in dependency order (--dim first), not command-line order.
  auto take = [&given](const char* name) { return find_value(given, name); };
  if (const std::string* v = take("--dim"))
    r.setup.dim = parse_choice<int>("--dim", *v, {{"2", 2}, {"3", 3}});
  const std::size_t dim = static_cast<std::size_t>(r.setup.dim);
  if (const std::string* v = take("--seed"))
    r.setup.seed = static_cast<std::uint32_t>(parse_integer("--seed", *v, 0, UINT32_MAX));
  if (const std::string* v = take("--backend"))
    r.where = parse_choice<backend>(
        "--backend", *v,
        {{"scalar", backend::scalar}, {"simd", backend::simd}, {"glsl", backend::glsl}});
  parse_size(take("--size") ? *take("--size") : kDefaultSize, r);
  if (const std::string* v = take("--origin")) {
    const std::vector<double> o = parse_finite_list("--origin", *v, dim);
    for (std::size_t a = 0; a < dim; ++a) r.grid.origin[a] = o[a];
  }
  double step = kDefaultStep;
  if (const std::string* v = take("--step")) {
    const char* valid = "a finite non-zero number";
    step = parse_finite("--step", *v, valid);
    if (step == 0) throw_bad_value("--step", *v, valid);
  }
  r.grid.step = {step, step, step};
  if (const std::string* v = take("--region")) parse_region(*v, r);
  const std::string* out = take("--out");
  if (!out) throw usage_error("missing --out FILE.npy|FILE.png (where to write the samples)");
  r.out = *out;
  r.out_format = parse_out(r.out);
  if (r.out_format == format::png) {
    if (!png_supported())
      throw usage_error("--out " + r.out + ": " + png_unavailable_reason() +
                        "; write .npy instead");
    if (r.grid.size[2] != 1)
      throw usage_error("--out " + r.out + ": a PNG holds one 2D image but --size gives " +
                        std::to_string(r.grid.size[2]) + " z-planes; write .npy instead");
    if (r.grid.count() > kMaxPngPixels)
      throw usage_error("--out " + r.out + ": a PNG holds at most " +
                        std::to_string(kMaxPngPixels) + " pixels; write .npy instead");
  }
  if (const std::string* v = take("--range")) {
    const char* valid = "two finite numbers lo,hi with lo < hi";
    const std::vector<double> lh = parse_finite_list("--range", *v, 2);
    if (!(lh[0] < lh[1]) || !std::isfinite(lh[1] - lh[0])) throw_bad_value("--range", *v, valid);
    if (r.out_format != format::png)
      throw usage_error("--range '" + *v +
                        "': only PNG output has a display range (--out FILE.png)");
    r.range = std::make_pair(lh[0], lh[1]);
  }
  // The noise's own options, as the noise entry parses them.
  for (const option_spec& o : r.noise->options)
    if (const std::string* v = take(o.name)) r.noise_options[o.name] = *v;
  return r;
}

// Calls on_row(row, values) for every row of the grid in C order, evaluating blocks of
// rows on the request's backend (one call per block keeps per-call costs small), with
// progress per block.
template <class OnRow>
void for_each_row(const noise_field& field, const request& r, OnRow on_row) {
  const sample_grid& grid = r.grid;
  const std::size_t nx = grid.size[0], ny = grid.size[1];
  // About a million samples per block, at least one row.
  const std::size_t block_rows = std::max<std::size_t>(1, (std::size_t(1) << 20) / nx);
  progress bar("hush sample", ny * grid.size[2]);
  std::vector<float> values(std::min(block_rows, ny) * nx);
  std::size_t done = 0;
  for (std::size_t k = 0; k < grid.size[2]; ++k)
    for (std::size_t j0 = 0; j0 < ny; j0 += block_rows) {
      const std::size_t rows = std::min(block_rows, ny - j0);
      field.sample_rows(grid, j0, rows, k, values.data(), r.where);
      for (std::size_t j = 0; j < rows; ++j) on_row(k * ny + j0 + j, values.data() + j * nx, nx);
      done += rows;
      bar.update(done);
    }
}

}  // namespace

const std::vector<option_spec>& sample_options() {
  static const std::vector<option_spec> options = {
      {"--dim", "2|3", "the dimension of the noise (default 2)"},
      {"--size", "N|NxM|NxMxK",
       "samples along x, y[, z] (default 256: NxN in 2D, NxNxN in 3D; NxM with --dim 3 is the "
       "z-plane at the origin's z); at most 2^31 samples"},
      {"--origin", "x,y[,z]",
       "the position of sample (0, 0[, 0]), one finite number per dimension (default 0)"},
      {"--step", "s", "the spacing of the samples, finite and non-zero (default 0.03125 = 1/32)"},
      {"--region", "x0,y0[,z0]:nx,ny[,nz]",
       "render only the block of nx x ny[ x nz] samples starting at sample (x0, y0[, z0]) of the "
       "--size grid (one number per axis of --size); blocks equal the same samples of the "
       "whole grid bit for bit, so a job can be split over machines (default: the whole grid)"},
      {"--seed", "n", "an integer in 0 ... 4294967295 (default 0)"},
      {"--backend", "scalar|simd|glsl",
       "the evaluation backend (default scalar): scalar C++, SIMD (Highway), or GLSL compute "
       "shaders"},
      {"--out", "FILE.npy|FILE.png", "the output file (required)"},
      {"--range", "lo,hi",
       "PNG only: the values shown black..white, finite, lo < hi, outside clipped (default per "
       "noise: -3,3 for unit-variance noise: wavelet (gaussian), Gabor, fBm, anisotropic fbm "
       "(3 standard deviations, 0.27 % of a Gaussian clipped); -1,1 for Perlin, uniform wavelet, "
       "unit_range fractals; 0,1 for turbulence)"},
  };
  return options;
}

int run_sample(const std::vector<std::string>& args) {
  const request r = parse_request(args);
  const std::unique_ptr<noise_field> field = make_noise(*r.noise, r.setup, r.noise_options);
  const std::string why_not = field->unsupported_reason(r.where);
  if (!why_not.empty())
    throw usage_error(std::string("--backend ") + backend_name(r.where) + ": " + why_not);
  const std::size_t nx = r.grid.size[0];
  if (r.out_format == format::npy) {
    std::optional<hush_tools::npy::writer> npy;  // streamed by rows: any size without holding it
    as_run_error([&] { npy.emplace(r.out, hush_tools::npy::dtype::float32, r.shape); });
    for_each_row(*field, r, [&](std::size_t, const float* row, std::size_t n) {
      as_run_error([&] { npy->write(row, n); });
    });
    as_run_error([&] { npy->close(); });
  } else {
    gray_image image(nx, r.grid.size[1]);
    const std::pair<double, double> range = r.range.value_or(field->png_range());
    for_each_row(*field, r, [&](std::size_t j, const float* row, std::size_t) {
      for (std::size_t i = 0; i < nx; ++i)
        image.at(i, j) = to_gray(row[i], range.first, range.second);
    });
    write_png(r.out, image);
  }
  return 0;
}

}  // namespace hush_cli
