// hush — the `hush` program: usage text and command dispatch.
//
//   hush info
//   hush sample NOISE [--dim 2|3] [--size N|NxM|NxMxK] [--origin x,y[,z]] [--step s]
//                     [--region x0,y0[,z0]:nx,ny[,nz]] [--seed n]
//                     [--backend scalar|simd|glsl] [NOISE OPTIONS] --out FILE
//   hush gallery [--out DIR]
//   hush glsl-export DIR
//   hush bench [--quick] [--interleave] [--json FILE] [--markdown FILE] [--plot FILE.svg]
//   hush scene list | hush scene render --scene NAME [--frames N] [--size WxH]
//                                       [--backend cpu|gl] --out DIR
//   hush render NOISE --gbuffer DIR --out DIR [--frames N] [--seed n]
//                     [--backend scalar|simd|glsl] [NOISE OPTIONS]
//
// Exit codes: 0 success, 1 a failure doing valid work (e.g. an unwritable file), 2 a
// usage error. Every error is one line on stderr: "hush <command>: <what is wrong>".
#include <cstdio>
#include <iostream>
#include <new>
#include <ostream>
#include <string>
#include <vector>

#include "args.hpp"
#include "commands.hpp"
#include "hush/core/error.hpp"
#include "noises.hpp"
#include "scene_noises.hpp"

namespace hush_cli {
namespace {

struct command {
  const char* name;
  const char* synopsis;
  const char* summary;
  int (*run)(const std::vector<std::string>& args);
};

const std::vector<command>& commands() {
  static const std::vector<command> table = {
      {"info", "hush info", "version, compiler, build options, backends", run_info},
      {"sample", "hush sample NOISE [options] --out FILE.npy|FILE.png",
       "sample a noise on a uniform grid", run_sample},
      {"gallery", "hush gallery [--out DIR]", "render the showcase images (PNG)", run_gallery},
      {"coherence", "hush coherence --frames DIR --gbuffer DIR [--json FILE]",
       "temporal-coherence metrics of noise frames (docs/coherence.md)", run_coherence},
      {"glsl-export", "hush glsl-export DIR", "write the generated GLSL library and runners",
       run_glsl_export},
      {"bench",
       "hush bench [--quick] [--interleave] [--json FILE] [--markdown FILE] [--plot FILE.svg]",
       "speed-vs-error table of every noise and backend", run_bench},
      {"scene", "hush scene list | render --scene NAME [options] --out DIR",
       "render test scenes to G-buffer files (.npy per channel)", run_scene},
      {"render", "hush render NOISE --gbuffer DIR --out DIR [options]",
       "scene-driven noises over a G-buffer sequence (coherent)", run_render_noise},
  };
  return table;
}

// "  --name metavar   help", the help wrapped under its own column; an option too long
// for the first column gets its help on the next line.
void print_options(std::ostream& os, const std::vector<option_spec>& options) {
  constexpr std::size_t kHelpColumn = 30, kWidth = 96;
  for (const option_spec& o : options) {
    std::string line = std::string("  ") + o.name + " " + o.metavar;
    if (line.size() + 2 > kHelpColumn) {
      os << line << '\n';
      line.clear();
    }
    line.resize(kHelpColumn, ' ');
    for (const std::string& word : split(o.help, ' ')) {
      if (line.size() > kHelpColumn && line.size() + 1 + word.size() > kWidth) {
        os << line << '\n';
        line.assign(kHelpColumn, ' ');
      }
      if (line.size() > kHelpColumn) line += ' ';
      line += word;
    }
    os << line << '\n';
  }
}

// One command's part of the usage text; `noise` (sample, render) keeps only that noise's
// options when it names one of the command's noises (empty or unknown: all of them).
void print_sample_help(std::ostream& os, const std::string& noise) {
  os << "\nhush sample NOISE [options] --out FILE.npy|FILE.png\n"
        "  Sample (i, j, k) is at origin + step * (i, j, k), i along x. FILE.npy holds float32\n"
        "  (little-endian, C order) of shape (ny, nx) or (nz, ny, nx); FILE.png (one 2D image)\n"
        "  maps --range lo,hi to black..white (values outside clip), j = 0 at the top; the\n"
        "  default range is per noise (below). With --region, the file holds that block of the\n"
        "  grid only, bit for bit as in the whole grid's file.\n";
  print_options(os, sample_options());
  bool known = false;
  for (const noise_entry& n : noise_table()) known = known || noise == n.name;
  for (const noise_entry& n : noise_table()) {
    if (known && noise != n.name) continue;
    os << "  NOISE " << n.name << ": " << n.summary << '\n';
    print_options(os, n.options);
  }
}
void print_render_help(std::ostream& os, const std::string& noise) {
  os << "\nhush render NOISE --gbuffer DIR --out DIR [options]\n"
        "  Writes OUT/NNNN.npy (float32 (H, W), or (H, W, C) for C channels) for the G-buffer\n"
        "  frames DIR/frame_NNNN/ of hush scene render, reading one frame at a time.\n";
  print_options(os, render_options());
  bool known = false;
  for (const render_entry& n : render_table()) known = known || noise == n.name;
  for (const render_entry& n : render_table()) {
    if (known && noise != n.name) continue;
    os << "  NOISE " << n.name << ": " << n.summary << '\n';
    print_options(os, n.options);
    print_options(os, n.flags);
  }
}
void print_coherence_help(std::ostream& os, const std::string&) {
  os << "\nhush coherence --frames DIR --gbuffer DIR [--json FILE] [options]\n"
        "  Motion coherence, temporal continuity and flatness of the noise frames DIR/NNNN.npy\n"
        "  (float32 (H, W)) over the G-buffers DIR/frame_NNNN/ (docs/coherence.md).\n";
  print_options(os, coherence_options());
  os << "\nhush coherence baseline --kind K --gbuffer DIR --out DIR [options]\n"
        "  Writes a calibration baseline's noise frames OUT/NNNN.npy for the G-buffers.\n";
  print_options(os, coherence_baseline_options());
}
void print_info_help(std::ostream& os, const std::string&) { os << "\nhush info\n"; }
void print_gallery_help(std::ostream& os, const std::string&) {
  os << "\nhush gallery [--out DIR]\n";
  print_options(os, gallery_options());
}
void print_glsl_export_help(std::ostream& os, const std::string&) {
  os << "\nhush glsl-export DIR\n"
        "  Writes hush_noise.glsl (the function library, no #version line), the compute\n"
        "  runners of every GLSL noise (hush_NOISE_points|grid|samples[_gradient].comp) and\n"
        "  coherent and NPR Gabor noise's shaders into DIR, created if needed.\n";
}
void print_bench_help(std::ostream& os, const std::string&) {
  os << "\nhush bench [--quick] [--interleave] [--json FILE] [--markdown FILE] [--plot FILE.svg]\n"
        "  Times every noise x backend x workload (ns/sample, median of repetitions, one\n"
        "  thread) next to its error against the double reference; Markdown on stdout.\n";
  print_options(os, bench_options());
}
void print_scene_help(std::ostream& os, const std::string&) {
  os << "\nhush scene list\n"
        "hush scene render --scene NAME [--frames N] [--size WxH] [--backend cpu|gl] --out DIR\n"
        "  Writes DIR/frame_NNNN/<channel>.npy (float32 or uint32, shape (H, W) or (H, W, C),\n"
        "  row 0 at the top; examples/scene/gbuffer.hpp) and preview PNGs for frames 0 ... N-1.\n";
  print_options(os, scene_options());
}

// Each command's help, in the order of the full usage text.
struct command_help {
  const char* name;
  void (*print)(std::ostream& os, const std::string& noise);
};
const std::vector<command_help>& command_helps() {
  static const std::vector<command_help> table = {
      {"info", print_info_help},           {"sample", print_sample_help},
      {"gallery", print_gallery_help},     {"coherence", print_coherence_help},
      {"glsl-export", print_glsl_export_help}, {"bench", print_bench_help},
      {"scene", print_scene_help},         {"render", print_render_help},
  };
  return table;
}

void print_footer(std::ostream& os) {
  os << "\nEvery option takes one value: '--seed 7' or '--seed=7' (bench --quick and\n"
        "--interleave are the flags, which take none).\n"
        "Exit codes: 0 success, 1 failure (e.g. unwritable output), 2 usage error.\n";
}

void print_usage(std::ostream& os) {
  os << "usage: hush <command> [options]      (hush --help shows this; hush COMMAND --help\n"
        "                                      that command's part)\n\ncommands:\n";
  for (const command& c : commands())
    os << "  " << c.name << std::string(13 - std::string(c.name).size(), ' ') << c.summary << '\n';
  for (const command_help& h : command_helps()) h.print(os, "");
  print_footer(os);
}

// `hush CMD [NOISE] --help`: that command's part (sample and render: only NOISE's options
// when NOISE is given); false when CMD is not a command.
bool print_command_usage(std::ostream& os, const std::vector<std::string>& args) {
  for (const command_help& h : command_helps()) {
    if (args[0] != h.name) continue;
    const std::string noise = args.size() > 1 && args[1].rfind('-', 0) != 0 ? args[1] : "";
    h.print(os, noise);
    print_footer(os);
    return true;
  }
  return false;
}

bool asks_for_help(const std::vector<std::string>& args) {
  for (const std::string& a : args)
    if (a == "--help" || a == "-h") return true;
  return false;
}

int run(const std::vector<std::string>& args) {
  if (args.empty()) {
    print_usage(std::cerr);
    return 2;
  }
  if (args[0] == "help" || asks_for_help(args)) {
    if (args[0] == "help" || !print_command_usage(std::cout, args)) print_usage(std::cout);
    return 0;
  }
  std::string names;
  for (const command& c : commands()) {
    if (args[0] != c.name) {
      names += (names.empty() ? "" : ", ") + std::string(c.name);
      continue;
    }
    const std::string who = std::string("hush ") + c.name + ": ";
    try {
      return c.run(std::vector<std::string>(args.begin() + 1, args.end()));
    } catch (const usage_error& e) {
      std::cerr << who << e.what() << '\n';
      return 2;
    } catch (const hush::invalid_argument& e) {  // a parameter no option check caught
      std::cerr << who << e.what() << '\n';
      return 2;
    } catch (const run_error& e) {
      std::cerr << who << e.what() << '\n';
      return 1;
    } catch (const std::bad_alloc&) {
      std::cerr << who << "out of memory\n";
      return 1;
    } catch (const std::exception& e) {
      std::cerr << who << e.what() << '\n';
      return 1;
    }
  }
  std::cerr << "hush: unknown command '" << args[0] << "'; valid: " << names
            << " (hush --help shows usage)\n";
  return 2;
}

}  // namespace
}  // namespace hush_cli

int main(int argc, char** argv) {
  return hush_cli::run(std::vector<std::string>(argv + 1, argv + argc));
}
