#include "tool/pareto_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "tool/report_files.hpp"

namespace softstep::tool {

namespace {

constexpr double kWidth = 900, kHeight = 620;
constexpr double kLeft = 100, kRight = 40, kTop = 70, kBottom = 80;

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

// "0.01", "1", "100", or "1e-05" for a decade 10^k.
std::string decade_label(int k) {
  char b[32];
  if (k >= -3 && k <= 4) {
    std::snprintf(b, sizeof b, "%g", std::pow(10.0, k));
  } else {
    std::snprintf(b, sizeof b, "1e%d", k);
  }
  return b;
}

// A log axis over whole decades that holds [lo, hi] with a fifth of a decade to spare, so
// that no point sits on the frame with its label over the axis.
struct LogAxis {
  int first, last;
  LogAxis(double lo, double hi)
      : first(static_cast<int>(std::floor(std::log10(lo) - 0.2))),
        last(std::max(first + 1, static_cast<int>(std::ceil(std::log10(hi) + 0.2)))) {}
  double fraction(double v) const { return (std::log10(v) - first) / (last - first); }
};

}  // namespace

std::string pareto_svg(const std::vector<CostPoint>& points, const std::vector<bool>& front,
                       const std::vector<std::string>& labels, const ChartText& text) {
  std::vector<std::size_t> shown;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (std::isfinite(points[i].error) && points[i].error > 0.0 && points[i].ms > 0.0)
      shown.push_back(i);
  }
  const auto range = [&](auto value) {
    double lo = 1e300, hi = 0.0;
    for (std::size_t i : shown) {
      lo = std::min(lo, value(points[i]));
      hi = std::max(hi, value(points[i]));
    }
    return shown.empty() ? std::pair{1.0, 10.0} : std::pair{lo, hi};
  };
  const auto [x_lo, x_hi] = range([](const CostPoint& p) { return p.ms; });
  const auto [y_lo, y_hi] = range([](const CostPoint& p) { return p.error; });
  const LogAxis xa(x_lo, x_hi), ya(y_lo, y_hi);
  const double pw = kWidth - kLeft - kRight, ph = kHeight - kTop - kBottom;
  const auto px = [&](double v) { return kLeft + xa.fraction(v) * pw; };
  const auto py = [&](double v) { return kTop + (1.0 - ya.fraction(v)) * ph; };

  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(kWidth) +
                  "\" height=\"" + num(kHeight) +
                  "\" font-family=\"sans-serif\" font-size=\"13\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<text x=\"" + num(kWidth / 2) + "\" y=\"28\" text-anchor=\"middle\" font-size=\"16\">" +
       markup_text(text.title) + "</text>\n";
  // Decade grid and tick labels.
  for (int k = xa.first; k <= xa.last; ++k) {
    const double x = px(std::pow(10.0, k));
    s += "<line x1=\"" + num(x) + "\" y1=\"" + num(kTop) + "\" x2=\"" + num(x) + "\" y2=\"" +
         num(kTop + ph) + "\" stroke=\"#ddd\"/>\n";
    s += "<text x=\"" + num(x) + "\" y=\"" + num(kTop + ph + 20) + "\" text-anchor=\"middle\">" +
         decade_label(k) + "</text>\n";
  }
  for (int k = ya.first; k <= ya.last; ++k) {
    const double y = py(std::pow(10.0, k));
    s += "<line x1=\"" + num(kLeft) + "\" y1=\"" + num(y) + "\" x2=\"" + num(kLeft + pw) +
         "\" y2=\"" + num(y) + "\" stroke=\"#ddd\"/>\n";
    s += "<text x=\"" + num(kLeft - 8) + "\" y=\"" + num(y + 4) + "\" text-anchor=\"end\">" +
         decade_label(k) + "</text>\n";
  }
  s += "<rect x=\"" + num(kLeft) + "\" y=\"" + num(kTop) + "\" width=\"" + num(pw) +
       "\" height=\"" + num(ph) + "\" fill=\"none\" stroke=\"black\"/>\n";
  s += "<text x=\"" + num(kLeft + pw / 2) + "\" y=\"" + num(kHeight - 30) +
       "\" text-anchor=\"middle\">" + markup_text(text.x_axis) + "</text>\n";
  s += "<text transform=\"translate(24 " + num(kTop + ph / 2) +
       ") rotate(-90)\" text-anchor=\"middle\">" + markup_text(text.y_axis) + "</text>\n";
  // Every setting, then the front as a line through its points, fastest first.
  for (std::size_t i : shown) {
    s += "<circle cx=\"" + num(px(points[i].ms)) + "\" cy=\"" + num(py(points[i].error)) +
         "\" r=\"4\" fill=\"" + (front[i] ? "#d62728" : "#1f77b4") + "\" fill-opacity=\"0.7\"/>\n";
  }
  std::vector<std::size_t> on_front;
  for (std::size_t i : shown) {
    if (front[i]) on_front.push_back(i);
  }
  std::sort(on_front.begin(), on_front.end(),
            [&](std::size_t a, std::size_t b) { return points[a].ms < points[b].ms; });
  if (!on_front.empty()) {
    s += "<polyline fill=\"none\" stroke=\"#d62728\" stroke-width=\"1.5\" points=\"";
    for (std::size_t i : on_front)
      s += num(px(points[i].ms)) + "," + num(py(points[i].error)) + " ";
    s += "\"/>\n";
    // Neighbours on the front are labelled on alternate sides (above right, below left), so
    // that close points do not write over each other.
    for (std::size_t k = 0; k < on_front.size(); ++k) {
      const std::size_t i = on_front[k];
      const bool above = k % 2 == 0;
      s += "<text x=\"" + num(px(points[i].ms) + (above ? 7 : -7)) + "\" y=\"" +
           num(py(points[i].error) + (above ? -7 : 16)) + "\" text-anchor=\"" +
           (above ? "start" : "end") + "\" font-size=\"11\" fill=\"#d62728\">" + markup_text(labels[i]) +
           "</text>\n";
    }
  }
  // Legend.
  const double lx = kLeft + 6, ly = kTop - 16, lx2 = lx + 110;
  s += "<circle cx=\"" + num(lx) + "\" cy=\"" + num(ly) + "\" r=\"4\" fill=\"#1f77b4\"/>";
  s += "<text x=\"" + num(lx + 10) + "\" y=\"" + num(ly + 4) + "\">a setting</text>\n";
  s += "<line x1=\"" + num(lx2 - 8) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(lx2 + 8) +
       "\" y2=\"" + num(ly) + "\" stroke=\"#d62728\" stroke-width=\"1.5\"/>";
  s += "<circle cx=\"" + num(lx2) + "\" cy=\"" + num(ly) + "\" r=\"4\" fill=\"#d62728\"/>";
  s += "<text x=\"" + num(lx2 + 14) + "\" y=\"" + num(ly + 4) +
       "\">Pareto front (nothing is both faster and more accurate)</text>\n";
  const std::size_t hidden = points.size() - shown.size();
  if (hidden > 0) {
    s += "<text x=\"" + num(kLeft + 8) + "\" y=\"" + num(kTop + ph - 10) + "\">" +
         std::to_string(hidden) + " setting(s) not drawn: blew up (error not finite)</text>\n";
  }
  s += "</svg>\n";
  return s;
}

}  // namespace softstep::tool
