// hush — the `hush` program: its commands (DESIGN.md, "The `hush` program").
//
// Each command receives the arguments after its name and returns the exit code. Mistakes
// are thrown: usage_error (exit 2) or run_error (exit 1); main prints them as one line.
#ifndef HUSH_CLI_COMMANDS_HPP
#define HUSH_CLI_COMMANDS_HPP

#include <string>
#include <vector>

#include "args.hpp"

namespace hush_cli {

// hush info: version, compiler, build options, backends and optional features.
int run_info(const std::vector<std::string>& args);

// hush sample NOISE [options] --out FILE.npy|FILE.png: a noise sampled on a grid.
int run_sample(const std::vector<std::string>& args);
// The options every noise takes (the noise's own come from its noise_entry).
const std::vector<option_spec>& sample_options();

// hush gallery [--out DIR]: the showcase PNG images.
int run_gallery(const std::vector<std::string>& args);
const std::vector<option_spec>& gallery_options();

// hush coherence --frames DIR --gbuffer DIR [--json FILE]: temporal-coherence metrics;
// hush coherence baseline --kind K --gbuffer DIR --out DIR: calibration baselines.
int run_coherence(const std::vector<std::string>& args);
const std::vector<option_spec>& coherence_options();
const std::vector<option_spec>& coherence_baseline_options();
// hush glsl-export DIR: the generated GLSL library and compute runners.
int run_glsl_export(const std::vector<std::string>& args);
// The GLSL backend's line in `hush info`: the GL renderer and version of an
// OSMesa context, or "unavailable: <reason>".
std::string glsl_status();
// hush bench [--quick] [--interleave] [--json FILE] [--markdown FILE] [--plot FILE.svg]: speed
// vs error.
int run_bench(const std::vector<std::string>& args);
const std::vector<option_spec>& bench_options();
// hush render NOISE --gbuffer DIR --out DIR [options]: scene-driven noises over G-buffers.
int run_render_noise(const std::vector<std::string>& args);
const std::vector<option_spec>& render_options();
// hush scene list | hush scene render --scene NAME ... --out DIR: test-scene G-buffers.
int run_scene(const std::vector<std::string>& args);
const std::vector<option_spec>& scene_options();

}  // namespace hush_cli

#endif  // HUSH_CLI_COMMANDS_HPP
