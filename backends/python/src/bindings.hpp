// hush's Python module: the machinery every noise's bindings share (one copy, used by
// src/noise_<noise>.cpp): backends named per call, numpy arrays in and out, keyword parameters
// checked by name, and hush's errors as Python exceptions.
#ifndef HUSH_PYTHON_BINDINGS_HPP
#define HUSH_PYTHON_BINDINGS_HPP

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <list>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "glsl.hpp"
#include "hush/hush.hpp"
#include "hush_python/docstrings.hpp"

namespace hush_python {

namespace py = pybind11;

// ---- Backends: backend="scalar" | "simd" | "glsl", threads=1 (one thread, the caller's), 0
// (one per hardware thread) or n. Threads never change scalar's or simd's values, bit
// for bit (exec.hpp); glsl runs on the process's GL device (glsl.hpp), one thread.
struct backend {
  bool simd = true;
  bool glsl = false;
  int threads = 1;
};

// The backend a call names ('simd', 'scalar' or 'glsl') and its thread count; ValueError otherwise.
inline backend parse_backend(const std::string& name, int threads) {
  backend b;
  if (name == "simd") {
    b.simd = true;
  } else if (name == "scalar") {
    b.simd = false;
  } else if (name == "glsl") {
    if (!glsl_available())
      throw py::value_error(
          "backend 'glsl': this hush module was built without the GL backend (CMake found "
          "neither OSMesa nor EGL); valid: 'simd', 'scalar'");
    b.simd = false;
    b.glsl = true;
  } else {
    throw py::value_error("backend '" + name + "' is invalid; valid: 'simd', 'scalar', 'glsl'");
  }
  if (threads < 0 || threads > hush::exec::parallel_t<hush::exec::simd_t>::kMaxThreads)
    throw py::value_error("threads " + std::to_string(threads) +
                          " is invalid; valid: 0 (one per hardware thread) ... 1024");
  if (b.glsl && threads != 1)
    throw py::value_error(
        "threads " + std::to_string(threads) +
        " is invalid for backend 'glsl'; valid: 1 (the GL device runs the batch)");
  b.threads = threads;
  return b;
}

// Calls f(exec) with the policy `b` names (glsl: on the GL thread, glsl.hpp).
template <class F>
void with_exec(const backend& b, F&& f) {
  if (b.glsl) {
    run_on_glsl_device([&](hush::glsl::device& d) { f(hush::exec::glsl<hush::glsl::device>{d}); });
  } else if (b.threads == 1) {
    if (b.simd)
      f(hush::exec::simd);
    else
      f(hush::exec::scalar);
  } else if (b.simd) {
    f(hush::exec::parallel(hush::exec::simd, b.threads));
  } else {
    f(hush::exec::parallel(hush::exec::scalar, b.threads));
  }
}

// ---- Arrays.
using float_array = py::array_t<float, py::array::c_style | py::array::forcecast>;

// `a` as float32 in C order with a last axis of `cols`: the array itself when it already is
// (no copy), else a converted copy of a real (integer or floating) array. A wrong dtype or
// shape raises ValueError naming `name`.
inline float_array as_rows(const py::handle& a, const char* name, py::ssize_t cols) {
  py::array arr = py::array::ensure(a);
  if (!arr) throw py::value_error(std::string(name) + ": expected an array-like of numbers");
  const char kind = arr.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::value_error(std::string(name) + ": dtype " +
                          py::str(arr.dtype()).cast<std::string>() +
                          " is invalid; valid: a real dtype (float32 is used without a copy)");
  if (arr.ndim() != 2 || arr.shape(1) != cols)
    throw py::value_error(std::string(name) + ": shape " +
                          py::str(py::tuple(py::cast(std::vector<py::ssize_t>(
                                      arr.shape(), arr.shape() + arr.ndim()))))
                              .cast<std::string>() +
                          " is invalid; valid: (N, " + std::to_string(cols) + ")");
  float_array f = float_array::ensure(arr);
  if (!f) throw py::error_already_set();
  return f;
}

// The array a result is written to: a new one of `shape` when `out` is None, else `out` itself,
// which must be a writable C-contiguous float32 array of that shape (reused across calls, it
// saves the allocation and first touch of a new array: backends/python/bench/overhead.py).
inline float_array output(const py::object& out, const std::vector<py::ssize_t>& shape) {
  if (out.is_none()) return float_array(shape);
  std::string want = "(";
  for (const py::ssize_t n : shape) want += std::to_string(n) + (shape.size() == 1 ? ",)" : ", ");
  if (shape.size() != 1) want = want.substr(0, want.size() - 2) + ")";
  const auto fail = [&] {
    throw py::value_error("out: valid: None or a writable C-contiguous float32 array of shape " +
                          want);
  };
  if (!py::isinstance<py::array_t<float, py::array::c_style>>(out)) fail();
  auto a = py::reinterpret_borrow<float_array>(out);
  if (!a.writeable() || a.ndim() != static_cast<py::ssize_t>(shape.size())) fail();
  for (std::size_t i = 0; i < shape.size(); ++i)
    if (a.shape(static_cast<py::ssize_t>(i)) != shape[i]) fail();
  return a;
}

// The values at `points` ((N, D) positions) of a point noise, as a float32 array of N.
template <class Noise>
float_array evaluate_points(const Noise& n, const py::handle& points,
                            const std::string& backend_name, int threads,
                            const py::object& out_arg = py::none()) {
  constexpr int D = Noise::dimension;
  const backend b = parse_backend(backend_name, threads);
  const float_array p = as_rows(points, "points", D);
  const auto count = static_cast<std::size_t>(p.shape(0));
  float_array out = output(out_arg, {static_cast<py::ssize_t>(count)});
  const auto* pts = reinterpret_cast<const hush::vec<float, D>*>(p.data());
  float* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    with_exec(b, [&](const auto& ex) {
      hush::evaluate(n, ex, hush::span<const hush::vec<float, D>>(pts, count),
                     hush::span<float>(o, count));
    });
  }
  return out;
}

// Values and gradients at `points`: (values (N,), gradients (N, D)).
template <class Noise>
std::pair<float_array, float_array> evaluate_gradients(const Noise& n, const py::handle& points,
                                                       const std::string& backend_name,
                                                       int threads) {
  constexpr int D = Noise::dimension;
  const backend b = parse_backend(backend_name, threads);
  const float_array p = as_rows(points, "points", D);
  const auto count = static_cast<std::size_t>(p.shape(0));
  float_array out(static_cast<py::ssize_t>(count));
  float_array grad(std::vector<py::ssize_t>{static_cast<py::ssize_t>(count), D});
  const auto* pts = reinterpret_cast<const hush::vec<float, D>*>(p.data());
  float* o = out.mutable_data();
  auto* g = reinterpret_cast<hush::vec<float, D>*>(grad.mutable_data());
  {
    py::gil_scoped_release release;
    with_exec(b, [&](const auto& ex) {
      hush::evaluate(n, ex, hush::span<const hush::vec<float, D>>(pts, count),
                     hush::span<float>(o, count), hush::span<hush::vec<float, D>>(g, count));
    });
  }
  return {out, grad};
}

// A D-vector from a number (every axis) or a sequence of D numbers.
template <int D>
hush::vec<double, D> as_vec(const py::handle& v, const char* name) {
  hush::vec<double, D> r;
  if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) {
    for (int a = 0; a < D; ++a) r[a] = v.cast<double>();
    return r;
  }
  std::vector<double> xs;
  try {
    xs = v.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    throw py::value_error(std::string(name) + ": expected a number or " + std::to_string(D) +
                          " numbers");
  }
  if (xs.size() != static_cast<std::size_t>(D))
    throw py::value_error(std::string(name) + ": " + std::to_string(xs.size()) +
                          " numbers given; valid: " + std::to_string(D));
  for (int a = 0; a < D; ++a) r[a] = xs[static_cast<std::size_t>(a)];
  return r;
}

// The grid of `shape` (numpy order: (ny, nx) or (nz, ny, nx)) whose sample (i, j[, k]) is at
// origin + step * (i, j[, k]), i along x: the layout of `hush sample`'s .npy output.
template <int D>
hush::grid<D> as_grid(const std::vector<py::ssize_t>& shape, const py::handle& origin,
                      const py::handle& step) {
  if (shape.size() != static_cast<std::size_t>(D))
    throw py::value_error("shape: " + std::to_string(shape.size()) + " axes given; valid: " +
                          std::to_string(D) + (D == 2 ? " (ny, nx)" : " (nz, ny, nx)"));
  hush::grid<D> g;
  g.origin = as_vec<D>(origin, "origin");
  g.step = as_vec<D>(step, "step");
  for (int a = 0; a < D; ++a) {
    const py::ssize_t n = shape[static_cast<std::size_t>(D - 1 - a)];
    if (n < 0) throw py::value_error("shape: a negative size; valid: sizes >= 0");
    g.size[static_cast<std::size_t>(a)] = static_cast<std::size_t>(n);
  }
  return g;
}

// The values of the grid `shape` (origin, step), or of its block (start, size) in numpy axis
// order when `block` is given: the block's samples equal the whole grid's bit for bit
// (hush::grid::block), so chunks computed anywhere assemble into the one-call result.
template <class Noise>
float_array evaluate_grid(const Noise& n, const std::vector<py::ssize_t>& shape,
                          const py::handle& origin, const py::handle& step, const py::object& block,
                          const std::string& backend_name, int threads,
                          const py::object& out_arg = py::none()) {
  constexpr int D = Noise::dimension;
  const backend b = parse_backend(backend_name, threads);
  hush::grid<D> g = as_grid<D>(shape, origin, step);
  std::vector<py::ssize_t> out_shape = shape;
  if (!block.is_none()) {
    std::vector<py::ssize_t> start, size;
    try {
      const auto pair = block.cast<std::pair<std::vector<py::ssize_t>, std::vector<py::ssize_t>>>();
      start = pair.first;
      size = pair.second;
    } catch (const py::cast_error&) {
      throw py::value_error("block: valid: (start, size), each " + std::to_string(D) +
                            " integers in numpy axis order");
    }
    if (start.size() != static_cast<std::size_t>(D) || size.size() != static_cast<std::size_t>(D))
      throw py::value_error("block: start and size need " + std::to_string(D) + " integers each");
    std::array<std::size_t, std::size_t{D}> first{}, count{};
    for (int a = 0; a < D; ++a) {
      const auto k = static_cast<std::size_t>(D - 1 - a);
      if (start[k] < 0 || size[k] < 0)
        throw py::value_error("block: negative start or size; valid: indices inside shape");
      first[static_cast<std::size_t>(a)] = static_cast<std::size_t>(start[k]);
      count[static_cast<std::size_t>(a)] = static_cast<std::size_t>(size[k]);
    }
    g = g.block(first, count);
    out_shape = size;
  }
  float_array out = output(out_arg, out_shape);
  float* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    with_exec(
        b, [&](const auto& ex) { hush::evaluate_grid(n, ex, g, hush::span<float>(o, g.count())); });
  }
  return out;
}

// ---- Samples: positions with footprints (widths (N,) or screen derivatives (N, 2, D): dp/dx,
// dp/dy), normals (N, 3) and surface maps (N, 2, 2), each optional (None).
template <class Noise>
float_array evaluate_samples(const Noise& n, const py::handle& points, const py::object& footprints,
                             const py::object& normals, const py::object& surface_maps,
                             const std::string& backend_name, int threads,
                             const py::object& out_arg = py::none()) {
  constexpr int D = Noise::dimension;
  const backend b = parse_backend(backend_name, threads);
  const float_array p = as_rows(points, "points", D);
  const auto count = static_cast<std::size_t>(p.shape(0));
  hush::samples<D> s;
  s.positions = {reinterpret_cast<const hush::vec<float, D>*>(p.data()), count};
  std::vector<hush::footprint<D>> fps;
  if (!footprints.is_none()) {
    py::array fa = py::array::ensure(footprints);
    if (!fa || (fa.ndim() != 1 && fa.ndim() != 3))
      throw py::value_error("footprints: valid: widths (N,) or derivatives (N, 2, " +
                            std::to_string(D) + ")");
    if (fa.ndim() == 1) {
      const auto w = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(fa);
      if (static_cast<std::size_t>(w.shape(0)) != count)
        throw py::value_error("footprints: " + std::to_string(w.shape(0)) + " widths for " +
                              std::to_string(count) + " points");
      for (std::size_t i = 0; i < count; ++i)
        fps.push_back(hush::footprint<D>::isotropic(w.data()[i]));
    } else {
      const auto d = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(fa);
      if (static_cast<std::size_t>(d.shape(0)) != count || d.shape(1) != 2 || d.shape(2) != D)
        throw py::value_error("footprints: derivatives must have shape (N, 2, " +
                              std::to_string(D) + ") with N = " + std::to_string(count));
      for (std::size_t i = 0; i < count; ++i) {
        hush::vec<double, D> dx, dy;
        for (int a = 0; a < D; ++a) {
          dx[a] = d.data()[i * 2 * D + static_cast<std::size_t>(a)];
          dy[a] = d.data()[i * 2 * D + D + static_cast<std::size_t>(a)];
        }
        fps.push_back(hush::footprint<D>::from_derivatives(dx, dy));
      }
    }
    s.footprints = {fps.data(), fps.size()};
  }
  float_array nrm;
  if (!normals.is_none()) {
    nrm = as_rows(normals, "normals", 3);
    s.normals = {reinterpret_cast<const hush::vec<float, 3>*>(nrm.data()),
                 static_cast<std::size_t>(nrm.shape(0))};
  }
  std::vector<hush::surface_map> maps;
  if (!surface_maps.is_none()) {
    const auto m =
        py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(surface_maps);
    if (!m || m.ndim() != 3 || m.shape(1) != 2 || m.shape(2) != 2)
      throw py::value_error("surface_maps: valid: shape (N, 2, 2)");
    for (py::ssize_t i = 0; i < m.shape(0); ++i) {
      const double* e = m.data() + i * 4;
      maps.push_back(hush::surface_map::from_matrix(e[0], e[1], e[2], e[3]));
    }
    s.surface_maps = {maps.data(), maps.size()};
  }
  float_array out = output(out_arg, {static_cast<py::ssize_t>(count)});
  float* o = out.mutable_data();
  {
    py::gil_scoped_release release;
    with_exec(b, [&](const auto& ex) { hush::evaluate(n, ex, s, hush::span<float>(o, count)); });
  }
  return out;
}

// ---- Keyword parameters: each noise reads its params struct's fields by name; a keyword that
// names no field raises TypeError listing the valid ones, a value of the wrong type ValueError.
class keywords {
 public:
  keywords(const char* where, py::kwargs kw) : where_(where), kw_(std::move(kw)) {}

  template <class T>
  void get(const char* name, T& field) {
    names_.insert(name);
    if (!kw_.contains(name)) return;
    try {
      field = kw_[name].cast<T>();
    } catch (const py::cast_error&) {
      throw py::value_error(std::string(where_) + ": " + name + "=" +
                            py::repr(kw_[name]).cast<std::string>() + " has the wrong type");
    }
  }
  // A per-axis array (periods) from a sequence of D values or one value for every axis.
  template <class T, std::size_t D>
  void get_axes(const char* name, std::array<T, D>& field) {
    names_.insert(name);
    if (!kw_.contains(name)) return;
    const py::object v = kw_[name];
    try {
      if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) {
        field.fill(v.cast<T>());
      } else {
        const auto xs = v.cast<std::vector<T>>();
        if (xs.size() != D) throw py::cast_error();
        for (std::size_t a = 0; a < D; ++a) field[a] = xs[a];
      }
    } catch (const py::cast_error&) {
      throw py::value_error(std::string(where_) + ": " + name + " must be a number or " +
                            std::to_string(D) + " numbers");
    }
  }
  // An enum by its C++ name, e.g. kind="turbulence".
  template <class E>
  void get_enum(const char* name, E& field, const std::vector<std::pair<const char*, E>>& values) {
    names_.insert(name);
    if (!kw_.contains(name)) return;
    std::string valid;
    if (py::isinstance<py::str>(kw_[name])) {
      const auto s = kw_[name].cast<std::string>();
      for (const auto& [text, value] : values)
        if (s == text) {
          field = value;
          return;
        }
    }
    for (const auto& [text, value] : values)
      valid += std::string(valid.empty() ? "'" : ", '") + text + "'";
    throw py::value_error(std::string(where_) + ": " + name + "=" +
                          py::repr(kw_[name]).cast<std::string>() + " is invalid; valid: " + valid);
  }
  // Raises TypeError for any keyword no get() asked for.
  void finish() const {
    for (const auto& item : kw_) {
      const auto k = item.first.cast<std::string>();
      if (names_.count(k)) continue;
      std::string valid;
      for (const auto& n : names_) valid += (valid.empty() ? "" : ", ") + n;
      throw py::type_error(std::string(where_) + ": unknown parameter '" + k +
                           "'; valid: " + valid);
    }
  }

 private:
  const char* where_;
  py::kwargs kw_;
  std::set<std::string> names_;
};

// A noise as Python holds it: the C++ object and the keyword parameters it was made from,
// which are also its pickled state (so a dask worker rebuilds the same noise).
template <class Noise>
struct held {
  Noise noise;
  py::dict params;
};

// A docstring composed at bind time, kept for the module's life (pybind11 keeps the pointer).
inline const char* kept(std::string text) {
  static std::list<std::string> texts;
  texts.push_back(std::move(text));
  return texts.back().c_str();
}

// The docstring of a noise's class: `summary` (one Python line), then the C++ contract and each
// params field's comment, as the generated docs:: tables hold them (tools/python_docstrings.py).
inline std::string class_doc(const char* summary, const docs::noise& d) {
  std::string text = std::string(summary) + "\n\n" + d.contract + "\n\nKeywords: the fields of " +
                     d.header +
                     "'s params (the same names, enums by name); a value outside its "
                     "domain raises ValueError naming it, an unknown keyword TypeError.\n";
  for (std::size_t i = 0; i < d.field_count; ++i) {
    const docs::field& f = d.fields[i];
    text += std::string("\n") + f.keyword + ": " + f.type;
    if (*f.doc) text += std::string("\n    ") + f.doc;
  }
  return text;
}

// The docstring of an evaluation method: `what` (the Python call), then the C++ contract of
// hush::evaluate that applies: `form` (exec.hpp's bullet for points, grids or samples), then
// the bullets every backend argument shares.
inline const char* method_doc(const std::string& what, const char* form) {
  std::string text = what + "\n\nC++ contract (include/hush/exec.hpp, hush::evaluate):";
  for (const char* b : {form, docs::exec_scalar, docs::exec_simd, docs::exec_glsl,
                        docs::exec_parallel, docs::exec_NaN})
    text += std::string("\n - ") + b;
  return kept(text);
}

// The Python class of a noise: made from keyword parameters by `make` (which reads them with
// a `keywords` and returns the noise), picklable, with its parameters as `params`; its
// docstring from `summary` and the contract comments `d`, and `keywords`, the table of its
// keyword parameters: {name: (python type, doc)} (the stubs are written from it).
template <class Noise, class Make>
py::class_<held<Noise>> bind_noise(py::module_& m, const char* name, const char* summary,
                                   const docs::noise& d, Make make) {
  py::class_<held<Noise>> c(m, name, kept(class_doc(summary, d)));
  py::dict table;
  for (std::size_t i = 0; i < d.field_count; ++i)
    table[d.fields[i].keyword] = py::make_tuple(d.fields[i].type, d.fields[i].doc);
  c.attr("keywords") = table;
  c.def(py::init([make](py::kwargs kw) { return held<Noise>{make(kw), py::dict(kw)}; }));
  c.def_property_readonly(
      "params", [](const held<Noise>& h) { return py::dict(h.params); },
      "The keyword parameters this noise was made from.");
  c.def(py::pickle([](const held<Noise>& h) { return py::dict(h.params); },
                   [make](const py::dict& dct) {
                     py::kwargs kw;
                     for (const auto& item : dct) kw[item.first] = item.second;
                     return held<Noise>{make(kw), py::dict(dct)};
                   }));
  c.def("__repr__", [name](const held<Noise>& h) {
    std::string text = std::string("hush.") + name + "(";
    for (const auto& item : h.params) {
      if (text.back() != '(') text += ", ";
      text += py::str(item.first).template cast<std::string>() + "=" +
              py::repr(item.second).template cast<std::string>();
    }
    return text + ")";
  });
  return c;
}

// The point-noise methods: __call__(points), gradient(points), grid(shape, origin, step).
template <class Noise>
void add_point_methods(py::class_<held<Noise>>& c) {
  using H = held<Noise>;
  c.def(
      "__call__",
      [](const H& h, const py::handle& points, const std::string& backend_name, int threads,
         const py::object& out) {
        return evaluate_points(h.noise, points, backend_name, threads, out);
      },
      py::arg("points"), py::arg("backend") = "simd", py::arg("threads") = 1,
      py::arg("out") = py::none(),
      method_doc("Values at points, an (N, D) array (float32 is used without a copy), as float32 "
                 "(N,). backend: 'simd' (default), 'scalar' or 'glsl' (the process's GL device); "
                 "threads: 1 (default), 0 (one per hardware thread) or n (scalar and simd). "
                 "out: None (a new array) or a writable C-contiguous float32 array of shape (N,), "
                 "written and returned (no allocation per call).",
                 docs::exec_points));
  c.def(
      "gradient",
      [](const H& h, const py::handle& points, const std::string& backend_name, int threads) {
        return evaluate_gradients(h.noise, points, backend_name, threads);
      },
      py::arg("points"), py::arg("backend") = "simd", py::arg("threads") = 1,
      method_doc("Values and analytic gradients at points: (values (N,), gradients (N, D)), "
                 "float32. backend and threads as for __call__.",
                 docs::exec_points));
  c.def(
      "grid",
      [](const H& h, const std::vector<py::ssize_t>& shape, const py::handle& origin,
         const py::handle& step, const std::string& backend_name, int threads,
         const py::object& block, const py::object& out) {
        return evaluate_grid(h.noise, shape, origin, step, block, backend_name, threads, out);
      },
      py::arg("shape"), py::arg("origin") = 0.0, py::arg("step") = 1.0, py::arg("backend") = "simd",
      py::arg("threads") = 1, py::arg("block") = py::none(), py::arg("out") = py::none(),
      method_doc(
          "Values on a uniform grid: shape (ny, nx) or (nz, ny, nx); sample (i, j[, k]) is at "
          "origin + step * (i, j[, k]), i along x (numpy's last axis), positions in double. "
          "block=(start, size) (numpy axis order) returns only that block of the grid, bit for "
          "bit the same samples as the whole grid's call. backend, threads and out (of the "
          "returned shape) as for __call__.",
          docs::exec_grids));
  // The C++ calls __call__ and grid make, timed without Python objects: the same inputs (the
  // points converted once), the output `out` (or one array for all repeats), the GIL released;
  // seconds per repeat. For backends/python/bench/overhead.py, which compares them with the Python
  // calls.
  c.def(
      "_cpp_seconds_points",
      [](const H& h, const py::handle& points, const std::string& backend_name, int threads,
         int repeats, const py::object& out_arg) {
        constexpr int D = Noise::dimension;
        const backend b = parse_backend(backend_name, threads);
        const float_array p = as_rows(points, "points", D);
        const auto count = static_cast<std::size_t>(p.shape(0));
        const auto* pts = reinterpret_cast<const hush::vec<float, D>*>(p.data());
        float_array out = output(out_arg, {static_cast<py::ssize_t>(count)});
        float* o = out.mutable_data();
        std::vector<double> seconds;
        py::gil_scoped_release release;
        for (int r = 0; r < repeats; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          with_exec(b, [&](const auto& ex) {
            hush::evaluate(h.noise, ex, hush::span<const hush::vec<float, D>>(pts, count),
                           hush::span<float>(o, count));
          });
          seconds.push_back(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        return seconds;
      },
      py::arg("points"), py::arg("backend") = "simd", py::arg("threads") = 1,
      py::arg("repeats") = 1, py::arg("out") = py::none());
  c.def(
      "_cpp_seconds_grid",
      [](const H& h, const std::vector<py::ssize_t>& shape, const py::handle& origin,
         const py::handle& step, const std::string& backend_name, int threads, int repeats,
         const py::object& out_arg) {
        constexpr int D = Noise::dimension;
        const backend b = parse_backend(backend_name, threads);
        const hush::grid<D> g = as_grid<D>(shape, origin, step);
        float_array out = output(out_arg, shape);
        float* o = out.mutable_data();
        std::vector<double> seconds;
        py::gil_scoped_release release;
        for (int r = 0; r < repeats; ++r) {
          const auto t0 = std::chrono::steady_clock::now();
          with_exec(b, [&](const auto& ex) {
            hush::evaluate_grid(h.noise, ex, g, hush::span<float>(o, g.count()));
          });
          seconds.push_back(
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        }
        return seconds;
      },
      py::arg("shape"), py::arg("origin") = 0.0, py::arg("step") = 1.0, py::arg("backend") = "simd",
      py::arg("threads") = 1, py::arg("repeats") = 1, py::arg("out") = py::none());
  c.def_property_readonly_static("dimension", [](py::object) { return Noise::dimension; });
}

// sample(points, footprints, normals, surface_maps) for the noises that filter or take normals
// or surface maps (core/samples.hpp); inputs a noise does not take raise ValueError.
template <class Noise>
void add_sample_methods(py::class_<held<Noise>>& c) {
  c.def(
      "sample",
      [](const held<Noise>& h, const py::handle& points, const py::object& footprints,
         const py::object& normals, const py::object& surface_maps, const std::string& backend_name,
         int threads, const py::object& out) {
        return evaluate_samples(h.noise, points, footprints, normals, surface_maps, backend_name,
                                threads, out);
      },
      py::arg("points"), py::arg("footprints") = py::none(), py::arg("normals") = py::none(),
      py::arg("surface_maps") = py::none(), py::arg("backend") = "simd", py::arg("threads") = 1,
      py::arg("out") = py::none(),
      method_doc("Filtered values at points: footprints as widths (N,) or screen derivatives "
                 "(N, 2, D) (dp/dx, dp/dy); normals (N, 3) for 3D noises that project; "
                 "surface_maps (N, 2, 2) for 2D texture-space noises. Each None or one per "
                 "point. backend, threads and out as for __call__.",
                 docs::exec_samples));
}

}  // namespace hush_python

#endif  // HUSH_PYTHON_BINDINGS_HPP
