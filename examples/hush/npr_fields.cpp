// hush — the `hush` program: NPR Gabor parameter fields (see npr_fields.hpp).
#include "npr_fields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "hush/core/param_source.hpp"
#include "hush/detail/constants.hpp"
#include "hush/npr_gabor/style.hpp"

namespace hush_cli {

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// A pixel the fields describe: a surface (object id > 0 where the G-buffer has ids) at a
// positive finite depth; elsewhere a field is NaN, i.e. the constant.
bool covered(const hush::frame& f, std::size_t x, std::size_t y) {
  const float z = f.depth(x, y);
  if (!(z > 0.0f) || !std::isfinite(z)) return false;
  return f.object_id.data == nullptr || f.object_id(x, y) != 0;
}

}  // namespace

npr_param_field parse_npr_field(const std::string& option, const std::string& spec, double min,
                                double max, const std::string& valid) {
  const std::string forms = "shading:LO,HI or depth:LO,HI with LO and HI in " + valid +
                            ", or file:NAME (DIR/frame_NNNN/NAME.npy)";
  npr_param_field p;
  p.option = option;
  const std::size_t colon = spec.find(':');
  if (colon == std::string::npos) throw_bad_value(option, spec, forms);
  const std::string head = spec.substr(0, colon), tail = spec.substr(colon + 1);
  if (head == "file") {
    // A plain file name in the frame directory (no path: the field belongs to each frame).
    if (tail.empty() || tail.find('/') != std::string::npos || tail == "." || tail == "..")
      throw_bad_value(option, spec, forms);
    p.from = npr_param_field::kind::file;
    p.file = tail;
    return p;
  }
  if (head == "shading")
    p.from = npr_param_field::kind::shading;
  else if (head == "depth")
    p.from = npr_param_field::kind::depth;
  else
    throw_bad_value(option, spec, forms);
  const std::vector<std::string> parts = split(tail, ',');
  if (parts.size() != 2 || !to_finite(parts[0], p.lo) || !to_finite(parts[1], p.hi) ||
      !(p.lo >= min && p.lo <= max && p.hi >= min && p.hi <= max))
    throw_bad_value(option, spec, forms);
  return p;
}

bool npr_field_options::uses(npr_param_field::kind k) const {
  return frequency.from == k || bandwidth.from == k || impulses.from == k;
}

bool npr_field_options::any() const {
  return frequency.from != npr_param_field::kind::constant ||
         bandwidth.from != npr_param_field::kind::constant ||
         impulses.from != npr_param_field::kind::constant;
}

void npr_fields::update(const hush::frame& f, const hush::triangle_list& t,
                        hush::image_view<const hush::vec3> normals, const field_loader& load) {
  width_ = f.width();
  height_ = f.height();
  if (o_.uses(npr_param_field::kind::depth) && !range_known_) {
    // The first frame drawn (frame 0) fixes the range for the sequence.
    if (!o_.depth_range_given) {
      double lo = std::numeric_limits<double>::infinity(), hi = 0;
      for (std::size_t y = 0; y < height_; ++y)
        for (std::size_t x = 0; x < width_; ++x)
          if (covered(f, x, y)) {
            lo = std::min(lo, static_cast<double>(f.depth(x, y)));
            hi = std::max(hi, static_cast<double>(f.depth(x, y)));
          }
      o_.z0 = std::isfinite(lo) ? lo : 0.0;
      o_.z1 = std::isfinite(lo) ? hi : 0.0;
    }
    range_known_ = true;
  }
  if (o_.uses(npr_param_field::kind::shading)) {
    tone_.assign(width_ * height_, kNaN);
    for (std::size_t y = 0; y < height_; ++y)
      for (std::size_t x = 0; x < width_; ++x)
        if (covered(f, x, y)) {
          const hush::vec3 n = normals(x, y);
          tone_[y * width_ + x] =
              static_cast<float>(hush::style::shading_tone({n.x, n.y, n.z}, o_.light, o_.ambient));
        }
  }
  fill(o_.frequency, frequency_, f, t, load);
  fill(o_.bandwidth, bandwidth_, f, t, load);
  fill(o_.impulses, impulses_, f, t, load);
}

void npr_fields::fill(const npr_param_field& p, values& out, const hush::frame& f,
                      const hush::triangle_list& t, const field_loader& load) {
  using kind = npr_param_field::kind;
  out.per_vertex = false;
  if (p.from == kind::constant) return;
  if (p.from == kind::file) {
    field_file file = load(p.file);
    const bool pixels = file.shape.size() == 2 && file.shape[0] == height_ && file.shape[1] == width_;
    const bool vertices = file.shape.size() == 1 && file.shape[0] == t.vertices();
    if (!pixels && !vertices)
      throw usage_error(p.option + " 'file:" + p.file + "': " + p.file + ".npy has shape (" +
                        [&] {
                          std::string s;
                          for (std::size_t k = 0; k < file.shape.size(); ++k)
                            s += (k ? ", " : "") + std::to_string(file.shape[k]);
                          return s + (file.shape.size() == 1 ? ",)" : ")");
                        }() +
                        "; valid: (" + std::to_string(height_) + ", " + std::to_string(width_) +
                        ") per pixel or (" + std::to_string(t.vertices()) + ",) per vertex");
    out.per_vertex = vertices;
    out.v = std::move(file.values);
    return;
  }
  out.v.assign(width_ * height_, kNaN);
  // Linear map of s (tone, or depth over [z0, z1]) to [lo, hi], s clamped to [0, 1].
  const double span = o_.z1 - o_.z0;
  for (std::size_t y = 0; y < height_; ++y)
    for (std::size_t x = 0; x < width_; ++x) {
      if (!covered(f, x, y)) continue;
      double s = 0;
      if (p.from == kind::shading)
        s = tone_[y * width_ + x];
      else if (span > 0)
        s = (static_cast<double>(f.depth(x, y)) - o_.z0) / span;
      s = std::clamp(s, 0.0, 1.0);
      out.v[y * width_ + x] = static_cast<float>(p.lo + (p.hi - p.lo) * s);
    }
}

hush::param_source npr_fields::source(const npr_param_field& p, values& in, double scale,
                                      double cap) const {
  if (p.from == npr_param_field::kind::constant) return {};
  const std::vector<float>* v = &in.v;
  if (scale != 1.0) {
    in.scaled.resize(in.v.size());
    for (std::size_t i = 0; i < in.v.size(); ++i) {
      const double s = scale * static_cast<double>(in.v[i]);
      in.scaled[i] = std::isnan(s) ? kNaN : static_cast<float>(std::min(s, cap));
    }
    v = &in.scaled;
  }
  if (in.per_vertex) return hush::param_source::per_vertex({v->data(), v->size()});
  return hush::param_source::per_pixel({v->data(), width_, height_});
}

hush::npr_gabor::sources npr_fields::sources(double frequency_scale, double bandwidth_scale) {
  namespace c = hush::detail::constants;
  hush::npr_gabor::sources s;
  s.frequency = source(o_.frequency, frequency_, frequency_scale, c::kNprGaborMaxFrequency);
  s.bandwidth = source(o_.bandwidth, bandwidth_, bandwidth_scale, c::kNprGaborMaxBandwidth);
  s.impulses = source(o_.impulses, impulses_, 1.0, c::kGaborMaxImpulses);
  return s;
}

}  // namespace hush_cli
