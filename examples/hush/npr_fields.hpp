// hush — the `hush` program: per-pixel and per-vertex fields for NPR Gabor noise's frequency
// F0, bandwidth a and density N' (`hush render npr-gabor --frequency-field SPEC`,
// `--bandwidth-field SPEC`, `--impulses-field SPEC`), handed to the library as
// hush::npr_gabor::sources (include/hush/core/param_source.hpp).
//
// SPEC is one of
//  - shading:LO,HI  per pixel, LO where the shading tone is 0 (dark) ... HI where it is 1 (lit),
//                   linear in the tone ambient + (1 - ambient) max(0, N.L) of the G-buffer's
//                   normals (the styles' tone: --light, --ambient); the paper's "frequency
//                   driven by shading" (Benard et al. 2010, sec. 4);
//  - depth:LO,HI    per pixel, LO at depth z0 ... HI at depth z1, linear in the G-buffer's
//                   linear depth and clamped to [LO, HI] outside; [z0, z1] is
//                   --field-depth-range, by default the covered depth range of frame 0, fixed
//                   for the whole sequence (a range measured per frame would rescale the
//                   field whenever the visible depths change); an empty range (frame 0 shows
//                   no surface, or one depth) gives LO everywhere;
//  - file:NAME      DIR/frame_NNNN/NAME.npy of every frame: float32, shape (H, W) per pixel or
//                   (V,) one value per vertex of that frame's tri_screen.npy (per vertex: the
//                   value moves with the surface). Values are not checked: the library takes
//                   the --frequency / ... constant where one is NaN or infinite and clamps the
//                   others to the parameter's range.
// LO and HI must lie in the parameter's range (the constant option's range; N' may be 0 in a
// field: no points there). The background (object 0) takes the constant.
#ifndef HUSH_CLI_NPR_FIELDS_HPP
#define HUSH_CLI_NPR_FIELDS_HPP

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "args.hpp"
#include "hush/core/frame.hpp"
#include "hush/core/triangles.hpp"
#include "hush/core/vec.hpp"
#include "hush/core/views.hpp"
#include "hush/npr_gabor.hpp"

namespace hush_cli {

// One parameter's field as given on the command line.
struct npr_param_field {
  enum class kind { constant, shading, depth, file };
  kind from = kind::constant;
  double lo = 0, hi = 0;  // shading: at tone 0 and 1; depth: at z0 and z1
  std::string file;       // file: NAME (DIR/frame_NNNN/NAME.npy)
  std::string option;     // "--frequency-field", for messages
};

// Parses SPEC given to `option` for a parameter whose values lie in [min, max] (`valid` phrases
// that range). Throws usage_error naming the option, the token and the valid forms.
npr_param_field parse_npr_field(const std::string& option, const std::string& spec, double min,
                                double max, const std::string& valid);

struct npr_field_options {
  npr_param_field frequency, bandwidth, impulses;
  bool depth_range_given = false;  // --field-depth-range z0,z1 (else frame 0's covered range)
  double z0 = 0, z1 = 0;
  double ambient = 0.15;             // the shading tone's (the styles' --ambient, --light)
  hush::dvec3 light{0.4, 0.7, 0.6};
  bool any() const;
  bool uses(npr_param_field::kind k) const;
};

// A file of a frame directory: its shape and float32 values (C order).
struct field_file {
  std::vector<std::size_t> shape;
  std::vector<float> values;
};
// Loads NAME.npy of the current frame's directory; throws usage_error / run_error naming the
// file when it is missing or not float32.
using field_loader = std::function<field_file(const std::string& name)>;

class npr_fields {
 public:
  explicit npr_fields(npr_field_options o) : o_(std::move(o)) {}
  bool any() const { return o_.any(); }
  // Computes or loads the fields of one frame (call before sources()). Throws usage_error
  // naming the option when a file has neither shape (H, W) nor (V,).
  void update(const hush::frame& f, const hush::triangle_list& t,
              hush::image_view<const hush::vec3> normals, const field_loader& load);
  // The sources of this frame's fields (constant where no field is given), valid until the
  // next update(); F0 and a multiplied by `frequency_scale` and `bandwidth_scale` and capped at
  // their maxima (graphite's fine layer: 3 F0, 3 a), NaN kept.
  hush::npr_gabor::sources sources(double frequency_scale = 1, double bandwidth_scale = 1);

 private:
  struct values {
    bool per_vertex = false;
    std::vector<float> v, scaled;
  };
  void fill(const npr_param_field& p, values& out, const hush::frame& f,
            const hush::triangle_list& t, const field_loader& load);
  hush::param_source source(const npr_param_field& p, values& in, double scale, double cap) const;

  npr_field_options o_;
  bool range_known_ = false;
  std::size_t width_ = 0, height_ = 0;
  std::vector<float> tone_;
  values frequency_, bandwidth_, impulses_;
};

}  // namespace hush_cli

#endif  // HUSH_CLI_NPR_FIELDS_HPP
