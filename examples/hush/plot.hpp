// hush — the `hush` program: a log-log scatter plot as SVG text (for `hush bench --plot`).
//
// Both axes are logarithmic and span whole decades around the data. A point whose y is not
// positive (an error of exactly 0) or not finite (an error that does not apply) is drawn on a
// dashed floor line one decade below the smallest positive y, which the plot's note explains.
// Labels are placed next to their point, avoiding labels already placed where possible.
#ifndef HUSH_CLI_PLOT_HPP
#define HUSH_CLI_PLOT_HPP

#include <string>
#include <vector>

namespace hush_cli {

enum class marker { circle, square, diamond, triangle };

struct plot_series {
  std::string name;    // in the legend
  std::string colour;  // an SVG colour, e.g. "#1f77b4"
  marker shape = marker::circle;
  bool hollow = false;  // outline only
};

struct plot_point {
  double x = 0;  // > 0 and finite, else the point is left out
  double y = 0;  // <= 0 or not finite: drawn on the floor line
  std::string label;
  std::size_t series = 0;  // index into scatter_plot::series
};

struct scatter_plot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::string floor_note;  // what a point on the floor line means
  std::string footer;      // one line under the plot, e.g. the machine and the command
  std::vector<plot_series> series;
  std::vector<plot_point> points;
};

// The plot as a standalone SVG document.
std::string to_svg(const scatter_plot& plot);

}  // namespace hush_cli

#endif  // HUSH_CLI_PLOT_HPP
