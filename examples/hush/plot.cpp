// hush — the `hush` program: a log-log scatter plot as SVG text (see plot.hpp).
#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace hush_cli {
namespace {

// Layout in SVG user units (pixels).
constexpr double kWidth = 960, kHeight = 640;
constexpr double kLeft = 90, kRight = 230, kTop = 50, kBottom = 90;  // margins; legend right
constexpr double kMarker = 5;                                        // marker half-size
constexpr double kFontSize = 10;                                     // labels
constexpr double kCharWidth = 5.6;  // average glyph width at kFontSize, to size label boxes

std::string escape(const std::string& s) {
  std::string r;
  for (const char c : s) {
    switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      default:
        r += c;
    }
  }
  return r;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

// A decade range [10^lo, 10^hi] covering [min, max].
struct log_axis {
  int lo = 0, hi = 1;
  double pixel_lo = 0, pixel_hi = 1;  // where 10^lo and 10^hi map
  double map(double v) const {
    const double t = (std::log10(v) - lo) / (hi - lo);
    return pixel_lo + t * (pixel_hi - pixel_lo);
  }
};

log_axis make_axis(double min, double max, double pixel_lo, double pixel_hi) {
  log_axis a;
  a.lo = static_cast<int>(std::floor(std::log10(min)));
  a.hi = static_cast<int>(std::ceil(std::log10(max)));
  if (a.hi <= a.lo) a.hi = a.lo + 1;
  a.pixel_lo = pixel_lo;
  a.pixel_hi = pixel_hi;
  return a;
}

std::string decade_label(int e) {
  if (e >= 0 && e <= 3) return std::to_string(std::lround(std::pow(10.0, e)));
  return "1e" + std::to_string(e);
}

void draw_marker(std::ostringstream& os, const plot_series& s, double x, double y) {
  const std::string style = s.hollow
                                ? "fill=\"white\" stroke=\"" + s.colour + "\" stroke-width=\"1.5\""
                                : "fill=\"" + s.colour + "\" stroke=\"black\" stroke-width=\"0.5\"";
  const double r = kMarker;
  switch (s.shape) {
    case marker::circle:
      os << "<circle cx=\"" << num(x) << "\" cy=\"" << num(y) << "\" r=\"" << num(r) << "\" "
         << style << "/>\n";
      break;
    case marker::square:
      os << "<rect x=\"" << num(x - r) << "\" y=\"" << num(y - r) << "\" width=\"" << num(2 * r)
         << "\" height=\"" << num(2 * r) << "\" " << style << "/>\n";
      break;
    case marker::diamond:
      os << "<polygon points=\"" << num(x) << "," << num(y - 1.3 * r) << " " << num(x + 1.3 * r)
         << "," << num(y) << " " << num(x) << "," << num(y + 1.3 * r) << " " << num(x - 1.3 * r)
         << "," << num(y) << "\" " << style << "/>\n";
      break;
    case marker::triangle:
      os << "<polygon points=\"" << num(x) << "," << num(y - 1.3 * r) << " " << num(x + 1.2 * r)
         << "," << num(y + r) << " " << num(x - 1.2 * r) << "," << num(y + r) << "\" " << style
         << "/>\n";
      break;
  }
}

struct box {
  double x0, y0, x1, y1;
  bool overlaps(const box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

}  // namespace

std::string to_svg(const scatter_plot& plot) {
  // Data ranges over the drawable points.
  double x_min = std::numeric_limits<double>::infinity(), x_max = 0;
  double y_min = std::numeric_limits<double>::infinity(), y_max = 0;
  bool any_floor = false;
  for (const plot_point& p : plot.points) {
    if (!(std::isfinite(p.x) && p.x > 0)) continue;
    x_min = std::min(x_min, p.x);
    x_max = std::max(x_max, p.x);
    if (std::isfinite(p.y) && p.y > 0) {
      y_min = std::min(y_min, p.y);
      y_max = std::max(y_max, p.y);
    } else {
      any_floor = true;
    }
  }
  if (!(x_max > 0)) x_min = 1, x_max = 10;
  if (!(y_max > 0)) y_min = 1e-8, y_max = 1e-7;
  // The floor sits one decade below the smallest positive error.
  const double floor_y = std::pow(10.0, std::floor(std::log10(y_min)) - (any_floor ? 1 : 0));
  const log_axis ax = make_axis(x_min, x_max, kLeft, kWidth - kRight);
  const log_axis ay = make_axis(floor_y, y_max, kHeight - kBottom, kTop);

  std::ostringstream os;
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\"" << kHeight
     << "\" viewBox=\"0 0 " << kWidth << " " << kHeight << "\" font-family=\"sans-serif\">\n"
     << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
     << "<text x=\"" << num(kWidth / 2) << "\" y=\"24\" font-size=\"16\" text-anchor=\"middle\">"
     << escape(plot.title) << "</text>\n";

  // Grid lines and tick labels: decades, plus 2 and 5 on the x axis ("1" + "00" -> "200").
  const double px0 = ax.pixel_lo, px1 = ax.pixel_hi, py0 = ay.pixel_lo, py1 = ay.pixel_hi;
  for (int e = ax.lo; e <= ax.hi; ++e)
    for (const int m : {1, 2, 5}) {
      const double v = m * std::pow(10.0, e), x = ax.map(v);
      if (x > px1 + 0.5) break;
      os << "<line x1=\"" << num(x) << "\" y1=\"" << num(py0) << "\" x2=\"" << num(x) << "\" y2=\""
         << num(py1) << "\" stroke=\"" << (m == 1 ? "#bbb" : "#e4e4e4") << "\"/>\n"
         << "<text x=\"" << num(x) << "\" y=\"" << num(py0 + 16)
         << "\" font-size=\"11\" text-anchor=\"middle\">"
         << std::to_string(m) + decade_label(e).substr(1) << "</text>\n";
      if (e == ax.hi) break;
    }
  for (int e = ay.lo; e <= ay.hi; ++e) {
    const double y = ay.map(std::pow(10.0, e));
    os << "<line x1=\"" << num(px0) << "\" y1=\"" << num(y) << "\" x2=\"" << num(px1) << "\" y2=\""
       << num(y) << "\" stroke=\"#bbb\"/>\n"
       << "<text x=\"" << num(px0 - 6) << "\" y=\"" << num(y + 4)
       << "\" font-size=\"11\" text-anchor=\"end\">" << decade_label(e) << "</text>\n";
  }
  os << "<rect x=\"" << num(px0) << "\" y=\"" << num(py1) << "\" width=\"" << num(px1 - px0)
     << "\" height=\"" << num(py0 - py1) << "\" fill=\"none\" stroke=\"black\"/>\n"
     << "<text x=\"" << num((px0 + px1) / 2) << "\" y=\"" << num(py0 + 36)
     << "\" font-size=\"13\" text-anchor=\"middle\">" << escape(plot.x_label) << "</text>\n"
     << "<text transform=\"translate(24," << num((py0 + py1) / 2)
     << ") rotate(-90)\" font-size=\"13\" text-anchor=\"middle\">" << escape(plot.y_label)
     << "</text>\n";
  // Boxes of what is drawn so far that labels should not cover.
  std::vector<box> placed;
  if (any_floor) {
    const double y = ay.map(floor_y);
    placed.push_back({px0 + 6, y - 6 - kFontSize,
                      px0 + 6 + kCharWidth * 1.1 * static_cast<double>(plot.floor_note.size()),
                      y - 4});
    os << "<line x1=\"" << num(px0) << "\" y1=\"" << num(y) << "\" x2=\"" << num(px1) << "\" y2=\""
       << num(y) << "\" stroke=\"#888\" stroke-dasharray=\"6,4\"/>\n"
       << "<text x=\"" << num(px0 + 6) << "\" y=\"" << num(y - 6)
       << "\" font-size=\"11\" fill=\"#555\">" << escape(plot.floor_note) << "</text>\n";
  }

  // Points, then labels placed where they overlap neither a placed label nor the frame.
  const std::size_t first_marker = placed.size();
  for (const plot_point& p : plot.points) {
    if (!(std::isfinite(p.x) && p.x > 0) || p.series >= plot.series.size()) continue;
    const double x = ax.map(p.x);
    const double y = ay.map(std::isfinite(p.y) && p.y > 0 ? p.y : floor_y);
    draw_marker(os, plot.series[p.series], x, y);
    placed.push_back({x - kMarker, y - kMarker, x + kMarker, y + kMarker});
  }
  std::size_t marker_index = first_marker;
  for (const plot_point& p : plot.points) {
    if (!(std::isfinite(p.x) && p.x > 0) || p.series >= plot.series.size()) continue;
    const box self = placed[marker_index++];
    const double x = (self.x0 + self.x1) / 2, y = (self.y0 + self.y1) / 2;
    const double w = kCharWidth * static_cast<double>(p.label.size()), h = kFontSize + 2;
    // Candidates: right, left, above, below (next to the marker), then further out.
    const double d = kMarker + 3;
    const std::vector<std::pair<double, double>> offsets = {
        {d, h / 2 - 2},   {-d - w, h / 2 - 2}, {-w / 2, -d},     {-w / 2, d + h - 2},
        {d, -h + 2},      {d, h + 2},          {-d - w, -h + 2}, {-d - w, h + 2},
        {-w / 2, -d - h}, {-w / 2, d + 2 * h}, {d, -2 * h},      {d, 2 * h + 2}};
    std::size_t best = 0;
    for (std::size_t n = 0; n < offsets.size(); ++n) {
      const auto& o = offsets[n];
      const box b{x + o.first, y + o.second - h + 2, x + o.first + w, y + o.second + 2};
      const bool inside = b.x0 >= px0 && b.x1 <= px1 && b.y0 >= py1 && b.y1 <= py0;
      bool free = inside;
      for (const box& q : placed)
        if (free && b.overlaps(q) && !(q.x0 == self.x0 && q.y0 == self.y0)) free = false;
      if (free) {
        best = n;
        break;
      }
    }
    const double lx = x + offsets[best].first, ly = y + offsets[best].second;
    placed.push_back({lx, ly - h + 2, lx + w, ly + 2});
    if (best >= 4) {  // away from its point: a thin leader line to the label's nearer end
      const double ex = lx > x ? lx : lx + w, ey = ly - h / 2 + 2;
      os << "<line x1=\"" << num(x) << "\" y1=\"" << num(y) << "\" x2=\"" << num(ex) << "\" y2=\""
         << num(ey) << "\" stroke=\"#999\" stroke-width=\"0.6\"/>\n";
    }
    os << "<text x=\"" << num(lx) << "\" y=\"" << num(ly) << "\" font-size=\"" << kFontSize
       << "\" fill=\"#333\">" << escape(p.label) << "</text>\n";
  }

  // Legend, right of the frame.
  double ly = py1 + 10;
  const double lx = px1 + 24;
  for (const plot_series& s : plot.series) {
    draw_marker(os, s, lx, ly);
    os << "<text x=\"" << num(lx + 12) << "\" y=\"" << num(ly + 4) << "\" font-size=\"12\">"
       << escape(s.name) << "</text>\n";
    ly += 22;
  }
  os << "<text x=\"" << num(kLeft) << "\" y=\"" << num(kHeight - 16)
     << "\" font-size=\"10\" fill=\"#555\">" << escape(plot.footer) << "</text>\n"
     << "</svg>\n";
  return os.str();
}

}  // namespace hush_cli
