// hush — the speed-vs-error benchmark: the peer libraries' rows, each where found at build time
// (bench/CMakeLists.txt): glm::perlin (perlin 2D, 3D) and libnoise's Perlin module (perlin and
// fbm 2D, 3D) on the point noises' grids and random points (rows.hpp).
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "rows.hpp"

#if HUSH_BENCH_HAVE_GLM
#include <glm/gtc/noise.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#endif
#if HUSH_BENCH_HAVE_LIBNOISE
#include <noise.h>
#endif

namespace hush_bench {
namespace {

// ---- Peer rows: the same positions through another library, value only (neither offers
// gradients). Grid rows form each position in double as hush's grid path does.

// A peer case from its per-position evaluation `eval(dvec<D>) -> float or double`; the loop
// reads double positions, as hush's grid path forms them (a float peer converts each).
template <int D, class Eval>
prepared_case prepare_peer(std::vector<dvec<D>> positions, Eval eval) {
  auto pos = std::make_shared<std::vector<dvec<D>>>(std::move(positions));
  auto out = std::make_shared<std::vector<float>>(pos->size());
  prepared_case p;
  p.samples = pos->size();
  p.run = [pos, out, eval] {
    float* o = out->data();
    for (std::size_t i = 0; i < pos->size(); ++i) o[i] = static_cast<float>(eval((*pos)[i]));
    keep(*out);
  };
  p.run();
  return p;
}

template <int D>
std::vector<dvec<D>> grid_positions(const hush::grid<D>& g) {
  std::vector<dvec<D>> pos(g.count());
  for_each_sample(g, [&](std::size_t idx, const dvec<D>& q) { pos[idx] = q; });
  return pos;
}

template <int D>
std::vector<dvec<D>> point_positions(std::size_t n) {
  std::vector<dvec<D>> pos;
  for (const fvec<D>& q : make_points<D>(n)) pos.push_back(hush::vec_cast<double>(q));
  return pos;
}

// Adds a peer's {grid, points} rows for one noise; `make_eval` returns the evaluator and
// `add_error(positions, stats)` measures its float error (nullptr: double only).
template <int D, class MakeEval>
void add_peer_rows(std::vector<bench_case>& cases, const sizes& s, bench_case row,
                   MakeEval make_eval,
                   void (*add_error)(const std::vector<dvec<D>>&, error_stats&)) {
  const hush::grid<D> g = make_grid<D>(s);
  const std::size_t n = s.points;
  auto prepare = [make_eval, add_error](std::vector<dvec<D>> pos) {
    prepared_case p = prepare_peer<D>(pos, make_eval());
    if (add_error) add_error(pos, p.value_error);
    return p;
  };
  row.peer = true;
  row.workload = grid_name(g);
  row.prepare = [prepare, g] { return prepare(grid_positions(g)); };
  cases.push_back(row);
  row.workload = "points " + std::to_string(n);
  row.prepare = [prepare, n] { return prepare(point_positions<D>(n)); };
  cases.push_back(row);
}

#if HUSH_BENCH_HAVE_GLM
// glm::perlin takes float vectors; its error is float against glm's own double evaluation at
// the same float-rounded positions (like for like: what float arithmetic costs glm).
template <int D>
using glm_vec = glm::vec<D, float, glm::defaultp>;
template <int D>
using glm_dvec = glm::vec<D, double, glm::defaultp>;

template <int D>
glm_vec<D> to_glm_float(const dvec<D>& p) {
  glm_vec<D> v;
  for (int a = 0; a < D; ++a) v[a] = static_cast<float>(p[a]);
  return v;
}

template <int D>
void glm_error(const std::vector<dvec<D>>& positions, error_stats& e) {
  for (const dvec<D>& p : positions) {
    const glm_vec<D> f = to_glm_float(p);
    e.add(glm::perlin(f), glm::perlin(glm_dvec<D>(f)));
  }
}

template <int D>
void add_glm_rows(std::vector<bench_case>& cases, const sizes& s) {
  bench_case row;
  row.noise = D == 2 ? "perlin 2D" : "perlin 3D";
  row.backend = "glm::perlin";
  row.reference = error_reference::glm_double;
  add_peer_rows<D>(
      cases, s, row, [] { return [](const dvec<D>& p) { return glm::perlin(to_glm_float(p)); }; },
      &glm_error<D>);
}
#endif

#if HUSH_BENCH_HAVE_LIBNOISE
// libnoise's Perlin module is 3D and double only; 2D rows evaluate the plane z = 0.
// QUALITY_BEST is the quintic fade of improved Perlin noise, as hush uses.
template <int D>
void add_libnoise_rows(std::vector<bench_case>& cases, const sizes& s, int octaves) {
  bench_case row;
  row.noise = std::string(octaves == 1 ? "perlin " : "fbm ") + (D == 2 ? "2D" : "3D");
  row.backend = "libnoise";
  row.reference = error_reference::none;
  row.note = "QUALITY_BEST, " + std::to_string(octaves) + " octave" + (octaves > 1 ? "s" : "") +
             (D == 2 ? ", 3D module at z = 0" : "");
  add_peer_rows<D>(
      cases, s, row,
      [octaves] {
        auto module = std::make_shared<noise::module::Perlin>();
        module->SetSeed(static_cast<int>(kNoiseSeed));
        module->SetOctaveCount(octaves);
        module->SetNoiseQuality(noise::QUALITY_BEST);
        return [module](const dvec<D>& p) {
          return module->GetValue(p[0], p[1], D == 3 ? p[D - 1] : 0.0);
        };
      },
      nullptr);
}
#endif

}  // namespace

void add_peer_cases([[maybe_unused]] std::vector<bench_case>& cases,
                    [[maybe_unused]] const sizes& s) {
#if HUSH_BENCH_HAVE_GLM
  add_glm_rows<2>(cases, s);
  add_glm_rows<3>(cases, s);
#endif
#if HUSH_BENCH_HAVE_LIBNOISE
  for (const int octaves : {1, kFbmOctaves}) {
    add_libnoise_rows<2>(cases, s, octaves);
    add_libnoise_rows<3>(cases, s, octaves);
  }
#endif
}

}  // namespace hush_bench
