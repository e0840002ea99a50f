// hush — temporal-coherence metrics: measurement and formatting (see report.hpp).
#include "coherence/report.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace hush_tools {
namespace coherence {
namespace {

std::string fixed4(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
      continue;
    }
    out += c;
  }
  return out + "\"";
}

}  // namespace

report measure(const std::vector<noise_frame>& frames, const std::vector<scene::gbuffer>& gbuffers,
               const options& o) {
  report r;
  r.temporal = measure_temporal(frames, gbuffers, o);  // validates everything first
  r.flatness = measure_flatness(frames, gbuffers, o);
  r.frames = static_cast<int>(frames.size());
  r.width = gbuffers[0].width;
  r.height = gbuffers[0].height;
  r.settings = o;
  return r;
}

std::string to_markdown(const report& r) {
  const temporal_metrics& t = r.temporal;
  const flatness_metrics& f = r.flatness;
  std::size_t compared = 0, offscreen = 0, disoccluded = 0, covered = 0;
  for (const pair_metrics& p : t.pairs) {
    compared += p.compared;
    offscreen += p.offscreen;
    disoccluded += p.disoccluded;
    covered += p.covered;
  }
  std::ostringstream os;
  os << "| metric | value | ideal |\n|---|---|---|\n";
  auto row = [&os](const char* name, double v, const char* ideal) {
    os << "| " << name << " | " << fixed4(v) << " | " << ideal << " |\n";
  };
  row("motion coherence (mean)", t.coherence_mean, "1");
  row("motion coherence (min)", t.coherence_min, "1");
  row("screen coherence, no compensation (mean)", t.screen_coherence_mean, "< coherence");
  row("motion following (mean)", t.following_mean, "1");
  row("change mean abs (sigma)", t.change_mean, "0");
  row("change p50 (sigma)", t.change_p50, "0");
  row("change p95 (sigma)", t.change_p95, "0");
  row("change p99 (sigma)", t.change_p99, "0");
  row("change p99.9 (sigma)", t.change_p999, "0");
  row("popping (fraction)", t.popping, "0");
  row("flatness frequency CV", f.frequency_cv, "0");
  row("flatness frequency max/min", f.frequency_ratio, "1");
  row("flatness variance CV", f.variance_cv, "0");
  row("flatness variance max/min", f.variance_ratio, "1");
  row("flatness frequency CV, all frames pooled", f.pooled_frequency_cv, "0");
  row("flatness variance CV, all frames pooled", f.pooled_variance_cv, "0");
  os << "\n"
     << r.frames << " frames of " << r.width << "x" << r.height << "; pixel pairs: " << compared
     << " compared of " << covered << " covered (" << offscreen << " off-screen, " << disoccluded
     << " disoccluded); flatness: " << (f.frames.size() - f.frames_without_value) << " of "
     << f.frames.size() << " frames measured.\n";
  for (const pair_metrics& p : t.pairs)
    if (!p.reason.empty()) os << "- frame " << p.frame << ": no coherence: " << p.reason << "\n";
  for (const flatness_frame& ff : f.frames)
    if (!ff.reason.empty()) os << "- frame " << ff.frame << ": no flatness: " << ff.reason << "\n";
  return os.str();
}

std::string to_json(const report& r) {
  const temporal_metrics& t = r.temporal;
  const flatness_metrics& f = r.flatness;
  std::ostringstream os;
  os << "{\n  \"frames\": " << r.frames << ", \"width\": " << r.width
     << ", \"height\": " << r.height << ",\n";
  const options& o = r.settings;
  os << "  \"options\": {\"depth_epsilon\": " << json_number(o.depth_epsilon)
     << ", \"min_pixels\": " << o.min_pixels
     << ", \"popping_threshold\": " << json_number(o.popping_threshold)
     << ", \"window\": " << o.window << ", \"window_stride\": " << o.window_stride
     << ", \"depth_bins\": " << o.depth_bins << ", \"min_windows\": " << o.min_windows << "},\n";
  os << "  \"motion_coherence\": {\"mean\": " << json_number(t.coherence_mean)
     << ", \"min\": " << json_number(t.coherence_min)
     << ", \"screen_mean\": " << json_number(t.screen_coherence_mean)
     << ", \"following_mean\": " << json_number(t.following_mean)
     << ", \"pairs_without_value\": " << t.pairs_without_coherence
     << ", \"pairs_without_following\": " << t.pairs_without_following << "},\n";
  os << "  \"continuity\": {\"changes\": " << t.changes
     << ", \"mean_abs\": " << json_number(t.change_mean)
     << ", \"p50\": " << json_number(t.change_p50) << ", \"p95\": " << json_number(t.change_p95)
     << ", \"p99\": " << json_number(t.change_p99) << ", \"p99_9\": " << json_number(t.change_p999)
     << ", \"popping\": " << json_number(t.popping)
     << ", \"popping_candidates\": " << t.popping_candidates << "},\n";
  os << "  \"flatness\": {\"frequency_cv\": " << json_number(f.frequency_cv)
     << ", \"frequency_ratio\": " << json_number(f.frequency_ratio)
     << ", \"variance_cv\": " << json_number(f.variance_cv)
     << ", \"variance_ratio\": " << json_number(f.variance_ratio)
     << ", \"frequency_cv_max\": " << json_number(f.frequency_cv_max)
     << ", \"variance_cv_max\": " << json_number(f.variance_cv_max)
     << ", \"pooled_frequency_cv\": " << json_number(f.pooled_frequency_cv)
     << ", \"pooled_frequency_ratio\": " << json_number(f.pooled_frequency_ratio)
     << ", \"pooled_variance_cv\": " << json_number(f.pooled_variance_cv)
     << ", \"pooled_variance_ratio\": " << json_number(f.pooled_variance_ratio)
     << ", \"frames_without_value\": " << f.frames_without_value << "},\n";
  os << "  \"pairs\": [";
  for (std::size_t i = 0; i < t.pairs.size(); ++i) {
    const pair_metrics& p = t.pairs[i];
    os << (i ? ",\n    " : "\n    ") << "{\"frame\": " << p.frame
       << ", \"coherence\": " << json_number(p.coherence)
       << ", \"screen_coherence\": " << json_number(p.screen_coherence)
       << ", \"following\": " << json_number(p.following) << ", \"covered\": " << p.covered
       << ", \"compared\": " << p.compared << ", \"offscreen\": " << p.offscreen
       << ", \"disoccluded\": " << p.disoccluded << ", \"sigma\": " << json_number(p.sigma)
       << ", \"reason\": " << json_string(p.reason) << "}";
  }
  os << "],\n  \"flatness_frames\": [";
  for (std::size_t i = 0; i < f.frames.size(); ++i) {
    const flatness_frame& ff = f.frames[i];
    os << (i ? ",\n    " : "\n    ") << "{\"frame\": " << ff.frame
       << ", \"windows\": " << ff.windows << ", \"regions\": " << ff.regions.size()
       << ", \"dropped_objects\": " << ff.dropped_objects
       << ", \"frequency_cv\": " << json_number(ff.frequency_cv)
       << ", \"variance_cv\": " << json_number(ff.variance_cv)
       << ", \"reason\": " << json_string(ff.reason) << "}";
  }
  os << "]\n}\n";
  return os.str();
}

}  // namespace coherence
}  // namespace hush_tools
