// hush — temporal-coherence metrics: every metric of a sequence, as a Markdown table or JSON.
#ifndef HUSH_COHERENCE_REPORT_HPP
#define HUSH_COHERENCE_REPORT_HPP

#include <string>
#include <vector>

#include "coherence/flatness.hpp"
#include "coherence/options.hpp"
#include "coherence/temporal.hpp"
#include "scene/gbuffer.hpp"

namespace hush_tools {
namespace coherence {

struct report {
  int frames = 0, width = 0, height = 0;
  options settings;
  temporal_metrics temporal;
  flatness_metrics flatness;
};

// measure_temporal and measure_flatness of one sequence (N >= 2; throws as they do).
report measure(const std::vector<noise_frame>& frames, const std::vector<scene::gbuffer>& gbuffers,
               const options& o = {});

// A Markdown table: one row per metric with its value and its ideal value, then the
// exclusion counts and the reasons for any NaN. Numbers with 6 significant digits.
std::string to_markdown(const report& r);
// The same numbers as one JSON object (NaN and infinities as null), including per-pair
// coherence and per-frame flatness; full double precision.
std::string to_json(const report& r);

}  // namespace coherence
}  // namespace hush_tools

#endif  // HUSH_COHERENCE_REPORT_HPP
